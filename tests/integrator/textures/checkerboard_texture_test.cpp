// Tests for integrator/checkerboard_texture: parity of the squares at known uvs (with scale,
// offset, negative and huge coordinates), the float version, maxValue, the factory, and a
// rendered checkerboard quad whose pixels show ρ_a·Lₑ and ρ_b·Lₑ in the right squares.
#include "integrator/textures/checkerboard_texture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "integrator/scene/factory.h"
#include "tests/integrator/texture_test_support.h"

namespace camsim {
namespace {

const SampledWavelengths kCheckerLambda = SampledWavelengths::sampleUniform(0.3f);

TEST(Checkerboard, ParityAtKnownUvs) {
  const glm::vec2 one(1.0f), zero(0.0f);
  const struct {
    glm::vec2 uv;
    bool a;
  } cases[] = {
      {{0.01f, 0.01f}, true},    // square (0, 0)
      {{0.13f, 0.01f}, false},   // (1, 0): 0.13·8 = 1.04
      {{0.13f, 0.13f}, true},    // (1, 1)
      {{0.01f, 0.99f}, false},   // (0, 7)
      {{0.99f, 0.99f}, true},    // (7, 7)
      {{-0.01f, 0.01f}, false},  // (−1, 0)
      {{-0.01f, -0.01f}, true},  // (−1, −1)
      {{1.01f, 0.01f}, true},    // (8, 0): repeats with period 2/checks
      {{0.125f, 0.0f}, false},   // on an edge: the square above/right of it
  };
  for (const auto& c : cases)
    EXPECT_EQ(checkerboardIsA(c.uv, 8.0f, one, zero), c.a) << c.uv.x << "," << c.uv.y;
  // uv' = uv · scale + offset before the squares.
  EXPECT_FALSE(checkerboardIsA({0.01f, 0.01f}, 8.0f, one, {0.125f, 0.0f}));
  EXPECT_FALSE(checkerboardIsA({0.07f, 0.01f}, 8.0f, {2.0f, 1.0f}, zero));  // u' = 0.14
  EXPECT_TRUE(checkerboardIsA({0.3f, 0.3f}, 2.0f, one, zero));
  EXPECT_FALSE(checkerboardIsA({0.7f, 0.3f}, 2.0f, one, zero));
  EXPECT_TRUE(checkerboardIsA({0.7f, 0.3f}, 1.0f, one, zero));
  // Huge and non-finite coordinates are defined (no overflow): NaN shows b.
  EXPECT_TRUE(checkerboardIsA({1e30f, 1e30f}, 8.0f, one, zero));  // far beyond 2²⁴: even integers
  EXPECT_FALSE(checkerboardIsA({std::numeric_limits<float>::quiet_NaN(), 0.0f}, 8.0f, one, zero));
}

TEST(Checkerboard, SpectrumAndFloatTexturesPickTheirValues) {
  const Spectrum a = Spectrum::constant(0.8), b = Spectrum::constant(0.2);
  const CheckerboardSpectrumTexture s(a, b, 4.0f);
  EXPECT_FLOAT_EQ(s.evaluate({0.1f, 0.1f}, kCheckerLambda)[0], 0.8f);
  EXPECT_FLOAT_EQ(s.evaluate({0.3f, 0.1f}, kCheckerLambda)[2], 0.2f);
  EXPECT_DOUBLE_EQ(s.maxValue(), std::max(a.maxValue(), b.maxValue()));
  const CheckerboardFloatTexture f(0.05f, 0.5f, 4.0f, {1.0f, 1.0f}, {0.25f, 0.0f});
  EXPECT_FLOAT_EQ(f.evaluate({0.1f, 0.1f}), 0.5f);  // u' = 0.35: square (1, 0)
  EXPECT_FLOAT_EQ(f.evaluate({0.3f, 0.1f}), 0.05f);

  TextureDescription d;
  d.kind = TextureDescription::Kind::kCheckerboard;
  d.checkerA = Spectrum::constant(0.3);
  d.checkerB = Spectrum::constant(0.6);
  d.checks = 2.0f;
  EXPECT_FLOAT_EQ(makeSpectrumTexture(d)->evaluate({0.75f, 0.75f}, kCheckerLambda)[1], 0.3f);
  EXPECT_FLOAT_EQ(makeFloatTexture(d)->evaluate({0.75f, 0.25f}), 0.6f);
}

// The quad inside the emitting sphere (texture_test_support.h) with checks: 4 and offset
// [0.25, 0]: each square is 2×2 pixels, and pixel (px, py) shows a where
// ⌊(u + 0.25)·4⌋ + ⌊v·4⌋ is even at its centre. Radiance ρ·Lₑ: Y = ρ · 0.01 · Km Σȳ.
// Tolerance 1 %: the quad's radiance is exact up to the Monte Carlo noise of light
// sampling under MIS (measured: largest deviation 0.35 % over the 64 pixels at 64 spp).
constexpr int kSpp = 1024;

TEST(Checkerboard, RenderedQuadShowsBothRadiancesInTheRightSquares) {
  const test::LuminanceImage img = test::renderLuminance(
      test::texturedQuadScene(
          "{checkerboard: {a: 0.8, b: {rgb: [0.2, 0.2, 0.2]}, checks: 4}, offset: [0.25, 0]}"),
      kSpp, 3);
  EXPECT_EQ(img.stats.rejectedSamples, 0u);
  test::MaxError worst;
  for (int py = 0; py < 8; ++py)
    for (int px = 0; px < 8; ++px) {
      const double u = (px + 0.5) / 8.0, v = 1.0 - (py + 0.5) / 8.0;
      const bool a = static_cast<int>(std::floor((u + 0.25) * 4.0) + std::floor(v * 4.0)) % 2 == 0;
      const double expected = (a ? 0.8 : 0.2) * 0.01 * test::flatRadianceY();
      EXPECT_LT(worst(img.at(px, py), expected), 0.01)
          << "pixel " << px << "," << py << (a ? " (a)" : " (b)");
    }
}

}  // namespace
}  // namespace camsim
