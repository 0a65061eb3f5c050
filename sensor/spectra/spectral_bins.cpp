#include "sensor/spectra/spectral_bins.h"

#include <algorithm>
#include <cmath>

namespace camsim {
namespace {

// A spectrum's piecewise-linear value at λ in [360, 830] nm, in double.
double valueAt(const Spectrum& s, double lambdaNm) {
  const double x = std::clamp(lambdaNm - kLambdaMinNm, 0.0, double(kSpectrumSamples - 1));
  const int i = std::min(static_cast<int>(x), kSpectrumSamples - 2);
  const double t = x - i;
  const double a = static_cast<double>(s.sample(i)), b = static_cast<double>(s.sample(i + 1));
  return a + t * (b - a);
}

}  // namespace

double binEdgeNm(int b) {
  if (b <= 0) return kLambdaMinNm;
  if (b >= kSpectralBins) return kLambdaMaxNm;
  return visibleWavelengthQuantile(static_cast<double>(b) / kSpectralBins);
}

float binCentreNm(int b) {
  return static_cast<float>(visibleWavelengthQuantile((b + 0.5) / kSpectralBins));
}

int binOf(float lambdaNm) {
  const double u = visibleWavelengthCdf(static_cast<double>(lambdaNm));
  return std::clamp(static_cast<int>(u * kSpectralBins), 0, kSpectralBins - 1);
}

std::array<double, kSpectralBins> binIntegrals(const Spectrum& a, const Spectrum& b) {
  std::array<double, kSpectralBins> out{};
  const auto f = [&](double x) { return valueAt(a, x) * valueAt(b, x); };
  for (int k = 0; k < kSpectralBins; ++k) {
    const double lo = binEdgeNm(k), hi = binEdgeNm(k + 1);
    double sum = 0.0;
    // Pieces between the bin's edges and the 1 nm grid points inside it: on each, a·b is
    // a quadratic, which Simpson's rule integrates exactly.
    for (double x0 = lo; x0 < hi;) {
      const double x1 = std::min(hi, std::floor(x0) + 1.0);
      sum += (x1 - x0) / 6.0 * (f(x0) + 4.0 * f(0.5 * (x0 + x1)) + f(x1));
      x0 = x1;
    }
    out[static_cast<std::size_t>(k)] = sum;
  }
  return out;
}

SpectralBins binAverages(const Spectrum& s) {
  const std::array<double, kSpectralBins> integrals = binIntegrals(s, Spectrum::constant(1.0));
  SpectralBins out;
  for (int b = 0; b < kSpectralBins; ++b)
    out[b] = static_cast<float>(integrals[static_cast<std::size_t>(b)] /
                                (binEdgeNm(b + 1) - binEdgeNm(b)));
  return out;
}

}  // namespace camsim
