#include "sensor/spectra/spectrum.h"

#include <algorithm>
#include <cmath>

#include "sensor/base/check.h"

namespace camsim {

Spectrum Spectrum::constant(double value) {
  Spectrum s;
  s.values_.fill(static_cast<float>(value));
  return s;
}

Spectrum Spectrum::blackbody(double kelvin) {
  CAMSIM_CHECK(kelvin > 0.0);
  constexpr double h = 6.62607015e-34;  // J·s
  constexpr double c = 299792458.0;     // m/s
  constexpr double kB = 1.380649e-23;   // J/K
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const double lambda = (kLambdaMinNm + i) * 1e-9;  // m
    const double radiancePerMetre =
        2.0 * h * c * c / (std::pow(lambda, 5) * std::expm1(h * c / (lambda * kB * kelvin)));
    s.values_[i] = static_cast<float>(radiancePerMetre * 1e-9);  // per nm
  }
  return s;
}

Spectrum Spectrum::fromSamples(std::span<const double> lambdaNm, std::span<const double> values,
                               Extrapolation outside) {
  CAMSIM_CHECK(lambdaNm.size() == values.size() && !lambdaNm.empty());
  Spectrum s;
  const size_t n = lambdaNm.size();
  size_t j = 0;
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const double lambda = kLambdaMinNm + i;
    double v;
    if (lambda < lambdaNm.front()) {
      v = outside == Extrapolation::kClamp ? values.front() : 0.0;
    } else if (lambda > lambdaNm.back()) {
      v = outside == Extrapolation::kClamp ? values.back() : 0.0;
    } else if (n == 1) {
      v = values.front();
    } else {
      while (j + 2 < n && lambdaNm[j + 1] < lambda) ++j;
      const double t = (lambda - lambdaNm[j]) / (lambdaNm[j + 1] - lambdaNm[j]);
      v = values[j] + std::clamp(t, 0.0, 1.0) * (values[j + 1] - values[j]);
    }
    s.values_[i] = static_cast<float>(v);
  }
  return s;
}

Spectrum& Spectrum::operator*=(double s) {
  for (float& v : values_) v = static_cast<float>(static_cast<double>(v) * s);
  return *this;
}

Spectrum& Spectrum::operator*=(const Spectrum& s) {
  for (int i = 0; i < kSpectrumSamples; ++i) values_[i] *= s.values_[i];
  return *this;
}

double Spectrum::maxValue() const {
  return static_cast<double>(*std::max_element(values_.begin(), values_.end()));
}
double Spectrum::minValue() const {
  return static_cast<double>(*std::min_element(values_.begin(), values_.end()));
}

double Spectrum::sum() const {
  double total = 0.0;
  for (float v : values_) total += static_cast<double>(v);
  return total;
}

double innerProduct(const Spectrum& a, const Spectrum& b) {
  double total = 0.0;
  for (int i = 0; i < kSpectrumSamples; ++i)
    total += static_cast<double>(a.sample(i)) * static_cast<double>(b.sample(i));
  return total;
}

}  // namespace camsim
