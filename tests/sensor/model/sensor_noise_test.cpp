// Tests for sensor/model/sensor_noise: the gain-dependent noise parameters (K(ISO), dual
// conversion gain, iso_table, ELD's fits), the Tukey-λ helpers, what expose() draws from
// them (moments against the closed forms written here), the parser's errors, and the ELD
// presets against ELD's published numbers (copied here from eld_camera_params.json).
// Fixed seeds; statistical tolerances are ≥ 5 standard errors unless stated.
#include "sensor/model/sensor_noise.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"
#include "sensor/model/sensor_model.h"
#include "sensor/model/sensor_spec.h"
#include "tests/support/lut_paths.h"

namespace camsim::sensor_noise_test {
namespace {

// A 14-bit RGGB sensor (K = 0.5 DN/e⁻ at ISO 100); tests append noise keys.
const std::string kBase =
    "name: test\n"
    "pixel_pitch_um: 4.0\n"
    "cfa: RGGB\n"
    "qe: {curves: cameras/nikon_d850.csv, peak_qe: 0.5}\n"
    "full_well_e: 40000\n"
    "conversion_gain_e_per_dn: 2.0\n"
    "base_iso: 100\n"
    "adc_bits: 14\n"
    "black_level_dn: 512\n";
const std::string kRead = "read_noise_e: 3.0\n";  // σ_pre

SensorSpec parse(const std::string& extra) {
  return parseSensorSpec(kBase + extra, "sensor.yaml", ".", test::kLuts);
}

struct Moments {
  double mean = 0.0, variance = 0.0;
};
Moments moments(const std::vector<double>& v) {
  double sum = 0.0, sum2 = 0.0;
  for (double x : v) sum += x;
  const double mean = sum / static_cast<double>(v.size());
  for (double x : v) sum2 += (x - mean) * (x - mean);
  return {mean, sum2 / static_cast<double>(v.size() - 1)};
}

// The DN of a flat exposure, as doubles.
std::vector<double> flatDn(const SensorSpec& s, double electrons, double iso, int w, int h,
                           std::uint64_t seed = 7, std::uint64_t frame = 0) {
  Image e(w, h, {"electrons"});
  for (float& v : e.pixels) v = static_cast<float>(electrons);
  const RawImage raw = expose(e, s, ExposureSettings{0.01, iso}, NoiseMode::kFull, seed, frame);
  return {raw.dn.begin(), raw.dn.end()};
}

TEST(SensorNoise, LinearModelWithoutNewKeys) {
  const SensorSpec s = parse(kRead);
  for (double iso : {50.0, 100.0, 800.0, 25600.0}) {
    const NoiseAtIso n = noiseAtIso(s, iso);
    EXPECT_DOUBLE_EQ(n.systemGainK, iso / 100.0 / 2.0);
    EXPECT_EQ(n.readPreE, 3.0);
    EXPECT_EQ(n.readPostDn, 0.0);
    EXPECT_FALSE(n.highConversionGain);
    EXPECT_EQ(n.fullWellE, 40000.0);
  }
  EXPECT_EQ(modelledNoiseTerms(s, 100.0), (std::vector<std::string>{"shot", "read_pre"}));
  EXPECT_THROW(noiseAtIso(s, 0.0), InputError);
  EXPECT_THROW(noiseAtIso(s, NAN), InputError);
}

TEST(SensorNoise, DualConversionGainSwitchesAtItsIso) {
  const SensorSpec s =
      parse(kRead +
            "read_noise_post_dn: 1.5\n"
            "dual_conversion_gain: {iso: 800, conversion_gain_e_per_dn: 0.5, read_noise_e: 1.2, "
            "full_well_e: 9000}\n");
  const NoiseAtIso low = noiseAtIso(s, 799.0), high = noiseAtIso(s, 800.0),
                   higher = noiseAtIso(s, 3200.0);
  EXPECT_DOUBLE_EQ(low.systemGainK, 7.99 / 2.0);
  EXPECT_EQ(low.readPreE, 3.0);
  EXPECT_EQ(low.fullWellE, 40000.0);
  EXPECT_TRUE(high.highConversionGain);
  EXPECT_DOUBLE_EQ(high.systemGainK, 2.0);  // 1 / 0.5 e⁻/DN at the switch
  EXPECT_DOUBLE_EQ(higher.systemGainK, 8.0);
  EXPECT_EQ(high.readPreE, 1.2);
  EXPECT_EQ(high.fullWellE, 9000.0);
  EXPECT_EQ(high.readPostDn, 1.5);
  EXPECT_DOUBLE_EQ(s.saturationElectrons(3200.0), std::min(9000.0, (16383.0 - 512.0) / 8.0));
  const auto terms = modelledNoiseTerms(s, 800.0);
  EXPECT_NE(std::find(terms.begin(), terms.end(), "dual_conversion_gain"), terms.end());
}

TEST(SensorNoise, IsoTableInterpolatesInLogIsoAndRefusesOutsideIt) {
  const SensorSpec s =
      parse(kRead +
            "iso_table:\n"
            "  - {iso: 100, system_gain_dn_per_e: 0.5, read_noise_post_dn: 2, tukey_lambda: 0.1,"
            " black_offsets_dn: [0, 1, 2, 3]}\n"
            "  - {iso: 400, system_gain_dn_per_e: 2.2, read_noise_post_dn: 8, tukey_lambda: -0.1,"
            " black_offsets_dn: [4, 5, 6, 7]}\n");
  const NoiseAtIso mid = noiseAtIso(s, 200.0);  // half-way in log ISO
  EXPECT_NEAR(mid.systemGainK, std::sqrt(0.5 * 2.2), 1e-12);
  EXPECT_NEAR(mid.readPostDn, 4.0, 1e-12);
  EXPECT_NEAR(mid.tukeyLambda, 0.0, 1e-12);
  EXPECT_EQ(mid.blackOffsetsDn, (std::vector<double>{2, 3, 4, 5}));
  EXPECT_EQ(mid.readPreE, 3.0);  // no column: the parametric value
  EXPECT_DOUBLE_EQ(noiseAtIso(s, 400.0).systemGainK, 2.2);
  try {
    noiseAtIso(s, 401.0);
    FAIL() << "accepted an ISO above the table";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "iso");
    EXPECT_NE(std::string(e.what()).find("100 to 400"), std::string::npos) << e.what();
  }
  EXPECT_THROW(noiseAtIso(s, 99.0), InputError);
  EXPECT_EQ(isoRange(s).min, 100.0);
  EXPECT_EQ(isoRange(s).max, 400.0);
}

TEST(SensorNoise, TukeyLambdaQuantileAndVariance) {
  // λ = 1: uniform on [−1, 1] (variance 1/3); λ = 0: logistic (π²/3); λ = 0.5: the
  // integral of Q(u)² over (0, 1) by the midpoint rule.
  EXPECT_NEAR(tukeyQuantile(1.0, 0.8), 0.6, 1e-12);
  EXPECT_NEAR(tukeyQuantile(0.0, 0.75), std::log(3.0), 1e-12);
  EXPECT_NEAR(tukeyVarianceFactor(1.0), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(tukeyVarianceFactor(0.0), std::numbers::pi * std::numbers::pi / 3.0, 1e-12);
  for (double lambda : {0.5, 0.14, -0.1}) {
    const int n = 2000000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double q = tukeyQuantile(lambda, (i + 0.5) / n);
      sum += q * q;
    }
    EXPECT_NEAR(tukeyVarianceFactor(lambda), sum / n, 2e-3 * sum / n) << lambda;
  }
}

TEST(SensorNoise, ExposeDrawsTheConfiguredVarianceAtEachIso) {
  // σ_y² = K²(σ_pre² + μ_e) + σ_post² at three ISOs, and the black offsets' means per tile
  // position. 256² photosites: the variance's standard error is √(2/N) ≈ 0.55 %.
  const SensorSpec s = parse(kRead +
                             "read_noise_post_dn: 2.5\n"
                             "black_offsets_dn: [0.5, -1.5, 2.0, 0]\n");
  for (double iso : {100.0, 400.0, 1600.0}) {
    const double k = iso / 100.0 / 2.0, mu = 500.0;
    const std::vector<double> dn = flatDn(s, mu, iso, 256, 256);
    const double expected = k * k * (9.0 + mu) + 2.5 * 2.5 + 1.0 / 12.0;  // + quantisation
    const VarianceLine line = temporalVarianceLine(s, ExposureSettings{0.01, iso});
    EXPECT_DOUBLE_EQ(line.slopeDn, k);
    EXPECT_DOUBLE_EQ(line.offsetDn2, k * k * 9.0 + 6.25);
    // Per tile position (the offsets differ): pool the four after removing their means.
    std::vector<std::vector<double>> pos(4);
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x)
        pos[static_cast<size_t>((y % 2) * 2 + x % 2)].push_back(
            dn[static_cast<size_t>(y * 256 + x)]);
    const double offsets[4] = {0.5, -1.5, 2.0, 0.0};
    double var = 0.0;
    for (int p = 0; p < 4; ++p) {
      const Moments m = moments(pos[static_cast<size_t>(p)]);
      const double se = std::sqrt(m.variance / static_cast<double>(pos[0].size()));
      EXPECT_NEAR(m.mean, 512.0 + k * mu + offsets[p], 5.0 * se) << "iso " << iso << " pos " << p;
      var += m.variance / 4.0;
    }
    EXPECT_NEAR(var, expected, 5.0 * std::sqrt(2.0 / 65536.0) * expected) << "iso " << iso;
  }
}

