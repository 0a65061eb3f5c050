#include "sensor/sampled_spectrum.h"

#include <algorithm>

namespace camsim {
namespace {

constexpr double kA = 0.0072;        // nm⁻¹
constexpr double kCentre = 538.0;    // nm

struct VisibleConstants {
  double tanhLo, tanhHi;
  VisibleConstants()
      : tanhLo(std::tanh(kA * (kLambdaMinNm - kCentre))),
        tanhHi(std::tanh(kA * (kLambdaMaxNm - kCentre))) {}
};
const VisibleConstants& visible() {
  static const VisibleConstants c;
  return c;
}

float wrap(float u) { return u >= 1.0f ? u - 1.0f : u; }

}  // namespace

float visibleWavelengthPdf(float lambdaNm) {
  if (lambdaNm < kLambdaMinNm || lambdaNm > kLambdaMaxNm) return 0.0f;
  const double c = std::cosh(kA * (static_cast<double>(lambdaNm) - kCentre));
  return static_cast<float>(kA / ((visible().tanhHi - visible().tanhLo) * c * c));
}

float sampleVisibleWavelength(float u) {
  const VisibleConstants& c = visible();
  const double t = c.tanhLo + static_cast<double>(u) * (c.tanhHi - c.tanhLo);
  const double lambda = kCentre + std::atanh(t) / kA;
  return static_cast<float>(std::clamp(lambda, double(kLambdaMinNm), double(kLambdaMaxNm)));
}

SampledWavelengths SampledWavelengths::sampleVisible(float u) {
  SampledWavelengths w;
  for (int i = 0; i < kWavelengthSamples; ++i) {
    const float ui = wrap(u + static_cast<float>(i) / kWavelengthSamples);
    w.lambda_[i] = sampleVisibleWavelength(ui);
    w.pdf_[i] = visibleWavelengthPdf(w.lambda_[i]);
  }
  return w;
}

SampledWavelengths SampledWavelengths::sampleUniform(float u) {
  SampledWavelengths w;
  constexpr float range = kLambdaMaxNm - kLambdaMinNm;
  for (int i = 0; i < kWavelengthSamples; ++i) {
    const float ui = wrap(u + static_cast<float>(i) / kWavelengthSamples);
    w.lambda_[i] = kLambdaMinNm + ui * range;
    w.pdf_[i] = 1.0f / range;
  }
  return w;
}

}  // namespace camsim
