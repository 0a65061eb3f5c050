// Tests for sensor/color_space: matrices derived from chromaticities against published
// matrices, and the sRGB transfer function.
//
// glm matrices are column-major: m[col][row]. The tables below are written row by row,
// as published, and compared with m[col][row].
#include "sensor/spectra/color_space.h"

#include <cmath>

#include <gtest/gtest.h>

namespace camsim {
namespace {

using Rows = double[3][3];

void expectMatrixNear(const glm::dmat3& m, const Rows& rows, double tolerance, const char* what) {
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col)
      EXPECT_NEAR(m[col][row], rows[row][col], tolerance)
          << what << " row " << row << " col " << col;
}

TEST(RgbColorSpace, LinearRec709XyzFromRgbMatchesIec61966) {
  // IEC 61966-2-1 (sRGB), 4 decimals.
  const Rows iec = {{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};
  const RgbColorSpace& cs = RgbColorSpace::linearRec709();
  // 2e-4 per entry (brief): the published entries are rounded to 4 decimals (±5e-5) and
  // were derived from the same chromaticities.
  expectMatrixNear(cs.xyzFromRgb(), iec, 2e-4, "xyzFromRgb");
  EXPECT_EQ(cs.name(), "lin_rec709");
}

TEST(RgbColorSpace, LinearRec709RgbFromXyzMatchesIec61966) {
  // IEC 61966-2-1 inverse matrix, 4 decimals. It was computed from the rounded forward
  // matrix, so it differs from the exact inverse of the chromaticity-derived matrix by up
  // to 3.7e-4 (entry R←X: 3.2406 published vs 3.24097 exact): tolerance 5e-4.
  const Rows iec = {
      {3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
  const RgbColorSpace& cs = RgbColorSpace::linearRec709();
  expectMatrixNear(cs.rgbFromXyz(), iec, 5e-4, "rgbFromXyz");
  // And the two matrices are inverses of each other (double precision: 1e-12).
  const glm::dmat3 product = cs.rgbFromXyz() * cs.xyzFromRgb();
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row) EXPECT_NEAR(product[col][row], col == row ? 1.0 : 0.0, 1e-12);
}

TEST(RgbColorSpace, ToXyzAndFromXyzApplyTheMatrices) {
  const RgbColorSpace& cs = RgbColorSpace::linearRec709();
  // Pure red is the first column of the IEC matrix (2e-4 as above).
  const glm::dvec3 red = cs.toXyz({1.0, 0.0, 0.0});
  EXPECT_NEAR(red.x, 0.4124, 2e-4);
  EXPECT_NEAR(red.y, 0.2126, 2e-4);
  EXPECT_NEAR(red.z, 0.0193, 2e-4);
  // Luminance of (0.2, 0.4, 0.6): Y = 0.2126·0.2 + 0.7152·0.4 + 0.0722·0.6 (2e-4).
  EXPECT_NEAR(cs.toXyz({0.2, 0.4, 0.6}).y, 0.2126 * 0.2 + 0.7152 * 0.4 + 0.0722 * 0.6, 2e-4);
  const glm::dvec3 rgb{0.3, 0.6, 0.1};
  const glm::dvec3 back = cs.fromXyz(cs.toXyz(rgb));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], rgb[k], 1e-12);
}

TEST(RgbColorSpace, WhiteMapsToTheWhitePoint) {
  for (const RgbColorSpace* cs :
       {&RgbColorSpace::linearRec709(), &RgbColorSpace::acesCg(), &RgbColorSpace::aces2065()}) {
    const Chromaticity w = cs->white();
    const glm::dvec3 xyz = cs->toXyz({1.0, 1.0, 1.0});
    // Independent: XYZ of (x, y) at Y = 1 is (x/y, 1, (1 − x − y)/y). Double: 1e-12.
    EXPECT_NEAR(xyz.x, w.x / w.y, 1e-12) << cs->name();
    EXPECT_NEAR(xyz.y, 1.0, 1e-12) << cs->name();
    EXPECT_NEAR(xyz.z, (1.0 - w.x - w.y) / w.y, 1e-12) << cs->name();
  }
  // The Rec.709 white is D65 (0.3127, 0.3290); ACES is (0.32168, 0.33767).
  EXPECT_EQ(RgbColorSpace::linearRec709().white().x, 0.3127);
  EXPECT_EQ(RgbColorSpace::linearRec709().white().y, 0.3290);
  EXPECT_EQ(RgbColorSpace::acesCg().white().x, 0.32168);
  EXPECT_EQ(RgbColorSpace::acesCg().white().y, 0.33767);
}

TEST(RgbColorSpace, PrimariesMapToTheirChromaticities) {
  const RgbColorSpace& cs = RgbColorSpace::acesCg();
  const Chromaticity expected[3] = {cs.red(), cs.green(), cs.blue()};
  for (int k = 0; k < 3; ++k) {
    glm::dvec3 rgb{0.0, 0.0, 0.0};
    rgb[k] = 1.0;
    const Chromaticity c = xyzToChromaticity(cs.toXyz(rgb));
    EXPECT_NEAR(c.x, expected[k].x, 1e-12);
    EXPECT_NEAR(c.y, expected[k].y, 1e-12);
  }
  // AP1 primaries (SMPTE ST 2065-1 / ACES S-2014-004).
  EXPECT_EQ(cs.red().x, 0.713);
  EXPECT_EQ(cs.green().y, 0.830);
  EXPECT_EQ(cs.blue().y, 0.044);
}

TEST(RgbColorSpace, AcesCgXyzFromRgbMatchesAp1Matrix) {
  // ACES AP1 → XYZ (ACES TB-2014-004), 10 decimals.
  const Rows ap1 = {{0.6624541811, 0.1340042065, 0.1561876870},
                    {0.2722287168, 0.6740817658, 0.0536895174},
                    {-0.0055746495, 0.0040607335, 1.0103391003}};
  // 1e-3 (brief); the derivation uses the same chromaticities, so in practice ≪ 1e-6.
  expectMatrixNear(RgbColorSpace::acesCg().xyzFromRgb(), ap1, 1e-3, "AP1");
  EXPECT_EQ(RgbColorSpace::acesCg().name(), "acescg");
}

TEST(RgbColorSpace, Aces2065XyzFromRgbMatchesAp0Matrix) {
  // ACES AP0 → XYZ (SMPTE ST 2065-1), 10 decimals; 1e-3 as for AP1.
  const Rows ap0 = {{0.9525523959, 0.0, 0.0000936786},
                    {0.3439664498, 0.7281660966, -0.0721325464},
                    {0.0, 0.0, 1.0088251844}};
  expectMatrixNear(RgbColorSpace::aces2065().xyzFromRgb(), ap0, 1e-3, "AP0");
}

TEST(RgbColorSpace, IlluminantIsTheWhiteSpectrum) {
  // The Rec.709 illuminant is D65: its chromaticity is the white point to 4 decimals.
  const Chromaticity c =
      xyzToChromaticity(spectrumToXyz(RgbColorSpace::linearRec709().illuminant()));
  EXPECT_NEAR(c.x, 0.3127, 5e-5);
  EXPECT_NEAR(c.y, 0.3290, 5e-5);
  // The ACES white (≈ D60): (0.32168, 0.33767), 2e-4 for the tabulated spectrum.
  const Chromaticity a = xyzToChromaticity(spectrumToXyz(RgbColorSpace::acesCg().illuminant()));
  EXPECT_NEAR(a.x, 0.32168, 2e-4);
  EXPECT_NEAR(a.y, 0.33767, 2e-4);
}

TEST(SrgbTransfer, MidGreyEncodesTo118) {
  // 0.18 linear → 0.46135 encoded → 117.64 → 118 (IEC 61966-2-1 formula by hand).
  EXPECT_EQ(std::lround(srgbEncode(0.18) * 255.0), 118);
  EXPECT_NEAR(srgbEncode(0.18), 1.055 * std::pow(0.18, 1.0 / 2.4) - 0.055, 1e-15);
}

TEST(SrgbTransfer, KnownValues) {
  EXPECT_EQ(srgbEncode(0.0), 0.0);
  EXPECT_NEAR(srgbEncode(1.0), 1.0, 1e-15);
  EXPECT_NEAR(srgbDecode(1.0), 1.0, 1e-15);
  // Linear segment: 12.92·x below 0.0031308.
  EXPECT_DOUBLE_EQ(srgbEncode(0.001), 0.01292);
  EXPECT_DOUBLE_EQ(srgbDecode(0.01292), 0.001);
  // 0.5 encoded ↔ 0.21404 linear (the usual "half-way" value; 1e-5).
  EXPECT_NEAR(srgbDecode(0.5), 0.21404, 1e-5);
  // The two pieces meet at the threshold: the standard's constants leave a jump of
  // ≈ 1e-8 there, so 1e-6.
  EXPECT_NEAR(srgbEncode(0.0031308), 1.055 * std::pow(0.0031308, 1.0 / 2.4) - 0.055, 1e-6);
  EXPECT_NEAR(srgbDecode(0.04045), std::pow((0.04045 + 0.055) / 1.055, 2.4), 1e-6);
}

TEST(SrgbTransfer, DecodeInvertsEncode) {
  for (int i = 0; i <= 1000; ++i) {
    const double x = i / 1000.0;
    // 1e-12 (brief): pow round trips lose a few ulps.
    EXPECT_NEAR(srgbDecode(srgbEncode(x)), x, 1e-12) << "x = " << x;
  }
  for (const double x : {1e-6, 0.0031307, 0.0031308, 0.0031309, 0.04, 0.999999})
    EXPECT_NEAR(srgbDecode(srgbEncode(x)), x, 1e-12) << "x = " << x;
}

TEST(SrgbTransfer, IsMonotonic) {
  double previous = srgbEncode(0.0);
  for (int i = 1; i <= 10000; ++i) {
    const double v = srgbEncode(i / 10000.0);
    EXPECT_GT(v, previous) << "i = " << i;
    previous = v;
  }
}

}  // namespace
}  // namespace camsim