TEST(SensorNoise, TukeyReadNoiseHasItsVariance) {
  const SensorSpec s = parse(
      "read_noise_e: 0\n"
      "read_noise_shape: tukey_lambda\n"
      "tukey_lambda: 0.05\n"
      "noise_fits: {tukey_scale_dn: {slope: 0, bias: 1.0}}\n");  // scale e¹ DN at every K
  const NoiseAtIso n = noiseAtIso(s, 100.0);
  EXPECT_NEAR(n.tukeyScaleDn, std::exp(1.0), 1e-12);
  const std::vector<double> dn = flatDn(s, 0.0, 100.0, 512, 512);
  const double expected = std::exp(2.0) * tukeyVarianceFactor(0.05) + 1.0 / 12.0;
  // Heavier tails than a Gaussian: a looser 3 % bound (the kurtosis of TL(0.05) is ≈ 4.9).
  EXPECT_NEAR(moments(dn).variance, expected, 0.03 * expected);
  EXPECT_EQ(modelledNoiseTerms(s, 100.0), (std::vector<std::string>{"shot", "read_tukey_lambda"}));
}

TEST(SensorNoise, HotAndStuckPhotositesAreFixedAndHaveTheirFraction) {
  const SensorSpec s = parse(
      "read_noise_e: 0\n"
      "temperature_c: 31\n"  // one doubling above the 25 °C reference (6 °C)
      "hot_pixels: {fraction: 0.01, dark_current_e_per_s: 50000}\n"
      "stuck_pixels: {fraction: 0.002, value_dn: 16383}\n");
  const int w = 512, h = 256, n = w * h;
  const std::vector<double> a = flatDn(s, 0.0, 100.0, w, h, 1, 0);
  const std::vector<double> b = flatDn(s, 0.0, 100.0, w, h, 2, 5);
  int hot = 0, stuck = 0, same = 0;
  for (int i = 0; i < n; ++i) {
    const auto u = static_cast<size_t>(i);
    if (a[u] == 16383.0) ++stuck, same += b[u] == 16383.0;
    // A hot photosite: 50000 e⁻/s · 2 · 0.01 s = 1000 e⁻ = 500 DN above the black level.
    else if (a[u] > 512.0 + 300.0)
      ++hot, same += b[u] > 512.0 + 300.0;
  }
  // Binomial counts: 5 standard errors.
  EXPECT_NEAR(hot, 0.01 * 0.998 * n, 5.0 * std::sqrt(0.01 * n));
  EXPECT_NEAR(stuck, 0.002 * n, 5.0 * std::sqrt(0.002 * n));
  EXPECT_EQ(same, hot + stuck);  // the same photosites in another frame and noise seed
}

