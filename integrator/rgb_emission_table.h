// RgbEmissionTable: linear Rec.709 RGB → the coefficients of a smooth spectral shape
// (Jakob & Hanika 2019), tabulated once so that per-texel uplift (environment maps) is a
// table lookup, never a fit.
//
// | parameter | unit | value | meaning |
// |-----------|------|-------|---------|
// | kNodes    | —    | 33    | table nodes per axis over [0, ½] |
// | kBinNm    | nm   | 5     | wavelength bins of the colour integrals in the fits |
//
// A colour c ≥ 0 with maximum m is uplifted through the reflectance ρ = c/(2m) (as
// rgbToEmissionShape does), whose largest component is ½; the other two, in channel
// order, index a kNodes × kNodes grid for each choice of the largest channel. Each node
// holds the sigmoid polynomial
//   s(λ) = S(c₀ t² + c₁ t + c₂),  t = (λ − 360 nm)/470 nm,  S(x) = ½ + x / (2√(1 + x²))
// whose colour under D65 (Σ s D65 x̄ȳz̄ / Σ D65 ȳ) is the node's ρ, fitted by Levenberg–
// Marquardt walking outward from grey (c = 0, exact) in small steps. Lookups interpolate
// the coefficients bilinearly; the caller fixes the luminance (s is only a shape).
#pragma once

#include <cmath>
#include <vector>

#include <glm/vec3.hpp>

#include "sensor/spectrum.h"

namespace camsim {

struct SigmoidCoefficients {
  float c0 = 0.0f, c1 = 0.0f, c2 = 0.0f;

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

class RgbEmissionTable {
 public:
  static constexpr int kNodes = 33;
  static constexpr int kBinNm = 5;

  // Built on first use (thread-safe).
  static const RgbEmissionTable& get();

  // The shape for colour rgb (components ≥ 0, not all 0).
  SigmoidCoefficients lookup(const glm::dvec3& rgb) const;

  // Colour of the reflectance s under D65, Y of the perfect diffuser = 1 (binned sums).
  static glm::dvec3 reflectanceXyz(const glm::dvec3& coefficients);

 private:
  RgbEmissionTable();
  std::vector<glm::dvec3> nodes_;  // [channel][ia][ib]
};

}  // namespace camsim
