// Tests for sensor/rgb_uplift: RGB → smooth bounded spectra (Jakob & Hanika 2019).
#include "sensor/spectra/rgb_uplift.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sensor/spectra/cie.h"

namespace camsim {
namespace {

std::string str(const glm::dvec3& v) {
  return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
}

// Largest |s(λ+1) − s(λ)| over the grid: the spectrum's steepest slope per nm.
double maxSlopePerNm(const Spectrum& s) {
  double slope = 0.0;
  for (int i = 0; i + 1 < kSpectrumSamples; ++i)
    slope = std::max(
        slope, std::abs(static_cast<double>(s.sample(i + 1)) - static_cast<double>(s.sample(i))));
  return slope;
}

// The round trip RGB → reflectance → RGB under the space's white. Tolerance 0.5 % of the
// largest component, and 0.005 absolute on zero components (brief). Measured errors are
// far smaller: ≤ 1e-8 for the primaries, secondaries and random colours (the fit
// converges to the float precision of the stored spectrum), ≤ 2.5e-4 for greys (a grey
// is returned as the exact constant spectrum; the tabulated D65's chromaticity differs
// from the space's (0.3127, 0.3290) white by < 5e-5).
void expectRoundTrip(const glm::dvec3& rgb, double maxSlope) {
  const RgbColorSpace& cs = RgbColorSpace::linearRec709();
  const Spectrum s = rgbToReflectance(rgb, cs);
  const glm::dvec3 back = reflectanceToRgb(s, cs);
  const double largest = std::max({rgb.x, rgb.y, rgb.z});
  for (int k = 0; k < 3; ++k) {
    const double tolerance = rgb[k] == 0.0 ? 0.005 : 0.005 * largest;
    EXPECT_NEAR(back[k], rgb[k], tolerance) << "rgb " << str(rgb) << " → " << str(back);
  }
  // A valid reflectance: within [0, 1] at every wavelength.
  EXPECT_GE(s.minValue(), 0.0) << str(rgb);
  EXPECT_LE(s.maxValue(), 1.0) << str(rgb);
  EXPECT_LT(maxSlopePerNm(s), maxSlope) << str(rgb);
}

// Smoothness bounds, per nm. Measured: primaries and secondaries ≤ 0.063 (red and cyan
// need the steepest edge; magenta and green 0.048, blue and yellow 0.035); colours in
// [0.05, 0.95]³ ≤ 0.018. The bounds leave headroom without admitting a step function
// (a reflectance jumping 0 → 1 within a few nm would have slope ≥ 0.2).
constexpr double kSlopeSaturated = 0.08;
constexpr double kSlopeInterior = 0.05;

TEST(RgbUplift, PrimariesRoundTrip) {
  expectRoundTrip({1.0, 0.0, 0.0}, kSlopeSaturated);
  expectRoundTrip({0.0, 1.0, 0.0}, kSlopeSaturated);
  expectRoundTrip({0.0, 0.0, 1.0}, kSlopeSaturated);
}

TEST(RgbUplift, SecondariesRoundTrip) {
  expectRoundTrip({1.0, 1.0, 0.0}, kSlopeSaturated);
  expectRoundTrip({0.0, 1.0, 1.0}, kSlopeSaturated);
  expectRoundTrip({1.0, 0.0, 1.0}, kSlopeSaturated);
}

TEST(RgbUplift, GreysAreExactConstants) {
  for (const double v : {0.0, 0.18, 0.5, 1.0}) {
    const glm::dvec3 rgb{v, v, v};
    expectRoundTrip(rgb, 1e-12);  // a constant has zero slope
    const Spectrum s = rgbToReflectance(rgb, RgbColorSpace::linearRec709());
    EXPECT_EQ(s.minValue(), static_cast<double>(static_cast<float>(v)));
    EXPECT_EQ(s.maxValue(), static_cast<double>(static_cast<float>(v)));
  }
}

TEST(RgbUplift, RandomColoursRoundTrip) {
  std::mt19937 rng(20240611u);
  auto uniform = [&rng] { return 0.05 + 0.9 * static_cast<double>(rng() >> 8) * 0x1p-24; };
  for (int n = 0; n < 20; ++n) {
    const glm::dvec3 rgb{uniform(), uniform(), uniform()};
    expectRoundTrip(rgb, kSlopeInterior);
  }
  // A few hand-picked near-primary colours, well inside [0, 1] but saturated.
  expectRoundTrip({0.9, 0.1, 0.1}, kSlopeInterior);
  expectRoundTrip({0.05, 0.95, 0.5}, kSlopeInterior);
  expectRoundTrip({0.1, 0.1, 0.9}, kSlopeInterior);
}

TEST(RgbUplift, RoundTripInAcesCg) {
  // ACEScg's gamut is wider; a moderately saturated colour still fits (measured ≤ 1e-8).
  const RgbColorSpace& cs = RgbColorSpace::acesCg();
  for (const glm::dvec3 rgb : {glm::dvec3{0.6, 0.3, 0.2}, glm::dvec3{0.2, 0.5, 0.7}}) {
    const glm::dvec3 back = reflectanceToRgb(rgbToReflectance(rgb, cs), cs);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], rgb[k], 0.005 * 0.7) << str(rgb);
  }
}