TEST(SensorNoise, MalformedKeysAreRejectedWithTheirKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"black_offsets_dn: [1, 2, 3]\n", "black_offsets_dn"},
      {"iso_table: [{iso: 200}, {iso: 100}]\n", "iso_table[1]"},
      {"iso_table: [{iso: 200}, {iso: 400}]\n", "iso_table"},  // base ISO 100 outside
      {"iso_table: []\n", "iso_table"},
      {"iso_table: [{iso: 100, gain: 2}]\n", "iso_table[0].gain"},
      {"read_noise_shape: tukey_lambda\n", "read_noise_shape"},  // no scale
      {"read_noise_shape: cauchy\n", "read_noise_shape"},
      {"tukey_lambda: -0.6\n", "tukey_lambda"},
      {"dual_conversion_gain: {iso: 50, conversion_gain_e_per_dn: 1, read_noise_e: 1}\n",
       "dual_conversion_gain.iso"},
      {"dual_conversion_gain: {iso: 800, read_noise_e: 1}\n",
       "dual_conversion_gain.conversion_gain_e_per_dn"},
      {"noise_fits: {read_noise_dn: {slope: 0.5}}\n", "noise_fits.read_noise_dn.bias"},
      {"noise_fits: {read_noise_dn: {slope: 0.5, bias: 1, sigma: -1}}\n",
       "noise_fits.read_noise_dn.sigma"},
      {"hot_pixels: {fraction: 2, dark_current_e_per_s: 1}\n", "hot_pixels.fraction"},
      {"stuck_pixels: {fraction: 0.1, value_dn: 70000}\n", "stuck_pixels.value_dn"},
      {"row_noise_dn: -1\n", "row_noise_dn"},
      {"dark_frames: /nonexistent/camsim/darks\n", "dark_frames"},
  };
  for (const auto& [extra, key] : cases) {
    try {
      parse(extra);
      ADD_FAILURE() << "accepted: " << extra;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), key) << extra << e.what();
      EXPECT_EQ(e.where().file, "sensor.yaml") << extra;
      EXPECT_GT(e.where().line, 0) << extra << e.what();
    }
  }
}

