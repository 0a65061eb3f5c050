// Tests for dark frames as the noise source (sensor/model/dark_frames.h,
// sensor/io/dark_frame_reader.h): frames written as DNG and raw EXR by camsim's own
// writers are read back exactly; injected into expose() they give the source frames'
// per-pixel mean and variance and row spectrum, plus the photo-electrons' shot noise; bad
// sets are refused naming the file. Fixed seeds; tolerances stated per check.
#include "sensor/io/dark_frame_reader.h"

#include <cmath>
#include <fstream>
#include <numbers>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"
#include "sensor/io/dng_writer.h"
#include "sensor/io/exr_io.h"
#include "sensor/model/sensor_model.h"
#include "tests/support/temp_dir.h"

namespace camsim::dark_frame_reader_test {
namespace {

constexpr int kW = 96, kH = 64, kSources = 12;

// A mono 12-bit sensor whose dark frames have structure: row noise (temporal), a fixed
// column pattern, DSNU, Gaussian read noise and hot pixels.
SensorSpec sourceSensor() {
  SensorSpec s;
  s.name = "dark-source";
  s.fullWellE = 20000.0;
  s.conversionGainEPerDn = 2.0;  // K = 0.5 DN/e⁻ at ISO 100
  s.readNoiseE = 2.0;
  s.adcBits = 12;
  s.blackLevelDn = 256.0;
  s.columnFpnE = 3.0;
  s.dsnuE = 1.0;
  s.noise.readNoisePostDn = 1.5;
  s.noise.rowNoiseDn = 2.0;
  s.noise.hotPixelFraction = 0.01;
  s.noise.hotPixelDarkCurrentEPerS = 2000.0;
  return s;
}

Image flat(double electrons) {
  Image e(kW, kH, {"electrons"});
  for (float& v : e.pixels) v = static_cast<float>(electrons);
  return e;
}

// Writes kSources dark frames, half as DNG, half as raw EXR; returns them.
std::vector<RawImage> writeSources(const std::filesystem::path& dir) {
  const SensorSpec s = sourceSensor();
  std::vector<RawImage> frames;
  for (int f = 0; f < kSources; ++f) {
    RawImage raw = expose(flat(0.0), s, ExposureSettings{0.1, 100.0}, NoiseMode::kFull, 99,
                          static_cast<std::uint64_t>(f));
    char name[32];
    std::snprintf(name, sizeof name, "dark_%02d", f);
    if (f % 2 == 0)
      writeDng(dir / (std::string(name) + ".dng"), raw, DngColor{}, {});
    else
      writeRawExr(dir / (std::string(name) + ".exr"), raw, flat(0.0), {});
    frames.push_back(std::move(raw));
  }
  return frames;
}

struct PixelStats {
  std::vector<double> mean, variance;
};
PixelStats pixelStats(const std::vector<std::vector<std::uint16_t>>& frames, double minus = 0.0) {
  const size_t n = frames.front().size();
  PixelStats p{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
  for (const auto& f : frames)
    for (size_t i = 0; i < n; ++i) p.mean[i] += (f[i] - minus) / static_cast<double>(frames.size());
  for (const auto& f : frames)
    for (size_t i = 0; i < n; ++i)
      p.variance[i] +=
          std::pow(f[i] - minus - p.mean[i], 2) / static_cast<double>(frames.size() - 1);
  return p;
}

// Mean periodogram of the row means (frequencies 1 … kH/2), over the frames.
std::vector<double> rowSpectrum(const std::vector<std::vector<std::uint16_t>>& frames) {
  std::vector<double> power(kH / 2, 0.0);
  for (const auto& f : frames) {
    std::vector<double> rows(kH, 0.0);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x)
        rows[static_cast<size_t>(y)] += f[static_cast<size_t>(y * kW + x)] / double(kW);
    for (int k = 1; k <= kH / 2; ++k) {
      double re = 0.0, im = 0.0;
      for (int y = 0; y < kH; ++y) {
        const double a = 2.0 * std::numbers::pi * k * y / kH;
        re += rows[static_cast<size_t>(y)] * std::cos(a);
        im += rows[static_cast<size_t>(y)] * std::sin(a);
      }
      power[static_cast<size_t>(k - 1)] +=
          (re * re + im * im) / kH / static_cast<double>(frames.size());
    }
  }
  return power;
}

TEST(DarkFrames, ReadBackExactlyFromDngAndRawExr) {
  test::TempDir dir;
  const std::vector<RawImage> sources = writeSources(dir.path());
  const DarkFrameSet set = loadDarkFrames(dir.path(), sourceSensor());
  ASSERT_EQ(set.frames.size(), static_cast<size_t>(kSources));
  EXPECT_EQ(set.width, kW);
  EXPECT_EQ(set.height, kH);
  EXPECT_EQ(set.blackLevelDn, 256.0);
  for (int f = 0; f < kSources; ++f) {  // sorted by name: dark_00 … dark_11
    EXPECT_EQ(set.frames[static_cast<size_t>(f)], sources[static_cast<size_t>(f)].dn) << f;
  }
  EXPECT_EQ(set.names.front(), "dark_00.dng");
  EXPECT_EQ(set.names[1], "dark_01.exr");
}

TEST(DarkFrames, InjectedNoiseHasTheSourceFramesStatistics) {
  test::TempDir dir;
  writeSources(dir.path());
  SensorSpec target = sourceSensor();
  const DarkFrameSet set = loadDarkFrames(dir.path(), target);
  // Parametric terms that must NOT be drawn with dark frames: a huge read noise.
  target.readNoiseE = 500.0;
  const ExposureSettings settings{0.1, 100.0, &set};
  const PixelStats source = pixelStats(set.frames);
  const std::vector<double> sourceSpectrum = rowSpectrum(set.frames);

  // Dark: every output is one of the source frames, and all of them are used.
  constexpr int kOutputs = 240;
  std::vector<std::vector<std::uint16_t>> dark;
  std::set<size_t> used;
  for (int f = 0; f < kOutputs; ++f) {
    RawImage raw =
        expose(flat(0.0), target, settings, NoiseMode::kFull, 5, static_cast<std::uint64_t>(f));
    bool found = false;
    for (size_t j = 0; j < set.frames.size() && !found; ++j)
      if (set.frames[j] == raw.dn) found = true, used.insert(j);
    EXPECT_TRUE(found) << "output " << f << " is not one of the dark frames";
    dark.push_back(std::move(raw.dn));
  }
  EXPECT_EQ(used.size(), set.frames.size());
  // Its per-pixel mean and variance are the source set's: resampling 12 frames, the means
  // lie within 5 standard errors of a mean of 240 draws, and the variance (averaged over
  // the image) is the set's population variance, 11/12 of its unbiased one, within 3 %.
  const PixelStats out = pixelStats(dark);
  double meanDev = 0.0, varOut = 0.0, varSource = 0.0;
  for (size_t i = 0; i < out.mean.size(); ++i) {
    meanDev = std::max(meanDev, std::abs(out.mean[i] - source.mean[i]) /
                                    std::sqrt(source.variance[i] / kOutputs + 1e-12));
    varOut += out.variance[i];
    varSource += source.variance[i];
  }
  EXPECT_LT(meanDev, 5.0);
  EXPECT_NEAR(varOut / varSource, 11.0 / 12.0, 0.03);
  const std::vector<double> outSpectrum = rowSpectrum(dark);
  double low = 0.0, lowSource = 0.0, high = 0.0, highSource = 0.0;
  for (size_t k = 0; k < outSpectrum.size(); ++k) {
    (k < outSpectrum.size() / 2 ? low : high) += outSpectrum[k];
    (k < outSpectrum.size() / 2 ? lowSource : highSource) += sourceSpectrum[k];
  }
  EXPECT_NEAR(low / lowSource, 1.0, 0.10);
  EXPECT_NEAR(high / highSource, 1.0, 0.10);

  // Lit: mean + K·μ and variance + K²·μ (shot noise of μ = 400 e⁻ at K = 0.5 DN/e⁻). The
  // same (seed, frame) adds the same dark frame, so the difference is K·n rounded half up:
  // an odd n gains ½ DN, so the mean shift is K·μ + ¼.
  std::vector<std::vector<std::uint16_t>> lit;
  for (int f = 0; f < kOutputs; ++f)
    lit.push_back(
        expose(flat(400.0), target, settings, NoiseMode::kFull, 5, static_cast<std::uint64_t>(f))
            .dn);
  const PixelStats litStats = pixelStats(lit);
  double meanShift = 0.0, varShift = 0.0;
  for (size_t i = 0; i < litStats.mean.size(); ++i) {
    meanShift += (litStats.mean[i] - out.mean[i]) / static_cast<double>(litStats.mean.size());
    varShift +=
        (litStats.variance[i] - out.variance[i]) / static_cast<double>(litStats.mean.size());
  }
  EXPECT_NEAR(meanShift, 0.5 * 400.0 + 0.25, 0.05);  // 6144 px × 240 frames: SE ≈ 0.01 DN
  EXPECT_NEAR(varShift, 0.25 * 400.0, 5.0);          // SE of the mean variance ≈ 0.6 DN²
}

TEST(DarkFrames, BadSetsAreRefusedNamingTheFile) {
  test::TempDir dir;
  writeSources(dir.path());
  const SensorSpec s = sourceSensor();
  const DarkFrameSet set = loadDarkFrames(dir.path(), s);
  // Another image size.
  Image small(32, 32, {"electrons"});
  EXPECT_THROW(expose(small, s, ExposureSettings{0.1, 100.0, &set}, NoiseMode::kFull, 1, 0),
               InputError);
  // Another black level.
  SensorSpec other = s;
  other.blackLevelDn = 64.0;
  try {
    loadDarkFrames(dir.path(), other);
    FAIL() << "accepted another black level";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "dark_frames");
    EXPECT_NE(e.where().file.find("dark_00.dng"), std::string::npos) << e.what();
  }
  // A file that is not a DNG.
  std::ofstream(dir.path() / "zz_bad.dng") << "not a tiff";
  try {
    loadDarkFrames(dir.path(), s);
    FAIL() << "accepted a broken DNG";
  } catch (const InputError& e) {
    EXPECT_NE(e.where().file.find("zz_bad.dng"), std::string::npos) << e.what();
  }
  // An empty directory.
  test::TempDir empty;
  EXPECT_THROW(loadDarkFrames(empty.path(), s), InputError);
}

// A header that claims more pixels than the file holds is refused before anything is
// allocated (the fuzzer's 968-byte file claimed about 4 GB of raw data).
TEST(DarkFrames, AHeaderClaimingMoreDataThanTheFileIsRefused) {
  const std::filesystem::path file = std::filesystem::path(CAMSIM_SOURCE_DIR) /
                                     "fuzz/regressions/raw_dng/header_claims_4gb_of_pixels.dng";
  try {
    readRawDng(file);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "dark_frames");
    EXPECT_NE(std::string(e.what()).find("bytes, the file has 968"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace camsim::dark_frame_reader_test
