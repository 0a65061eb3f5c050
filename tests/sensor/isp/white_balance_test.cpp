// Tests for sensor/white_balance: illuminant gains from measured QE curves make a neutral
// surface neutral (spectrally and through the whole raw pipeline with noise), grey-region
// and grey-world estimates agree with them, clipped data are skipped, and gains land on the
// right photosites.
#include "sensor/isp/white_balance.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"
#include "sensor/isp/demosaic.h"
#include "sensor/isp/isp_black_level.h"
#include "sensor/model/sensor_model.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/spectral_data.h"
#include "tests/support/lut_paths.h"

namespace camsim {
namespace {

const SensorSpec& d850() {
  static const SensorSpec spec = loadSensorSpec("fullframe-d850", test::kLuts);
  return spec;
}

// A scene of flat spectral reflectances seen by the sensor: expected electrons per
// photosite, each photosite its CFA channel's response. reflectance(x, y) picks the patch.
template <typename F>
Image electronsOf(const SensorSpec& s, const Spectrum& illuminant, int w, int h, double scale,
                  F reflectance) {
  Image e(w, h, {"expected"});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::vector<double> c = cameraResponse(s.qe, reflectance(x, y), illuminant);
      e.at(x, y, 0) = static_cast<float>(scale * c[static_cast<size_t>(s.cfa.channelAt(x, y))]);
    }
  return e;
}

// Scale that puts a perfect white's G response at `fraction` of the saturation electrons.
double exposureScale(const SensorSpec& s, const Spectrum& illuminant, double fraction) {
  const double g = cameraResponse(s.qe, Spectrum::constant(1.0), illuminant)[1];
  return fraction * s.saturationElectrons(s.baseIso) / g;
}

TEST(WhiteBalanceFromIlluminant, FlatGreyBecomesExactlyNeutralUnderAAndF2) {
  const Spectrum grey = Spectrum::constant(0.18);
  for (const char* name : {"A", "F2", "D65"}) {
    const Spectrum ill = cieIlluminant(name);
    const std::vector<double> g = whiteBalanceFromIlluminant(d850(), ill);
    ASSERT_EQ(g.size(), 3u);
    EXPECT_EQ(g[1], 1.0) << name;
    const std::vector<double> c = cameraResponse(d850().qe, grey, ill);
    // Exact up to rounding: the gains are ratios of the same sums (1e-12 relative).
    EXPECT_NEAR(c[0] * g[0] / (c[1] * g[1]), 1.0, 1e-12) << name;
    EXPECT_NEAR(c[2] * g[2] / (c[1] * g[1]), 1.0, 1e-12) << name;
    std::printf("[ d850 gains %-3s ] R %.4f  G %.4f  B %.4f\n", name, g[0], g[1], g[2]);
  }
  // Tungsten is red-heavy: R needs less gain and B more than under D65.
  const auto a = whiteBalanceFromIlluminant(d850(), cieIlluminant("A"));
  const auto d65 = whiteBalanceFromIlluminant(d850(), cieIlluminant("D65"));
  EXPECT_LT(a[0], d65[0]);
  EXPECT_GT(a[2], d65[2]);
}

TEST(WhiteBalanceFromIlluminant, ColorCheckerGreysStayNearlyNeutral) {
  // Patches 20–23 (neutral 8 … 3.5) are not spectrally flat: after the white balance their
  // channel ratios differ from 1 by the chart's own tint: < 3 % (measured up to 2.7 %, R/G of
  // patch 23 under A; deterministic, no noise).
  const SpectralTable chart =
      readSpectralCsv(test::kLuts / "spectra/colorchecker_classic_reflectance.csv");
  for (const char* name : {"A", "F2"}) {
    const Spectrum ill = cieIlluminant(name);
    const std::vector<double> g = whiteBalanceFromIlluminant(d850(), ill);
    for (size_t p = 19; p <= 22; ++p) {
      const auto c = cameraResponse(d850().qe, chart.spectrum(p, Extrapolation::kClamp), ill);
      const double rg = c[0] * g[0] / c[1], bg = c[2] * g[2] / c[1];
      std::printf("[ %-3s patch %2zu ] R/G %.4f  B/G %.4f\n", name, p + 1, rg, bg);
      EXPECT_NEAR(rg, 1.0, 0.03) << name << " patch " << p + 1;
      EXPECT_NEAR(bg, 1.0, 0.03) << name << " patch " << p + 1;
    }
  }
}

TEST(WhiteBalanceFromIlluminant, IdealXyzSensorGainsAreTheWhitePointRatios) {
  const SensorSpec ideal = loadSensorSpec("ideal-xyz", test::kLuts);
  const Spectrum d65 = cieIlluminant("D65");
  const std::vector<double> g = whiteBalanceFromIlluminant(ideal, d65);
  const glm::dvec3 white = reflectanceToXyz(Spectrum::constant(1.0), d65);
  EXPECT_NEAR(g[0], 1.0 / white.x, 1e-6);  // reference channel Y
  EXPECT_EQ(g[1], 1.0);
  EXPECT_NEAR(g[2], 1.0 / white.z, 1e-6);
}

// The whole raw path with noise: grey card under A and F2 → expose (full noise, seed 11)
// → normalise → white balance on the mosaic → demosaic → the card's mean is neutral.
TEST(WhiteBalancePipeline, NoisyGreyCardIsNeutralAfterDemosaic) {
  const SensorSpec& s = d850();
  for (const char* name : {"A", "F2"}) {
    const Spectrum ill = cieIlluminant(name);
    const Spectrum grey = Spectrum::constant(0.5);
    const Image e =
        electronsOf(s, ill, 64, 64, exposureScale(s, ill, 0.8), [&](int, int) { return grey; });
    const RawImage raw = expose(e, s, {1.0 / 60.0, s.baseIso}, NoiseMode::kFull, 11, 0);
    const std::vector<double> gains = whiteBalanceFromIlluminant(s, ill);
    const Image rgb = demosaic(applyWhiteBalance(normalizeRaw(raw), s.cfa, gains), s.cfa,
                               DemosaicMethod::kMalvarHeCutler);
    double sum[3] = {0, 0, 0};
    for (int y = 4; y < 60; ++y)
      for (int x = 4; x < 60; ++x)
        for (int c = 0; c < 3; ++c) sum[c] += static_cast<double>(rgb.at(x, y, c));
    // 3136 pixels at ~20 000 e⁻ (shot noise 0.7 %, PRNU 0.5 %): the mean's ratio error is
    // ~4e-4 (1σ); the black level and quantisation add < 1e-4. Tolerance 0.3 %.
    EXPECT_NEAR(sum[0] / sum[1], 1.0, 3e-3) << name;
    EXPECT_NEAR(sum[2] / sum[1], 1.0, 3e-3) << name;
    std::printf("[ pipeline %-3s ] R/G %.5f  B/G %.5f\n", name, sum[0] / sum[1], sum[2] / sum[1]);
  }
}

TEST(WhiteBalanceEstimates, GreyRegionAndGreyWorldMatchTheIlluminantGains) {
  const SensorSpec& s = d850();
  const Spectrum ill = cieIlluminant("A");
  const SpectralTable chart =
      readSpectralCsv(test::kLuts / "spectra/colorchecker_classic_reflectance.csv");
  const Spectrum grey = Spectrum::constant(0.4);
  const Spectrum red = chart.spectrum(14, Extrapolation::kClamp);  // patch 15, red
  // Left half grey card, right half red patch (which would fool grey world).
  const Image e = electronsOf(s, ill, 64, 32, exposureScale(s, ill, 0.9),
                              [&](int x, int) { return x < 32 ? grey : red; });
  const RawImage raw = expose(e, s, {1.0 / 60.0, s.baseIso}, NoiseMode::kFull, 5, 0);
  const Image mosaic = normalizeRaw(raw);
  const std::vector<double> truth = whiteBalanceFromIlluminant(s, ill);
  // 0.5 % tolerance: ~500 photosites per channel at ≥ 10 000 e⁻ (noise ~1e-3 relative).
  const PixelRegion left{1, 0, 30, 32};  // starts off the tile grid: whole tiles only
  const auto fromMosaic = whiteBalanceFromRegion(mosaic, s.cfa, left);
  const Image rgb = demosaic(mosaic, s.cfa, DemosaicMethod::kBilinear);
  const auto fromRgb = whiteBalanceFromRegion(rgb, {2, 2, 26, 28});
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(fromMosaic[static_cast<size_t>(k)] / truth[static_cast<size_t>(k)], 1.0, 5e-3) << k;
    EXPECT_NEAR(fromRgb[static_cast<size_t>(k)] / truth[static_cast<size_t>(k)], 1.0, 5e-3) << k;
  }
  // Grey world over the grey half only is right; over the whole frame the red patch pulls
  // R's gain down by far more than the tolerance.
  Image greyHalf(32, 32, {"CFA"});
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) greyHalf.at(x, y, 0) = mosaic.at(x, y, 0);
  const auto world = whiteBalanceGreyWorld(greyHalf, s.cfa);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(world[static_cast<size_t>(k)] / truth[static_cast<size_t>(k)], 1.0, 5e-3) << k;
  EXPECT_LT(whiteBalanceGreyWorld(mosaic, s.cfa)[0], 0.9 * truth[0]);
  EXPECT_NEAR(whiteBalanceGreyWorld(rgb)[0], whiteBalanceGreyWorld(mosaic, s.cfa)[0],
              0.01 * truth[0]);
}

