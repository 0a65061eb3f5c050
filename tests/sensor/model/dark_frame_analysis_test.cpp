// Tests for sensor/model/dark_frame_analysis.cpp on dark frames from expose(): the temporal
// row noise within 5 % of row_noise_dn (beside a fixed row pattern, row_fpn_e, that stays
// from frame to frame), and the Tukey-λ shape of an iso_table column recovered by the PPCC
// fit within 0.05. Fixed seeds; 256 × 256 monochrome photosites.
#include "sensor/model/dark_frame_analysis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include "sensor/base/image.h"
#include "sensor/model/sensor_model.h"
#include "sensor/model/sensor_noise.h"
#include "sensor/model/sensor_spec.h"

namespace camsim::dark_frame_analysis_test {
namespace {

constexpr int kSize = 256;

SensorSpec sensorFrom(const std::string& extra) {
  const std::string text =
      "name: test-dark\n"
      "pixel_pitch_um: 4.0\n"
      "cfa: mono\n"
      "qe: {csv: cameras/nikon_d850.csv, columns: [g], peak_qe: 0.5}\n"
      "full_well_e: 20000\n"
      "conversion_gain_e_per_dn: 1.0\n"
      "base_iso: 100\n"
      "adc_bits: 16\n"
      "black_level_dn: 2048\n"
      "dark_current_e_per_s: 0\n"
      "pattern_seed: 9\n" +
      extra;
  return parseSensorSpec(text, "test-dark.yaml", CAMSIM_LUTS_DIR, CAMSIM_LUTS_DIR);
}

std::vector<RawImage> darkFrames(const SensorSpec& s, int count, std::uint64_t seed) {
  const Image black(kSize, kSize, {"electrons"});
  std::vector<RawImage> frames;
  for (int f = 0; f < count; ++f)
    frames.push_back(
        expose(black, s, {0.01, s.baseIso}, NoiseMode::kFull, seed, static_cast<std::uint64_t>(f)));
  return frames;
}

std::vector<std::size_t> allPixels() {
  std::vector<std::size_t> p(static_cast<std::size_t>(kSize * kSize));
  std::iota(p.begin(), p.end(), std::size_t{0});
  return p;
}

std::vector<double> rowMeans(const RawImage& f) {
  std::vector<double> m(static_cast<std::size_t>(f.height), 0.0);
  for (int y = 0; y < f.height; ++y) {
    for (int x = 0; x < f.width; ++x) m[static_cast<std::size_t>(y)] += f.at(x, y);
    m[static_cast<std::size_t>(y)] /= f.width;
  }
  return m;
}

double rms(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s / static_cast<double>(a.size()));
}

TEST(DarkFrameAnalysis, TemporalRowNoiseApartFromTheFixedRowPattern) {
  // σ_row = 2 DN per row per frame; fixed row pattern 3 e⁻ (K = 1: 3 DN); pixel noise 2 e⁻ + 1 DN.
  const SensorSpec s = sensorFrom(
      "read_noise_e: 2.0\nread_noise_post_dn: 1.0\nrow_fpn_e: 3.0\n"
      "row_noise_dn: 2.0\n");
  const std::vector<RawImage> frames = darkFrames(s, 32, 21);
  const DarkFrameAnalysis a = analyseDarkFrames(frames, allPixels());
  EXPECT_NEAR(a.rowTemporalDn.value, 2.0, 0.05 * 2.0)
      << a.rowTemporalDn.value << " ± " << a.rowTemporalDn.uncertainty;
  EXPECT_NEAR(a.rowTemporalDn.value, 2.0, 4.0 * a.rowTemporalDn.uncertainty);
  std::printf("[ measured ] sigma_row %.4f +- %.4f DN, fixed row pattern %.4f +- %.4f DN\n",
              a.rowTemporalDn.value, a.rowTemporalDn.uncertainty, a.rowFixedDn.value,
              a.rowFixedDn.uncertainty);
  EXPECT_NEAR(a.rowFixedDn.value, 3.0, 0.15 * 3.0) << a.rowFixedDn.value;  // 256 rows: ±4.4 %
  EXPECT_NEAR(a.rowFixedDn.value, 3.0, 4.0 * a.rowFixedDn.uncertainty) << a.rowFixedDn.uncertainty;
  // Row means differ per frame by the temporal noise: rms difference √2·σ_row (+ pixel part).
  const double pixelPart = std::sqrt(2.0 * (4.0 + 1.0 + 1.0 / 12.0) / kSize);
  const double expected = std::sqrt(2.0 * 4.0 + pixelPart * pixelPart);
  EXPECT_NEAR(rms(rowMeans(frames[0]), rowMeans(frames[1])), expected, 0.15 * expected);
  // The fixed pattern stays: the same sensor without row noise has the same mean row
  // pattern, to the temporal noise left in 32 frames' means (σ_row/√32 ≈ 0.35 DN).
  const SensorSpec quiet =
      sensorFrom("read_noise_e: 2.0\nread_noise_post_dn: 1.0\nrow_fpn_e: 3.0\n");
  const std::vector<RawImage> quietFrames = darkFrames(quiet, 32, 22);
  std::vector<double> withNoise(kSize, 0.0), without(kSize, 0.0);
  for (int f = 0; f < 32; ++f) {
    const std::vector<double> a1 = rowMeans(frames[static_cast<std::size_t>(f)]);
    const std::vector<double> b1 = rowMeans(quietFrames[static_cast<std::size_t>(f)]);
    for (int y = 0; y < kSize; ++y) withNoise[y] += a1[y] / 32, without[y] += b1[y] / 32;
  }
  EXPECT_LT(rms(withNoise, without), 0.5) << rms(withNoise, without);
  EXPECT_GT(rms(withNoise, std::vector<double>(kSize, 2048.0)), 2.0);  // a pattern is there
  // Without row noise none is measured.
  const DarkFrameAnalysis q = analyseDarkFrames(quietFrames, allPixels());
  EXPECT_LT(q.rowTemporalDn.value, 0.15) << q.rowTemporalDn.value;
}

TEST(DarkFrameAnalysis, TukeyLambdaRecoveredByPpcc) {
  for (double lambda : {0.1, -0.05, 0.0}) {
    SCOPED_TRACE(lambda);
    // λ and the scale (8 DN) from the iso_table; no other read noise.
    const std::string row =
        "{iso: 100, tukey_lambda: " + std::to_string(lambda) + ", tukey_scale_dn: 8}";
    const SensorSpec s = sensorFrom(
        "read_noise_e: 0\nread_noise_shape: tukey_lambda\n"
        "iso_table: [" +
        row + "]\n");
    ASSERT_EQ(noiseAtIso(s, 100).shape, ReadNoiseShape::kTukeyLambda);
    const DarkFrameAnalysis a = analyseDarkFrames(darkFrames(s, 8, 31), allPixels());
    EXPECT_NEAR(a.tukeyLambda.value, lambda, 0.05)
        << a.tukeyLambda.value << " ± " << a.tukeyLambda.uncertainty;
    EXPECT_NEAR(a.tukeyScaleDn.value, 8.0, 0.08 * 8.0) << a.tukeyScaleDn.value;
    EXPECT_GT(a.tukeyCorrelation.value, 0.999);
    std::printf("[ measured ] lambda %.4f +- %.4f (configured %.2f), scale %.4f DN\n",
                a.tukeyLambda.value, a.tukeyLambda.uncertainty, lambda, a.tukeyScaleDn.value);
    EXPECT_GT(a.tukeyLambda.uncertainty, 0.0);
    // The normal plot's slope is close to the std (it is the std for a Gaussian).
    const double sd = 8.0 * std::sqrt(tukeyVarianceFactor(lambda));
    EXPECT_NEAR(a.readGaussianDn.value, sd, 0.1 * sd);
  }
}

TEST(DarkFrameAnalysis, GaussianReadNoiseHasTheNormalShape) {
  // Gaussian read noise: λ ≈ 0.14 (Tukey-λ's closest to the normal), σ_read = √(σ² + 1/12).
  const SensorSpec s = sensorFrom("read_noise_e: 6.0\n");
  const DarkFrameAnalysis a = analyseDarkFrames(darkFrames(s, 8, 41), allPixels());
  EXPECT_NEAR(a.tukeyLambda.value, 0.14, 0.03) << a.tukeyLambda.value;
  EXPECT_NEAR(a.readGaussianDn.value, std::sqrt(36.0 + 1.0 / 12.0), 0.02 * 6.0)
      << a.readGaussianDn.value;
  EXPECT_GT(a.normalCorrelation.value, 0.9995);
}

TEST(NormalQuantile, MatchesTheCdf) {
  for (double p : {1e-9, 1e-4, 0.025, 0.3, 0.5, 0.8, 0.975, 1 - 1e-6}) {
    const double x = normalQuantile(p);
    EXPECT_NEAR(0.5 * std::erfc(-x / std::sqrt(2.0)), p,
                1e-12 * std::max(1.0, p / (1 - p) > 1 ? 1.0 : 1.0))
        << p;
  }
  EXPECT_NEAR(normalQuantile(0.975), 1.959963984540054, 1e-9);
}

}  // namespace
}  // namespace camsim::dark_frame_analysis_test
