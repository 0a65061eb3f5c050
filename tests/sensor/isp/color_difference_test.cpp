// Tests for sensor/color_difference: CIELAB against hand-derived values and CIEDE2000
// against the published test data of Sharma, Wu & Dalal (2005), Table 1 (all 34 pairs,
// entered by hand from the paper: L*, a*, b* of both samples and ΔE00 to 4 decimals).
#include "sensor/isp/color_difference.h"

#include <cmath>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"

namespace camsim {
namespace {

struct SharmaPair {
  double l1, a1, b1, l2, a2, b2, deltaE;
};

// Sharma, Wu & Dalal, Color Res. Appl. 30(1) 21–30 (2005), Table 1.
constexpr SharmaPair kSharma[] = {
    {50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425},
    {50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615},
    {50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412},
    {50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669},
    {50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461},
    {50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065},
    {50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492},
    {50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977},
    {50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030},
    {50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000},
    {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644},
    {63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630},
    {61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731},
    {35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645},
    {22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373},
    {36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146},
    {90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441},
    {90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381},
    {6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377},
    {2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082},
};

TEST(Ciede2000, MatchesSharmaWuDalalTestData) {
  // The paper gives ΔE00 rounded to 4 decimals: |error| ≤ 5e-5, tolerance 1e-4.
  int i = 1;
  for (const SharmaPair& p : kSharma) {
    const glm::dvec3 lab1(p.l1, p.a1, p.b1), lab2(p.l2, p.a2, p.b2);
    EXPECT_NEAR(deltaE2000(lab1, lab2), p.deltaE, 1e-4) << "pair " << i;
    EXPECT_NEAR(deltaE2000(lab2, lab1), p.deltaE, 1e-4) << "pair " << i << " swapped";
    ++i;
  }
  EXPECT_EQ(i, 35);
}

TEST(Ciede2000, ZeroForIdenticalColoursAndLightnessOnlyAtL50) {
  EXPECT_EQ(deltaE2000({50.0, 10.0, -20.0}, {50.0, 10.0, -20.0}), 0.0);
  // Neutral pair around L̄ = 50: S_L = 1, so ΔE00 = ΔL.
  EXPECT_NEAR(deltaE2000({49.0, 0.0, 0.0}, {51.0, 0.0, 0.0}), 2.0, 1e-12);
}

TEST(Ciede2000, ParametricFactorScalesTheLightnessTerm) {
  const Ciede2000Weights k{2.0, 1.0, 1.0};
  EXPECT_NEAR(deltaE2000({49.0, 0.0, 0.0}, {51.0, 0.0, 0.0}, k), 1.0, 1e-12);
}

TEST(CieLab, WhiteBlackAndLinearSegment) {
  const glm::dvec3 white(0.95047, 1.0, 1.08883);
  const glm::dvec3 w = xyzToLab(white, white);
  EXPECT_NEAR(w.x, 100.0, 1e-12);
  EXPECT_NEAR(w.y, 0.0, 1e-12);
  EXPECT_NEAR(w.z, 0.0, 1e-12);
  // 18 % grey: L* = 116 · 0.18^(1/3) − 16 = 49.4961...
  EXPECT_NEAR(xyzToLab(white * 0.18, white).x, 116.0 * std::cbrt(0.18) - 16.0, 1e-12);
  // Below (6/29)³ the linear segment: L* = (29/3)³ · Y/Yn = 903.296… · Y.
  EXPECT_NEAR(xyzToLab(white * 0.001, white).x, std::pow(29.0 / 3.0, 3.0) * 0.001, 1e-9);
  // Continuity at the junction t = (6/29)³.
  const double t = std::pow(6.0 / 29.0, 3.0);
  EXPECT_NEAR(xyzToLab(white * (t * (1 + 1e-9)), white).x, xyzToLab(white * t, white).x, 1e-6);
  // a* > 0 for an excess of X (reddish), b* < 0 for an excess of Z (bluish).
  EXPECT_GT(xyzToLab({0.6, 0.5, 0.5}, white).y, 0.0);
  EXPECT_LT(xyzToLab({0.5, 0.5, 0.8}, white).z, 0.0);
}

TEST(CieLab, ImageVersionsMatchThePixelFunctions) {
  const glm::dvec3 white(0.95047, 1.0, 1.08883);
  Image xyz(2, 1, {"X", "Y", "Z"});
  xyz.pixels = {0.2f, 0.3f, 0.1f, 0.5f, 0.4f, 0.6f};
  const Image lab = xyzToLab(xyz, white);
  ASSERT_EQ(lab.channels, (std::vector<std::string>{"L", "a", "b"}));
  const glm::dvec3 expected = xyzToLab(glm::dvec3(0.5f, 0.4f, 0.6f), white);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(lab.at(1, 0, c), expected[c], 1e-4);
  Image other = lab;
  other.at(0, 0, 0) += 2.0f;
  const Image de = deltaE2000(lab, other);
  ASSERT_EQ(de.channelCount(), 1);
  EXPECT_GT(de.at(0, 0, 0), 0.5f);
  EXPECT_EQ(de.at(1, 0, 0), 0.0f);
  EXPECT_THROW(xyzToLab(Image(1, 1, {"Y"}), white), InputError);
  EXPECT_THROW(deltaE2000(lab, Image(1, 1, {"L", "a", "b"})), InputError);
}

}  // namespace
}  // namespace camsim