TEST(WhiteBalanceEstimates, ClippedTilesAreSkipped) {
  const CfaLayout cfa = CfaLayout::fromName("GRBG");
  Image m(4, 2, {"CFA"});
  // Tile 1 (x 0–1): G 0.5, R 0.25, B 0.125, G 0.5. Tile 2 (x 2–3): clipped R.
  const float tile1[2][2] = {{0.5f, 0.25f}, {0.125f, 0.5f}};
  const float tile2[2][2] = {{0.9f, 1.0f}, {0.1f, 0.9f}};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      m.at(x, y, 0) = tile1[y][x];
      m.at(x + 2, y, 0) = tile2[y][x];
    }
  const auto g = whiteBalanceGreyWorld(m, cfa);  // cfa.channels = R, G, B
  EXPECT_DOUBLE_EQ(g[0], 2.0);
  EXPECT_DOUBLE_EQ(g[1], 1.0);
  EXPECT_DOUBLE_EQ(g[2], 4.0);
  // With a higher clip level both tiles count.
  const auto all = whiteBalanceGreyWorld(m, cfa, 2.0);
  EXPECT_NEAR(all[0], 0.7 / 0.625, 1e-6);  // G mean 0.7, R mean (0.25 + 1) / 2
  EXPECT_THROW(whiteBalanceFromRegion(m, cfa, {2, 0, 2, 2}), InputError);  // only clipped
  EXPECT_THROW(whiteBalanceFromRegion(m, cfa, {1, 0, 2, 2}), InputError);  // no whole tile
  EXPECT_THROW(whiteBalanceFromRegion(m, cfa, {3, 0, 2, 2}), InputError);  // outside
  // x + width past INT_MAX wrapped negative and passed the check: reads outside the image
  // (found by probing Python's develop(): a segfault).
  const int big = std::numeric_limits<int>::max();
  for (const PixelRegion r : {PixelRegion{big, 0, 2, 2}, PixelRegion{big - 1, big - 1, big, big}})
    try {
      (void)whiteBalanceFromRegion(m, cfa, r);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_NE(e.message().find("is empty or outside the 4 × 2 image"), std::string::npos)
          << e.what();
    }
}

