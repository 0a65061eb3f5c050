// Tests for sensor/isp_black_level: (DN − black)/(white − black), clipped photosites at ≥ 1,
// values below black kept, channel naming, stacked planes and bad input.
#include "sensor/isp/isp_black_level.h"

#include <cstdint>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"
#include "sensor/model/sensor_model.h"
#include "sensor/model/sensor_spec.h"

namespace camsim {
namespace {

RawImage rawOf(const std::vector<std::uint16_t>& dn, int width, const CfaLayout& cfa, double black,
               double white) {
  RawImage raw;
  raw.width = width;
  raw.height = static_cast<int>(dn.size()) / width;
  raw.dn = dn;
  raw.cfa = cfa;
  raw.blackLevelDn = black;
  raw.whiteLevelDn = white;
  return raw;
}

TEST(NormalizeRaw, MapsBlackToZeroWhiteToOneAndKeepsNegatives) {
  const RawImage raw =
      rawOf({400, 16383, 8191, 390, 0, 16382}, 3, CfaLayout::fromName("RGGB"), 400.0, 16383.0);
  const Image v = normalizeRaw(raw);
  ASSERT_EQ(v.width, 3);
  ASSERT_EQ(v.height, 2);
  ASSERT_EQ(v.channels, std::vector<std::string>{"CFA"});
  const double range = 16383.0 - 400.0;
  EXPECT_EQ(v.at(0, 0, 0), 0.0f);
  EXPECT_EQ(v.at(1, 0, 0), 1.0f);  // exactly the white level
  EXPECT_FLOAT_EQ(v.at(2, 0, 0), static_cast<float>((8191.0 - 400.0) / range));
  EXPECT_FLOAT_EQ(v.at(0, 1, 0), static_cast<float>(-10.0 / range));  // below black: kept
  EXPECT_FLOAT_EQ(v.at(1, 1, 0), static_cast<float>(-400.0 / range));
  EXPECT_TRUE(isClipped(v.at(1, 0, 0)));
  EXPECT_FALSE(isClipped(v.at(2, 1, 0)));  // one DN below white
  EXPECT_LT(v.at(2, 1, 0), 1.0f);
}

TEST(NormalizeRaw, SaturatedSensorOutputIsFlaggedAsClipped) {
  // The D850 preset: ADC and full well saturate together (50 000 e⁻ ≈ 15 983 DN · 3.13).
  // Photosites far above the full well must come out at exactly 1; a dark frame near 0.
  const SensorSpec d850 = loadSensorSpec("fullframe-d850", std::filesystem::path(CAMSIM_LUTS_DIR));
  Image electrons(16, 16, {"expected"});
  for (int x = 0; x < 16; ++x) electrons.at(x, 0, 0) = 2.0e5f;  // 4× the full well
  const RawImage raw = expose(electrons, d850, {}, NoiseMode::kFull, 7, 0);
  const Image v = normalizeRaw(raw);
  for (int x = 0; x < 16; ++x) EXPECT_TRUE(isClipped(v.at(x, 0, 0))) << x;
  double darkMean = 0.0;
  for (int y = 1; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      EXPECT_FALSE(isClipped(v.at(x, y, 0)));
      darkMean += static_cast<double>(v.at(x, y, 0)) / (15.0 * 16.0);
    }
  // Dark signal ≈ 0.3 e⁻/s · 2^(5/6) · 1/60 s ≈ 0.01 e⁻: the mean of 240 photosites with
  // 3 e⁻ read noise (σ/√240 ≈ 0.2 e⁻ = 4e-6 of the range) is 0 within 1e-4 of the range.
  EXPECT_NEAR(darkMean, 0.0, 1e-4);
}

TEST(NormalizeRaw, MonochromeChannelKeepsItsName) {
  const Image v = normalizeRaw(rawOf({0, 1023}, 2, CfaLayout::fromName("mono"), 64.0, 1023.0));
  EXPECT_EQ(v.channels, std::vector<std::string>{"Y"});
  EXPECT_FLOAT_EQ(v.at(0, 0, 0), static_cast<float>(-64.0 / 959.0));
  EXPECT_EQ(v.at(1, 0, 0), 1.0f);
}

TEST(NormalizeRaw, StackedPlanesBecomeOneImage) {
  const CfaLayout xyz = CfaLayout::fromName("xyz");
  const std::vector<RawImage> planes = {rawOf({0, 100}, 2, xyz, 0.0, 200.0),
                                        rawOf({50, 150}, 2, xyz, 0.0, 200.0),
                                        rawOf({200, 20}, 2, xyz, 0.0, 200.0)};
  const Image v = normalizeStackedRaw(planes);
  ASSERT_EQ(v.channels, (std::vector<std::string>{"X", "Y", "Z"}));
  EXPECT_EQ(v.at(0, 0, 0), 0.0f);
  EXPECT_EQ(v.at(1, 0, 0), 0.5f);
  EXPECT_EQ(v.at(0, 0, 1), 0.25f);
  EXPECT_EQ(v.at(1, 0, 1), 0.75f);
  EXPECT_EQ(v.at(0, 0, 2), 1.0f);
  EXPECT_EQ(v.at(1, 0, 2), 0.1f);
  EXPECT_THROW(normalizeStackedRaw({planes[0], planes[1]}), InputError);
}

TEST(NormalizeRaw, RejectsBadLevelsAndSizes) {
  const CfaLayout rggb = CfaLayout::fromName("RGGB");
  EXPECT_THROW(normalizeRaw(rawOf({1, 2}, 2, rggb, 100.0, 100.0)), InputError);
  RawImage bad = rawOf({1, 2}, 2, rggb, 0.0, 100.0);
  bad.height = 2;
  EXPECT_THROW(normalizeRaw(bad), InputError);
}

}  // namespace
}  // namespace camsim
