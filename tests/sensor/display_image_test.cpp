// Tests for sensor/display_image: XYZ → RGB images and the 8-bit sRGB quick look.
#include "sensor/display_image.h"

#include <cmath>

#include <gtest/gtest.h>

namespace camsim {
namespace {

// D65 white at luminance Y: (x/y, 1, (1 − x − y)/y)·Y with (x, y) = (0.3127, 0.3290).
glm::dvec3 d65White(double Y) {
  return {0.3127 / 0.3290 * Y, Y, (1.0 - 0.3127 - 0.3290) / 0.3290 * Y};
}

Image constantXyz(int w, int h, const glm::dvec3& xyz) {
  Image image(w, h, {"X", "Y", "Z"});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = static_cast<float>(xyz[c]);
  return image;
}

TEST(XyzToRgb, KnownValues) {
  // Three pixels in a 3×1 image: the sRGB red primary, the D65 white at Y = 2, black.
  Image xyz(3, 1, {"X", "Y", "Z"});
  const glm::dvec3 red{0.4124, 0.2126, 0.0193};  // IEC 61966-2-1 first column
  const glm::dvec3 white = d65White(2.0);
  for (int c = 0; c < 3; ++c) {
    xyz.at(0, 0, c) = static_cast<float>(red[c]);
    xyz.at(1, 0, c) = static_cast<float>(white[c]);
  }
  const Image rgb = xyzToRgb(xyz, RgbColorSpace::linearRec709());
  ASSERT_EQ(rgb.width, 3);
  ASSERT_EQ(rgb.height, 1);
  ASSERT_EQ(rgb.channels, (std::vector<std::string>{"R", "G", "B"}));
  // Red → (1, 0, 0): 1e-3 for the 4-decimal rounding of the IEC entries times the
  // inverse matrix's gain (≤ 3.3) plus float storage.
  EXPECT_NEAR(static_cast<double>(rgb.at(0, 0, 0)), 1.0, 1e-3);
  EXPECT_NEAR(static_cast<double>(rgb.at(0, 0, 1)), 0.0, 1e-3);
  EXPECT_NEAR(static_cast<double>(rgb.at(0, 0, 2)), 0.0, 1e-3);
  // White at Y = 2 → (2, 2, 2): units are kept; float storage, 1e-6.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(static_cast<double>(rgb.at(1, 0, c)), 2.0, 1e-6);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(rgb.at(2, 0, c), 0.0f);
}

TEST(XyzToRgb, UsesChannelNamesNotPositions) {
  // Channels stored as Z, X, Y, plus an unrelated channel: the names decide.
  Image xyz(1, 2, {"Z", "A", "X", "Y"});
  const glm::dvec3 white = d65White(0.5);
  for (int y = 0; y < 2; ++y) {
    xyz.at(0, y, 0) = static_cast<float>(white.z);
    xyz.at(0, y, 1) = 123.0f;
    xyz.at(0, y, 2) = static_cast<float>(white.x);
    xyz.at(0, y, 3) = static_cast<float>(white.y);
  }
  const Image rgb = xyzToRgb(xyz, RgbColorSpace::linearRec709());
  for (int y = 0; y < 2; ++y)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(static_cast<double>(rgb.at(0, y, c)), 0.5, 1e-6);
}

TEST(XyzToRgb, AcesCgWhite) {
  // The ACES white (0.32168, 0.33767) at Y = 1 is RGB (1, 1, 1) in ACEScg (1e-6, float).
  const double x = 0.32168;
  const double y = 0.33767;
  const Image rgb =
      xyzToRgb(constantXyz(2, 2, {x / y, 1.0, (1.0 - x - y) / y}), RgbColorSpace::acesCg());
  for (const float v : rgb.pixels) EXPECT_NEAR(static_cast<double>(v), 1.0, 1e-6);
}

TEST(QuickLookSrgb8, ConstantD65ImageIsMidGrey) {
  const Image xyz = constantXyz(4, 3, d65White(10.0));
  const QuickLook q = quickLookSrgb8(xyz);
  // Exposure 0.18 / mean Y = 0.018 (float Y = 10 is exact: 1e-12).
  EXPECT_NEAR(q.exposure, 0.018, 1e-12);
  ASSERT_EQ(q.rgb8.size(), 4u * 3u * 3u);
  // 0.18 linear → sRGB 0.4614 → 117.6 → 118 in every channel (≥ 0.3 code values margin).
  for (size_t i = 0; i < q.rgb8.size(); ++i) EXPECT_EQ(q.rgb8[i], 118) << "i = " << i;
}

TEST(QuickLookSrgb8, ExposureFromMeanLuminanceAndClipping) {
  // Half the pixels at Y = 1, half at Y = 3: mean 2, exposure 0.09. The bright pixels map
  // to linear 0.27 → 0.5564 → 141.9 → 142 (by hand), the dark ones to 0.09 → 0.3318 → 84.6 → 85.
  Image xyz(2, 1, {"X", "Y", "Z"});
  const glm::dvec3 dark = d65White(1.0);
  const glm::dvec3 bright = d65White(3.0);
  for (int c = 0; c < 3; ++c) {
    xyz.at(0, 0, c) = static_cast<float>(dark[c]);
    xyz.at(1, 0, c) = static_cast<float>(bright[c]);
  }
  const QuickLook q = quickLookSrgb8(xyz);
  EXPECT_NEAR(q.exposure, 0.09, 1e-12);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(q.rgb8[static_cast<size_t>(c)], std::lround(srgbEncode(0.09) * 255.0));
    EXPECT_EQ(q.rgb8[static_cast<size_t>(3 + c)], std::lround(srgbEncode(0.27) * 255.0));
  }
  EXPECT_EQ(std::lround(srgbEncode(0.09) * 255.0), 85);
  EXPECT_EQ(std::lround(srgbEncode(0.27) * 255.0), 142);

