// Tests for integrator/rgb_emission_table: the table of sigmoid-polynomial shapes that
// uplifts environment-map texels.
//  - a node holds ReflectanceUplift's fit of its reflectance ρ = c/(2m) (RGB within 1.5e-5
//    by that fit's own tests), to single precision;
//  - between nodes (bilinear in the coefficients) the chromaticity of 2000 random colours,
//    from near-grey to the gamut's faces, stays within 6e-3 of the colour's (measured
//    5.1e-3, worst for a near-pure red with 2 % blue; the table fitted by its own
//    Levenberg–Marquardt walk before 2026-11-22 measured 5.15e-3); the primaries within 1e-4;
//  - the shape depends only on the colour's direction: c and 7c give the same shape.
#include "integrator/lights/rgb_emission_table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "integrator/textures/reflectance_uplift.h"
#include "sensor/spectra/color_space.h"
#include "sensor/spectra/rgb_uplift.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {
namespace {

glm::dvec3 shapeRgb(const SigmoidCoefficients& c) {
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) s.sample(i) = c(static_cast<float>(kLambdaMinNm + i));
  return reflectanceToRgb(s, RgbColorSpace::linearRec709());
}

glm::dvec2 chromaticity(const glm::dvec3& rgb) {
  const glm::dvec3 xyz = RgbColorSpace::linearRec709().toXyz(rgb);
  return glm::dvec2(xyz.x, xyz.y) / (xyz.x + xyz.y + xyz.z);
}

TEST(RgbEmissionTable, NodesHoldTheFittedReflectance) {
  const RgbEmissionTable& table = RgbEmissionTable::get();
  constexpr int kLast = RgbEmissionTable::kNodes - 1;
  for (int channel = 0; channel < 3; ++channel)
    for (int a : {0, 5, kLast / 2, kLast - 1})
      for (int b : {0, 11, kLast - 1}) {
        glm::dvec3 rho(0.0);
        rho[channel] = 0.5;
        rho[(channel + 1) % 3] = 0.5 * a / kLast;
        rho[(channel + 2) % 3] = 0.5 * b / kLast;
        const SigmoidCoefficients c = table.lookup(2.0 * rho);
        const SigmoidCoefficients fit =
            SigmoidCoefficients::from(ReflectanceUplift::linearRec709().fit(rho));
        EXPECT_NEAR(c.c0, fit.c0, 1e-5f * (1.0f + std::abs(fit.c0)))
            << channel << " " << a << " " << b;
        EXPECT_NEAR(c.c1, fit.c1, 1e-5f * (1.0f + std::abs(fit.c1)))
            << channel << " " << a << " " << b;
        EXPECT_NEAR(c.c2, fit.c2, 1e-5f * (1.0f + std::abs(fit.c2)))
            << channel << " " << a << " " << b;
      }
}

TEST(RgbEmissionTable, ChromaticityBetweenNodesAndScaleInvariance) {
  const RgbEmissionTable& table = RgbEmissionTable::get();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < 2000; ++k) {
    glm::dvec3 c(u(rng), u(rng), u(rng));
    if (k % 4 == 0) c = glm::dvec3(1.0) - 0.02 * c;  // near grey
    if (k % 4 == 1) c[k % 3] = 0.0;                  // on the gamut's faces
    if (std::max({c.x, c.y, c.z}) <= 0.0) continue;
    const SigmoidCoefficients s = table.lookup(c);
    const glm::dvec2 d = chromaticity(shapeRgb(s)) - chromaticity(c);
    worst = std::max(worst, std::max(std::abs(d.x), std::abs(d.y)));
    const SigmoidCoefficients s7 = table.lookup(7.0 * c);
    EXPECT_FLOAT_EQ(s7.c0, s.c0);
    EXPECT_FLOAT_EQ(s7.c1, s.c1);
    EXPECT_FLOAT_EQ(s7.c2, s.c2);
  }
  std::printf("[measured] worst chromaticity error of 2000 colours: %.2e\n", worst);
  EXPECT_LT(worst, 6e-3);
  for (int k = 0; k < 3; ++k) {  // the primaries themselves
    glm::dvec3 c(0.0);
    c[k] = 1.0;
    const glm::dvec2 d = chromaticity(shapeRgb(table.lookup(c))) - chromaticity(c);
    EXPECT_LT(std::max(std::abs(d.x), std::abs(d.y)), 1e-4) << k;
  }
}

}  // namespace
}  // namespace camsim
