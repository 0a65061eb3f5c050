#include "sensor/spectra/sampled_spectrum.h"

#include <algorithm>
#include <array>

#include "sensor/base/check.h"
#include "sensor/base/float_math.h"
#include "sensor/spectra/spectral_bins.h"

namespace camsim {
namespace {

constexpr double kA = 0.0072;      // nm⁻¹
constexpr double kCentre = 538.0;  // nm

// The CDF's bounds, tanh(a(360 − 538)) and Z = tanh(a(830 − 538)) − it, in double for
// visibleWavelengthCdf/Quantile (the bins of spectral_bins.h), and in float for sampling.
// Single precision on purpose: every pixel sample draws kWavelengthSamples wavelengths, and
// the double-precision atanh/cosh of libm cost several times the rest of the sampling. In
// float, λ is within ≈ 2e-4 nm of the exact inverse CDF and visibleWavelengthPdf within
// ≈ 1e-6 relative; sampleVisible's p from t agrees with it within 1e-5 (the tests bound all
// three), far below what a 1 nm spectrum grid resolves.
struct VisibleConstants {
  double tanhLoD, tanhRangeD;
  float tanhLo, tanhRange;  // the same, in float
  float pdfScale;           // a / Z
  VisibleConstants()
      : tanhLoD(std::tanh(kA * (kLambdaMinNm - kCentre))),
        tanhRangeD(std::tanh(kA * (kLambdaMaxNm - kCentre)) - tanhLoD),
        tanhLo(static_cast<float>(tanhLoD)),
        tanhRange(static_cast<float>(tanhRangeD)),
        pdfScale(static_cast<float>(kA / tanhRangeD)) {}
};
const VisibleConstants& visible() {
  static const VisibleConstants c;
  return c;
}

// u mod 1 for u in [0, 2): a select, lane by lane for a Float4 (float_math.h).
// F: float or Float4, here and below.
template <typename F>
F wrap(F u) {
  return u >= 1.0f ? u - 1.0f : u;
}

// λ = 538 + atanh(t)/a with t uniform over [tanhLo, tanhHi]; atanh(t) = ½ log((1+t)/(1−t)).
// Also returns p(λ) = (a/Z)·sech²(a(λ − 538)) = (a/Z)·(1 − t)(1 + t): no exp needed (and
// (1 − t)(1 + t) keeps its relative precision where 1 − t² would cancel).
template <typename F>
struct VisibleSample {
  F lambda;  // nm
  F pdf;     // nm⁻¹
};
template <typename F>
[[gnu::always_inline]] inline VisibleSample<F> sampleVisibleWithPdf(F u) {
  const VisibleConstants& c = visible();
  const F t = c.tanhLo + u * c.tanhRange;
  F lambda = static_cast<float>(kCentre) +
             static_cast<float>(0.5 / kA) * logOfNormal((1.0f + t) / (1.0f - t));
  constexpr auto lo = static_cast<float>(kLambdaMinNm), hi = static_cast<float>(kLambdaMaxNm);
  lambda = lambda < lo ? lo : lambda;  // std::clamp's order, lane by lane
  lambda = hi < lambda ? hi : lambda;
  return {lambda, c.pdfScale * ((1.0f - t) * (1.0f + t))};
}

}  // namespace

// 1/cosh²(x) = 4e/(e + 1)² with e = exp(2x): one expf.
float visibleWavelengthPdf(float lambdaNm) {
  if (lambdaNm < kLambdaMinNm || lambdaNm > kLambdaMaxNm) return 0.0f;
  const float e = std::exp(static_cast<float>(2.0 * kA) * (lambdaNm - static_cast<float>(kCentre)));
  return visible().pdfScale * 4.0f * e / ((e + 1.0f) * (e + 1.0f));
}

double visibleWavelengthCdf(double lambdaNm) {
  return (std::tanh(kA * (lambdaNm - kCentre)) - visible().tanhLoD) / visible().tanhRangeD;
}

double visibleWavelengthQuantile(double u) {
  return kCentre + std::atanh(visible().tanhLoD + u * visible().tanhRangeD) / kA;
}

float sampleVisibleWavelength(float u) {
  return sampleVisibleWithPdf(u).lambda;
}

// Sampled wavelengths lie in [360, 830] nm (both samplers clamp or stay inside), where
// Spectrum::operator() interpolates at exactly this position.
void SampledWavelengths::locateOnGrid() {
  Spectrum::gridPositionLanes(lambda_, gridIndex_, gridFraction_);
}

// The four wavelengths in one pass of SSE arithmetic (the same bits as one at a time).
SampledWavelengths SampledWavelengths::sampleVisible(float u) {
  FloatW offsets;
  for (int i = 0; i < kWavelengthSamples; ++i)
    offsets[i] = static_cast<float>(i) / static_cast<float>(kWavelengthSamples);
  const FloatW ui = wrap(u + offsets);
  const VisibleSample<FloatW> v = sampleVisibleWithPdf(ui);
  SampledWavelengths w;
  w.lambda_ = v.lambda;
  w.pdf_ = v.pdf;
  w.locateOnGrid();
  // The bin of equal probability is ⌊B·u⌋: u is the wavelength's place in the CDF.
  const IntW bins = lanes::toInt(ui * static_cast<float>(kSpectralBins));
  w.bin_ = bins > kSpectralBins - 1 ? IntW{} + (kSpectralBins - 1) : bins;
  return w;
}

SampledWavelengths SampledWavelengths::sampleUniform(float u) {
  SampledWavelengths w;
  constexpr float range = kLambdaMaxNm - kLambdaMinNm;
  for (int i = 0; i < kWavelengthSamples; ++i) {
    const float ui = wrap(u + static_cast<float>(i) / kWavelengthSamples);
    w.lambda_[i] = kLambdaMinNm + ui * range;
    w.pdf_[i] = 1.0f / range;
    w.bin_[i] = binOf(w.lambda_[i]);
  }
  w.locateOnGrid();
  return w;
}

SampledWavelengths SampledWavelengths::monochromatic(float lambdaNm) {
  CAMSIM_CHECK(lambdaNm >= static_cast<float>(kLambdaMinNm) &&
               lambdaNm <= static_cast<float>(kLambdaMaxNm));
  SampledWavelengths w;
  const int bin = binOf(lambdaNm);
  for (int i = 0; i < kWavelengthSamples; ++i) {
    w.lambda_[i] = lambdaNm;
    w.pdf_[i] = 1.0f;
    w.bin_[i] = bin;
  }
  w.locateOnGrid();
  return w;
}

const SampledWavelengths& SampledWavelengths::binCentres(int k) {
  constexpr int kGroups = kSpectralBins / kWavelengthSamples;
  static const std::array<SampledWavelengths, kGroups> groups = [] {
    std::array<SampledWavelengths, kGroups> g;
    for (int j = 0; j < kGroups; ++j) {
      SampledWavelengths& w = g[static_cast<std::size_t>(j)];
      for (int i = 0; i < kWavelengthSamples; ++i) {
        w.bin_[i] = j * kWavelengthSamples + i;
        w.lambda_[i] = binCentreNm(w.bin_[i]);
        w.pdf_[i] = 1.0f;
      }
      w.locateOnGrid();
    }
    return g;
  }();
  CAMSIM_CHECK(k >= 0 && k < kGroups);
  return groups[static_cast<std::size_t>(k)];
}

}  // namespace camsim
