// ReflectanceUplift: the Jakob–Hanika RGB → spectrum uplift (sensor/spectra/rgb_uplift.h) for every
// texel of an image texture. fitSigmoidPolynomial takes ~13 ms per colour (it walks from grey
// in 32 damped steps on the 1 nm grid); this does the same fit in ~2 µs:
//
// | parameter       | unit | value    | meaning |
// |-----------------|------|----------|---------|
// | node spacing    | nm   | 5        | quadrature nodes λ_j = 360 + 5j, j = 0 … 94 |
// | table size      | —    | 3 × 16³  | start coefficients over (max channel, z, a, b) |
// | tolerance       | —    | 1e-6     | Newton stops when ‖RGB(c) − target‖ is below this |
// | Newton steps    | —    | ≤ 6      | per colour, with step halving |
// | trusted         | —    | 1e-4     | below this residual the last step is taken unchecked |
// | table fits      | —    | 30 steps, 1e-7 | per table node, continued from its neighbour |
//
//   s(λ) = S(c₀ t² + c₁ t + c₂),  t = (λ − 360 nm)/470 nm,  S(x) = ½ + x/(2√(1 + x²))
//   RGB(c) = Σ_j S(x_j) W_j with W_j = Σ_i M·cmf(λ_i)·I(λ_i)/(Σ I ȳ) · L_j(λ_i): the 1 nm
//     sum of reflectanceToRgb applied to the cubic Lagrange interpolant of s through the
//     5 nm nodes (L_j: the cubic basis; M: the space's rgbFromXyz; I: its white)
//   start: trilinear interpolation of a table indexed by the largest channel m, its value
//     z = rgb_m (nodes smoothstep(smoothstep(k/15)), dense near 0 and 1) and the other two
//     channels divided by z; the table itself is fitted once per process (~0.1 s).
//   refine: c ← c − J⁻¹ (RGB(c) − rgb), halving the step until the residual decreases; from
//     a residual < 1e-4 Newton converges quadratically, so that last step is not re-evaluated.
//   greys r = g = b are exact: c = (0, 0, S⁻¹(r)),  S⁻¹(y) = (2y − 1)/(2√(y(1 − y))),
//     clamped to ±10¹⁰ (black and white: S = 0 and 1 exactly, in single and double precision).
//
// Measured (tests/integrator/reflectance_uplift_test) against reflectanceToRgb on the 1 nm
// grid over 1006 colours (dark, saturated, the cube's corners): RGB error mean 2.4e-6, max
// 1.5e-5 (the 5 nm quadrature's); 2.4 evaluations per colour. Speed: `camsim bench`'s texture
// load (1024² random colours: 1.98 µs of CPU per texel, 1.09 s wall on 2 cores).
#pragma once

#include <array>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "sensor/spectra/color_space.h"
#include "sensor/spectra/rgb_uplift.h"

namespace camsim {

class ReflectanceUplift {
 public:
  // For linear Rec.709 (sRGB primaries, D65), built on first use; thread-safe.
  static const ReflectanceUplift& linearRec709();

  explicit ReflectanceUplift(const RgbColorSpace& space);

  // Sigmoid polynomial whose colour under the space's white is rgb (components clamped to
  // [0, 1]; NaN counts as 0).
  SigmoidPolynomial fit(glm::dvec3 rgb) const;
  // RGB of a sigmoid polynomial by the 5 nm quadrature above (what fit() solves for).
  glm::dvec3 rgbOf(const SigmoidPolynomial& p) const;

  static constexpr int kNodes = 95;
  static constexpr int kTableRes = 16;
  static constexpr int kLanes = 8;  // evaluate() works on 8 nodes at a time (vectorised)
  static constexpr int kPaddedNodes = 96;

 private:
  using Coeffs = std::array<double, 3>;
  // RGB and the Jacobian (column k = ∂RGB/∂c_k) at c.
  glm::dvec3 evaluate(const Coeffs& c, glm::dmat3* jacobian) const;
  // Newton from c towards target until the residual is below tolerance. Once it is below
  // `trusted`, the last step is taken without evaluating its result (returns 0 then);
  // otherwise returns the final residual norm.
  double refine(const glm::dvec3& target, Coeffs& c, int maxSteps, double tolerance,
                double trusted) const;
  Coeffs start(const glm::dvec3& rgb) const;
  void buildTable();
  static size_t index(int m, int k, int j, int i) {  // table_[m][k (z)][j (b)][i (a)]
    return ((static_cast<size_t>(m) * kTableRes + static_cast<size_t>(k)) * kTableRes +
            static_cast<size_t>(j)) *
               kTableRes +
           static_cast<size_t>(i);
  }

  // Per node j (padded with zero weights): t_j and t_jᵖ·W_j for p = 0, 1, 2 and each
  // channel. Single precision: the sums of 95 terms stay well below the 1e-6 tolerance.
  alignas(32) std::array<float, kPaddedNodes> t_{};
  alignas(32)
      std::array<std::array<std::array<float, kPaddedNodes>, 3>, 3> weights_{};  // [p][channel][j]
  std::array<double, kTableRes> zNodes_{};
  std::vector<std::array<float, 3>> table_;
};

}  // namespace camsim
