// Tests for sensor/display_image: XYZ → RGB images and the 8-bit sRGB quick look.
#include "sensor/isp/display_image.h"

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

}  // namespace
}  // namespace camsim
