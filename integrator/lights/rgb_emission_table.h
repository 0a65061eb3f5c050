// RgbEmissionTable: linear Rec.709 RGB → the coefficients of a smooth spectral shape
// (Jakob & Hanika 2019), tabulated once so that per-texel uplift (environment maps) is a
// table lookup, never a fit.
//
// | parameter | unit | value | meaning |
// |-----------|------|-------|---------|
// | kNodes    | —    | 33    | table nodes per axis over [0, ½] |
//
// A colour c ≥ 0 with maximum m is uplifted through the reflectance ρ = c/(2m) (as
// rgbToEmissionShape does), whose largest component is ½; the other two, in channel
// order, index a kNodes × kNodes grid for each choice of the largest channel. Each node
// holds the sigmoid polynomial
//   s(λ) = S(c₀ t² + c₁ t + c₂),  t = (λ − 360 nm)/470 nm,  S(x) = ½ + x / (2√(1 + x²))
// whose colour under D65 is the node's ρ, fitted by ReflectanceUplift (the texture uplift:
// RGB error ≤ 1.5e-5; 3·33² fits, a few ms). Lookups interpolate the coefficients
// bilinearly; the caller fixes the luminance (s is only a shape).
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "sensor/spectra/rgb_uplift.h"

namespace camsim {

class RgbEmissionTable {
 public:
  static constexpr int kNodes = 33;

  // Built on first use (thread-safe).
  static const RgbEmissionTable& get();

  // The shape for colour rgb (components ≥ 0, not all 0).
  SigmoidCoefficients lookup(const glm::dvec3& rgb) const;

 private:
  RgbEmissionTable();
  std::vector<glm::dvec3> nodes_;  // [channel][ia][ib]
};

}  // namespace camsim