TEST(RgbUplift, SigmoidPolynomialEvaluation) {
  // s(λ) = S(c0 t² + c1 t + c2), t = (λ − 360)/470, S(x) = ½ + x / (2√(1 + x²)).
  const SigmoidPolynomial p{2.0, -1.0, 0.5};
  for (const double lambda : {360.0, 500.0, 612.5, 830.0}) {
    const double t = (lambda - 360.0) / 470.0;
    const double x = 2.0 * t * t - t + 0.5;
    EXPECT_NEAR(p(lambda), 0.5 + x / (2.0 * std::sqrt(1.0 + x * x)), 1e-15) << lambda;
  }
  EXPECT_DOUBLE_EQ(SigmoidPolynomial{}(550.0), 0.5);
  const Spectrum s = p.toSpectrum();
  EXPECT_NEAR(static_cast<double>(s.sample(140)), p(500.0), 1e-7);  // float storage
}

TEST(RgbUplift, EmissionShapeHasTheColoursXyz) {
  const RgbColorSpace& cs = RgbColorSpace::linearRec709();
  for (const glm::dvec3 rgb :
       {glm::dvec3{2.0, 1.0, 0.5}, glm::dvec3{1.0, 1.0, 1.0}, glm::dvec3{0.2, 0.5, 3.0},
        glm::dvec3{1.0, 0.0, 0.0}, glm::dvec3{0.3, 0.3, 0.3}}) {
    const Spectrum e = rgbToEmissionShape(rgb, cs);
    EXPECT_GE(e.minValue(), 0.0) << str(rgb);
    const glm::dvec3 got = spectrumToXyz(e);
    const glm::dvec3 expected = cs.toXyz(rgb);
    const double largest = std::max({expected.x, expected.y, expected.z});
    // 0.5 % of the largest XYZ component (brief). Measured: ≤ 1e-6 relative for chromatic
    // colours, 2.1e-4 for greys (D65 table vs the (0.3127, 0.3290) white).
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(got[k], expected[k], 0.005 * largest) << str(rgb) << " k = " << k;
  }
}

TEST(RgbUplift, EmissionShapeScalesLinearly) {
  const RgbColorSpace& cs = RgbColorSpace::linearRec709();
  const Spectrum a = rgbToEmissionShape({0.4, 0.2, 0.1}, cs);
  const Spectrum b = rgbToEmissionShape({4.0, 2.0, 1.0}, cs);
  // Same chromaticity: the same reflectance fit, scaled by 10 (float: 1e-6 relative).
  for (int i = 0; i < kSpectrumSamples; i += 10)
    EXPECT_NEAR(static_cast<double>(b.sample(i)), 10.0 * static_cast<double>(a.sample(i)),
                1e-6 * 10.0 * a.maxValue() + 1e-12);
}

}  // namespace
}  // namespace camsim