TEST(ApplyWhiteBalance, GainsLandOnTheirCfaChannels) {
  for (const char* name : {"RGGB", "BGGR", "GRBG", "GBRG"}) {
    const CfaLayout cfa = CfaLayout::fromName(name);
    Image m(4, 4, {"CFA"});
    for (float& v : m.pixels) v = 0.5f;
    const Image out = applyWhiteBalance(m, cfa, {2.0, 1.0, 3.0});
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        const float expected = 0.5f * (cfa.channelAt(x, y) == 0   ? 2.0f
                                       : cfa.channelAt(x, y) == 2 ? 3.0f
                                                                  : 1.0f);
        EXPECT_EQ(out.at(x, y, 0), expected) << name << " " << x << "," << y;
      }
    EXPECT_THROW(applyWhiteBalance(m, cfa, {1.0, 1.0}), InputError);
  }
  Image rgb(1, 1, {"R", "G", "B"});
  rgb.pixels = {0.1f, 0.2f, 0.3f};
  const Image out = applyWhiteBalance(rgb, {2.0, 1.0, 0.5});
  EXPECT_FLOAT_EQ(out.at(0, 0, 0), 0.2f);
  EXPECT_FLOAT_EQ(out.at(0, 0, 1), 0.2f);
  EXPECT_FLOAT_EQ(out.at(0, 0, 2), 0.15f);
  EXPECT_THROW(gainsFromWhite({1.0, 0.0, 1.0}, 1), InputError);
}

}  // namespace
}  // namespace camsim
