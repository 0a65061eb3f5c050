// RGB → smooth, bounded spectrum (Jakob & Hanika 2019, "A Low-Dimensional Function Space
// for Efficient Spectral Upsampling").
//
//   s(λ) = S(c₀ t² + c₁ t + c₂),  t = (λ − 360 nm) / 470 nm,  S(x) = ½ + x / (2 √(1 + x²))
//
// s is smooth and lies in (0, 1), so an uplifted reflectance is always physically valid.
// The coefficients are found by damped Gauss–Newton on the residual
//   r(c) = RGB(s_c under the colour space's white illuminant) − target,
// walking from mid-grey (c = 0) to the target in small steps, so saturated colours
// converge. Fits are done once, when a scene is loaded.
#pragma once

#include <cmath>

#include <glm/vec3.hpp>

#include "sensor/spectra/color_space.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

struct SigmoidPolynomial {
  double c0 = 0.0, c1 = 0.0, c2 = 0.0;
  double operator()(double lambdaNm) const;
  Spectrum toSpectrum() const;
};

// The same in single precision, for per-texel storage and evaluation while rendering.
struct SigmoidCoefficients {
  float c0 = 0.0f, c1 = 0.0f, c2 = 0.0f;

  static SigmoidCoefficients from(const SigmoidPolynomial& p) {
    return {static_cast<float>(p.c0), static_cast<float>(p.c1), static_cast<float>(p.c2)};
  }
  // s at t = (λ − 360 nm)/470 nm.
  float at(float t) const {
    const float x = (c0 * t + c1) * t + c2;
    return 0.5f + x / (2.0f * std::sqrt(1.0f + x * x));
  }
  float operator()(float lambdaNm) const {
    return at((lambdaNm - static_cast<float>(kLambdaMinNm)) /
              static_cast<float>(kLambdaMaxNm - kLambdaMinNm));
  }
};

// Best sigmoid polynomial for an RGB reflectance with components in [0, 1].
SigmoidPolynomial fitSigmoidPolynomial(const glm::dvec3& rgb, const RgbColorSpace& space);

// Reflectance whose colour under the space's white is rgb (components in [0, 1]);
// r = g = b gives the constant spectrum exactly.
Spectrum rgbToReflectance(const glm::dvec3& rgb, const RgbColorSpace& space);

// Relative emission spectrum whose colour is rgb (components ≥ 0, not all 0):
//   E(λ) = 2m · s_{rgb/2m}(λ) · I(λ) / Σ I ȳ,  m = max(rgb),  I = the space's white.
// Its XYZ (Σ E·cmf) equals the space's XYZ of rgb; scale it to absolute units afterwards.
Spectrum rgbToEmissionShape(const glm::dvec3& rgb, const RgbColorSpace& space);

// RGB of a reflectance under the space's white (the inverse of rgbToReflectance).
glm::dvec3 reflectanceToRgb(const Spectrum& reflectance, const RgbColorSpace& space);

}  // namespace camsim