// A fit's sigma (ELD's residual spread) is documented as read and ignored: it was refused,
// "not allowed together with the keys given here" (found by probing).
TEST(SensorNoiseSpec, AFitsSigmaIsReadAndIgnored) {
  EXPECT_NO_THROW(parse("noise_fits: {read_noise_dn: {slope: 0.54, bias: 1.2, sigma: 0.1}}\n"));
}

// ELD's published numbers (eld_camera_params.json, Profile-1): K_min, and the fits
// ln σ = slope · ln K + bias for g_scale, G_scale and R_scale, and the first and last
// G_shape and color_bias rows.
struct Published {
  const char* preset;
  double kMin;
  double g[2], tukey[2], row[2];
  double firstLambda, lastLambda;
  double firstBias[4];  // R, G1, B, G2 (ELD's order)
};

TEST(SensorNoise, EldPresetsCarryThePublishedCalibration) {
  const Published cameras[] = {
      {"eld-canon-5d4",
       0.2181895124454343,
       {0.6771267783987617, 1.5121876510805845},
       {0.6558756156508007, 1.09268679594838},
       {0.4712797750747537, -0.8078958947116487},
       0.15714285714285714,
       0.11428571428571421,
       {0.0319037064909935, 0.7472504377365112, 0.7182117104530334, -0.030375981703400612}},
      {"eld-nikon-d850",
       0.4150393264348262,
       {0.5634612649498357, 0.799410107756515},
       {0.4773896839219417, -0.09044499670414502},
       {0.44829219631519307, -1.7977103277112132},
       0.0,
       0.0,
       {0, 0, 0, 0}},
      {"eld-sony-a7s2",
       0.09391607086816033,
       {0.5407496082896145, 1.218237123334061},
       {0.46210495986526035, 0.5657147358616816},
       {0.5275360468633209, -0.5917002648887661},
       0.114286,
       -0.142857,
       {1.4821642637252808, 1.468152403831482, 1.4833444356918335, 1.4700759649276733}},
  };
  for (const Published& p : cameras) {
    SCOPED_TRACE(p.preset);
    const SensorSpec s = loadSensorSpec(p.preset, test::kLuts);
    EXPECT_EQ(isoRange(s).min, 100.0);
    EXPECT_EQ(isoRange(s).max, 6400.0);
    for (double iso : {100.0, 800.0, 6400.0}) {
      const NoiseAtIso n = noiseAtIso(s, iso);
      const double k = p.kMin * iso / 100.0;
      EXPECT_NEAR(n.systemGainK, k, 1e-12 * k);
      const auto at = [k](const double* f) { return std::exp(f[0] * std::log(k) + f[1]); };
      EXPECT_NEAR(n.readPostDn, at(p.g), 1e-9 * at(p.g));
      EXPECT_NEAR(n.tukeyScaleDn, at(p.tukey), 1e-9 * at(p.tukey));
      EXPECT_NEAR(n.rowNoiseDn, at(p.row), 1e-9 * at(p.row));
      EXPECT_EQ(n.readPreE, 0.0);
      EXPECT_EQ(n.shape, ReadNoiseShape::kTukeyLambda);
    }
    if (p.firstBias[0] != 0.0) {  // the D850's values are not repeated here
      const NoiseAtIso first = noiseAtIso(s, 100.0), last = noiseAtIso(s, 6400.0);
      EXPECT_NEAR(first.tukeyLambda, p.firstLambda, 1e-5);
      EXPECT_NEAR(last.tukeyLambda, p.lastLambda, 1e-5);
      // Tile order R, G1, G2, B from ELD's R, G1, B, G2.
      const double tile[4] = {p.firstBias[0], p.firstBias[1], p.firstBias[3], p.firstBias[2]};
      for (int i = 0; i < 4; ++i)
        EXPECT_NEAR(first.blackOffsetsDn[static_cast<size_t>(i)], tile[i], 1e-5) << i;
    }
    EXPECT_THROW(noiseAtIso(s, 12800.0), InputError);
  }
}

}  // namespace
}  // namespace camsim::sensor_noise_test