  // 10 pixels, mean Y = 101/10 = 10.1, exposure 0.18/10.1. Pixel 1 (Y = 100) maps to
  // linear 1.78: clipped to 255. Pixel 0 is XYZ (0, 1, 0), outside the Rec.709 gamut:
  // R = −1.5372·Y and B = −0.2040·Y clip to 0, G = 1.8758 · 0.18/10.1 = 0.03343 linear →
  // sRGB 0.2010 → 51.27 → 51 (by hand with the IEC inverse matrix; margin 0.23 codes).
  Image hot(10, 1, {"X", "Y", "Z"});
  const glm::dvec3 hi = d65White(100.0);
  for (int c = 0; c < 3; ++c) hot.at(1, 0, c) = static_cast<float>(hi[c]);
  hot.at(0, 0, 1) = 1.0f;
  const QuickLook h = quickLookSrgb8(hot);
  EXPECT_NEAR(h.exposure, 0.18 / 10.1, 1e-9);  // float Y = 100: sum exact, 1e-9 is generous
  for (int c = 0; c < 3; ++c) EXPECT_EQ(h.rgb8[static_cast<size_t>(3 + c)], 255);
  EXPECT_EQ(h.rgb8[0], 0);
  EXPECT_EQ(h.rgb8[1], 51);
  EXPECT_EQ(h.rgb8[2], 0);
  for (size_t i = 6; i < h.rgb8.size(); ++i) EXPECT_EQ(h.rgb8[i], 0) << "i = " << i;
}

TEST(QuickLookSrgb8, BlackImage) {
  const QuickLook q = quickLookSrgb8(constantXyz(2, 2, {0.0, 0.0, 0.0}));
  EXPECT_EQ(q.exposure, 1.0);  // no light: no exposure scaling
  for (const std::uint8_t v : q.rgb8) EXPECT_EQ(v, 0);
}

}  // namespace
}  // namespace camsim
