// Tests for re-exposure of a render's electrons (sensor/io/expose_file.cpp) on synthetic raw
// EXRs: flat levels whose frames' mean and temporal variance must match the model
// (expectedDn, temporalVarianceLine of sensor/model/sensor_model.h) within 2 %; exposure
// scaling; seeds; what is refused (moving scene at X ≠ 1, missing layers and attributes, an
// ISO outside the calibrated range, another sensor's CFA, 0 frames).
#include "sensor/io/expose_file.h"
#include "tests/support/temp_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "sensor/io/output_set.h"
#include "sensor/model/sensor_noise.h"
#include "tests/support/lut_paths.h"
#include "tests/support/text_file.h"

namespace camsim::expose_file_test {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

const fs::path kLuts = CAMSIM_LUTS_DIR;
constexpr int kLevelSide = 64;  // each level a 64×64 block of photosites
const std::vector<double> kLevels = {0.0, 40.0, 120.0, 250.0, 400.0, 600.0};  // e⁻

Metadata rawMeta(const std::string& sensor, const std::string& cfa, const std::string& isStatic) {
  Metadata m = {{"camsim:sensor", sensor},          {"camsim:cfa", cfa},
                {"camsim:exposure_time_s", "0.01"}, {"camsim:iso", "400"},
                {"camsim:noise_seed", "7"},         {"camsim:f_number", "2"},
                {"camsim:focal_length_m", "0.005"}};
  if (!isStatic.empty()) m.push_back({"camsim:static_scene", isStatic});
  return m;
}

// Six flat levels side by side (6·64 × 64 photosites) as a render's raw EXR.
fs::path writeLevels(const fs::path& dir, const Metadata& meta,
                     const std::vector<std::string>& channels = {"electrons.e"}) {
  Image img(kLevelSide * static_cast<int>(kLevels.size()), kLevelSide, channels);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < img.channelCount(); ++c)
        img.at(x, y, c) = static_cast<float>(kLevels[static_cast<std::size_t>(x / kLevelSide)]);
  const fs::path path = dir / "flat_raw.exr";
  writeExr(path, img, meta, std::nullopt);
  return path;
}

struct LevelStats {
  double mean = 0.0, variance = 0.0;
};

// Per level: the mean over photosites and frames, and the temporal variance (each
// photosite's variance over the frames, averaged: the fixed patterns drop out).
std::vector<LevelStats> levelStats(const ExposeJob& job, int frames) {
  const std::size_t n = static_cast<std::size_t>(job.electrons.width) *
                        static_cast<std::size_t>(job.electrons.height);
  std::vector<double> sum(n, 0.0), sum2(n, 0.0);
  for (int f = 0; f < frames; ++f) {
    const std::vector<RawImage> raws = exposeJobFrame(job, static_cast<std::uint64_t>(f));
    for (std::size_t p = 0; p < n; ++p) {
      const double v = raws[0].dn[p];
      sum[p] += v;
      sum2[p] += v * v;
    }
  }
  std::vector<LevelStats> out(kLevels.size());
  for (std::size_t p = 0; p < n; ++p) {
    const std::size_t level = (p % static_cast<std::size_t>(job.electrons.width)) / kLevelSide;
    const double mean = sum[p] / frames;
    out[level].mean += mean;
    out[level].variance += (sum2[p] - frames * mean * mean) / (frames - 1);
  }
  for (LevelStats& s : out) {
    s.mean /= kLevelSide * kLevelSide;
    s.variance /= kLevelSide * kLevelSide;
  }
  return out;
}

// Mean and temporal variance of each level against the model: expectedDn, and the variance
// line plus the ADC's quantisation noise 1/12 DN² (EMVA 1288: the line is before rounding).
void expectModel(const ExposeJob& job, int frames, double scale) {
  const std::vector<LevelStats> stats = levelStats(job, frames);
  const VarianceLine line = temporalVarianceLine(job.sensor, job.exposure);
  for (std::size_t i = 0; i < kLevels.size(); ++i) {
    const double mu = expectedDn(kLevels[i] * scale, job.sensor, job.exposure);
    const double var = line.slopeDn * (mu - job.sensor.blackLevelDn) + line.offsetDn2 + 1.0 / 12;
    EXPECT_NEAR(stats[i].mean, mu, 0.02 * mu) << "level " << kLevels[i] << " e-, x" << scale;
    EXPECT_NEAR(stats[i].variance, var, 0.02 * var) << "level " << kLevels[i] << " e-, x" << scale;
  }
}

TEST(ExposeFile, FramesMatchTheModelsMeanAndVariancePerLevel) {
  TempDir dir;
  const fs::path exr = writeLevels(dir.path(), rawMeta("smartphone-1.4um", "RGGB", "1"));
  ExposeFileSettings s;
  s.frames = 24;
  ExposeJob job = prepareExpose(exr, s, kLuts);
  EXPECT_EQ(job.exposure.iso, 400.0);  // the file's
  EXPECT_EQ(job.seed, 7u);             // the file's
  EXPECT_DOUBLE_EQ(job.exposure.exposureTimeS, 0.01);
  expectModel(job, 24, 1.0);
  // Half the exposure at ISO 800: electrons × 0.5, the exposure time too, K doubled.
  s.exposureScale = 0.5;
  s.iso = 800.0;
  job = prepareExpose(exr, s, kLuts);
  EXPECT_DOUBLE_EQ(job.exposure.exposureTimeS, 0.005);
  EXPECT_EQ(job.electrons.at(5 * kLevelSide, 0, 0), 300.0f);
  expectModel(job, 24, 0.5);
}

TEST(ExposeFile, SameSeedSameBytesOtherSeedOrFrameDiffers) {
  TempDir dir;
  const fs::path exr = writeLevels(dir.path(), rawMeta("smartphone-1.4um", "RGGB", "1"));
  ExposeFileSettings s;
  s.frames = 2;
  s.seed = 11;
  const ExposeJob a = prepareExpose(exr, s, kLuts), b = prepareExpose(exr, s, kLuts);
  EXPECT_EQ(exposeJobFrame(a, 0)[0].dn, exposeJobFrame(b, 0)[0].dn);
  EXPECT_NE(exposeJobFrame(a, 0)[0].dn, exposeJobFrame(a, 1)[0].dn);
  s.seed = 12;
  EXPECT_NE(exposeJobFrame(a, 0)[0].dn, exposeJobFrame(prepareExpose(exr, s, kLuts), 0)[0].dn);
  // Written twice: the same bytes; names carry the frame.
  for (const char* sub : {"one", "two"}) {
    OutputSet out(dir.path() / sub);
    fs::create_directories(dir.path() / sub);
    writeExposedFrames(a, out, {});
    out.commit();
  }
  for (const char* f : {"flat_f0000.dng", "flat_f0001.dng", "flat_f0001_raw.exr"}) {
    const std::string bx = test::readFile(dir.path() / "one" / f);
    const std::string by = test::readFile(dir.path() / "two" / f);
    EXPECT_GT(bx.size(), 1000u) << f;
    EXPECT_EQ(bx, by) << f;
  }
  // The written raw EXR is itself re-exposable, and records what was done.
  const ElectronsExr again = readElectronsExr(dir.path() / "one" / "flat_f0001_raw.exr");
  EXPECT_EQ(again.noiseSeed, 11u);
  EXPECT_TRUE(again.staticScene);
  bool hasFrame = false;
  for (const auto& [k, v] : again.metadata)
    hasFrame = hasFrame || (k == "camsim:frame" && v == "1");
  EXPECT_TRUE(hasFrame);
}

// The InputError of prepareExpose, or "" if none.
std::string errorOf(const fs::path& exr, const ExposeFileSettings& s, std::string* key = nullptr) {
  try {
    prepareExpose(exr, s, kLuts);
  } catch (const InputError& e) {
    if (key) *key = e.key();
    return e.what();
  }
  return "";
}

TEST(ExposeFile, MovingSceneIsRefusedUnlessTheExposureStays) {
  TempDir dir;
  Metadata meta = rawMeta("smartphone-1.4um", "RGGB", "0");
  meta.push_back({"camsim:modelled", "pinhole, time (1 moving object; 2 motion steps), 4 wl"});
  const fs::path exr = writeLevels(dir.path(), meta);
  ExposeFileSettings s;
  s.exposureScale = 2.0;
  std::string key;
  const std::string e = errorOf(exr, s, &key);
  EXPECT_EQ(key, "exposure_scale");
  EXPECT_NE(e.find("moves during the exposure"), std::string::npos) << e;
  EXPECT_NE(e.find("1 moving object"), std::string::npos) << e;
  EXPECT_NE(e.find("flat_raw.exr"), std::string::npos) << e;
  s.exposureScale = 1.0;  // new noise on the same electrons: exact
  EXPECT_EQ(errorOf(exr, s), "");
}

TEST(ExposeFile, OldFilesAreJudgedByTheirModelledAttribute) {
  TempDir dir;
  ExposeFileSettings s;
  s.exposureScale = 2.0;
  Metadata meta = rawMeta("smartphone-1.4um", "RGGB", "");
  meta.push_back({"camsim:modelled", "pinhole, static (no time sampling), 4 wavelengths"});
  EXPECT_EQ(errorOf(writeLevels(dir.path(), meta), s), "");
  meta.back().second = "pinhole, time (moving camera; 2 motion steps), 4 wavelengths";
  EXPECT_NE(errorOf(writeLevels(dir.path(), meta), s), "");
  meta.pop_back();  // neither attribute
  const std::string e = errorOf(writeLevels(dir.path(), meta), s);
  EXPECT_NE(e.find("camsim:static_scene"), std::string::npos) << e;
}

TEST(ExposeFile, BadInputsNameTheFileAndKey) {
  TempDir dir;
  const fs::path good = writeLevels(dir.path(), rawMeta("smartphone-1.4um", "RGGB", "1"));
  ExposeFileSettings s;
  std::string key;
  // A missing file.
  std::string e = errorOf(dir.path() / "missing_raw.exr", s);
  EXPECT_NE(e.find("missing_raw.exr"), std::string::npos) << e;
  EXPECT_NE(e.find("no such file"), std::string::npos) << e;
  // No electrons layer (the main EXR of a render, say).
  {
    TempDir other;
    e = errorOf(writeLevels(other.path(), rawMeta("smartphone-1.4um", "RGGB", "1"), {"R", "G"}), s,
                &key);
    EXPECT_EQ(key, "electrons.<channel>");
  }
  // No camsim:sensor.
  {
    TempDir other;
    Metadata m = rawMeta("smartphone-1.4um", "RGGB", "1");
    m.erase(m.begin());
    e = errorOf(writeLevels(other.path(), m), s, &key);
    EXPECT_EQ(key, "camsim:sensor") << e;
  }
  // 0 frames, a scale of 0, an unknown noise mode.
  s.frames = 0;
  e = errorOf(good, s, &key);
  EXPECT_EQ(key, "frames");
  EXPECT_NE(e.find("[1, 100000]"), std::string::npos) << e;
  s.frames = 1;
  s.exposureScale = 0.0;
  EXPECT_NE(errorOf(good, s, &key), "");
  EXPECT_EQ(key, "exposure_scale");
  s.exposureScale = 1.0;
  s.noise = "loud";
  EXPECT_NE(errorOf(good, s, &key), "");
  EXPECT_EQ(key, "noise");
  s.noise = "full";
  // Another sensor with another CFA and photosite: refused, naming both.
  s.sensor = "fullframe-d850";
  e = errorOf(good, s, &key);
  EXPECT_EQ(key, "sensor");
  EXPECT_NE(e.find("fullframe-d850"), std::string::npos) << e;
  EXPECT_NE(e.find("smartphone-1.4um"), std::string::npos) << e;
  // The stacked sensor's CFA against a file recorded as RGGB.
  s.sensor = "ideal-xyz";
  EXPECT_NE(errorOf(good, s, &key), "");
  EXPECT_EQ(key, "sensor");
  // The same photosite area to the decimals a description gives (√2 · 1.4 µm at fill factor
  // 0.5) sees the same light: it was refused as "1.96 µm² against 1.96 µm²" (found by
  // probing); 1 % more area is another sensor, both areas printed so that they differ.
  std::string text = test::readFile(test::kLuts / "sensors" / "smartphone-1.4um.yaml");
  for (const auto& [pitch, accepted] :
       {std::pair<const char*, bool>{"1.979898987", true}, {"1.9897", false}}) {
    std::string other = text;
    other.replace(other.find("name: smartphone-1.4um"), 22, "name: other");
    other.replace(other.find("pixel_pitch_um: 1.4"), 19, std::string("pixel_pitch_um: ") + pitch);
    other.replace(other.find("fill_factor: 1.0"), 16, "fill_factor: 0.5");
    const fs::path file = dir.path() / "other.yaml";
    test::writeFile(file, other);
    s.sensor = file.string();
    e = errorOf(good, s, &key);
    if (accepted) {
      EXPECT_EQ(e, "") << pitch;
    } else {
      EXPECT_NE(e.find("1.979453045 µm² against 1.96 µm²"), std::string::npos) << e;
    }
  }
}

// Found by probing: a noise seed of -1 or 1e20 became 2^64 - 1, and an f-number or focal
// length of 0, -2 or nan was taken (the DNG then lost its tag), each exit 0.
TEST(ExposeFile, HeaderValuesOutOfRangeAreRefusedByKey) {
  const struct {
    const char* key;
    const char* value;
    const char* says;
  } cases[] = {
      {"camsim:noise_seed", "-1", "[0, 2^63 - 1]"},
      {"camsim:noise_seed", "99999999999999999999", "[0, 2^63 - 1]"},
      {"camsim:noise_seed", "9223372036854775808", "[0, 2^63 - 1]"},
      {"camsim:noise_seed", "+5", "[0, 2^63 - 1]"},
      {"camsim:f_number", "0", "> 0"},
      {"camsim:f_number", "-2", "> 0"},
      {"camsim:f_number", "nan", "expected a number"},
      {"camsim:focal_length_m", "0", "> 0"},
      // Found by probing: beyond an EXIF rational, the DNG said 4294967295/0 (exit 0).
      {"camsim:exposure_time_s", "1e300", "beyond what the DNG's EXIF ExposureTime holds"},
      {"camsim:exposure_time_s", "0", "must be positive"},  // accepted (found by probing)
      {"camsim:f_number", "1e10", "beyond what the DNG's EXIF FNumber holds"},
      {"camsim:focal_length_m", "1e300", "beyond what the DNG's EXIF FocalLength holds"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(std::string(c.key) + "=" + c.value);
    TempDir dir;
    Metadata m = rawMeta("smartphone-1.4um", "RGGB", "1");
    for (auto& [k, v] : m)
      if (k == c.key) v = c.value;
    std::string key;
    const std::string e = errorOf(writeLevels(dir.path(), m), ExposeFileSettings{}, &key);
    EXPECT_EQ(key, c.key) << e;
    EXPECT_NE(e.find(c.says), std::string::npos) << e;
  }
  // The largest seed and a real lens still read.
  TempDir dir;
  Metadata m = rawMeta("smartphone-1.4um", "RGGB", "1");
  for (auto& [k, v] : m)
    if (k == "camsim:noise_seed") v = "9223372036854775807";
  EXPECT_EQ(errorOf(writeLevels(dir.path(), m), ExposeFileSettings{}), "");
}

// Found by probing: a scale that took electrons past the float range wrote inf into the
// output raw EXR (which expose itself then refused), and one that took the exposure past an
// EXIF rational wrote 4294967295/0 into the DNG, both exit 0; an unknown --sensor preset
// named "<input>" instead of the file. Each refused naming the file and the key.
TEST(ExposeFile, ScalesBeyondWhatTheOutputsHoldAreRefused) {
  TempDir dir;
  ExposeFileSettings s;
  std::string key;
  // The exposure: 1e4 s × 1e6 = 1e10 s.
  Metadata m = rawMeta("smartphone-1.4um", "RGGB", "1");
  for (auto& [k, v] : m)
    if (k == "camsim:exposure_time_s") v = "1e4";
  const fs::path longExposure = writeLevels(dir.path(), m);
  s.exposureScale = 1e6;
  std::string e = errorOf(longExposure, s, &key);
  EXPECT_EQ(key, "exposure_scale") << e;
  EXPECT_NE(e.find("ExposureTime holds"), std::string::npos) << e;
  s.exposureScale = 4e5;  // 4e9 s: still held
  EXPECT_EQ(errorOf(longExposure, s), "");
  // The electrons: 3e38 × 2.
  TempDir other;
  Image huge(4, 4, {"electrons.e"});
  for (float& v : huge.pixels) v = 3e38f;
  const fs::path hugeExr = other.path() / "huge_raw.exr";
  writeExr(hugeExr, huge, rawMeta("smartphone-1.4um", "RGGB", "1"), std::nullopt);
  s.exposureScale = 2.0;
  e = errorOf(hugeExr, s, &key);
  EXPECT_EQ(key, "exposure_scale") << e;
  EXPECT_NE(e.find("beyond the float range"), std::string::npos) << e;
  EXPECT_NE(e.find("huge_raw.exr"), std::string::npos) << e;
  // An unknown preset.
  s.exposureScale = 1.0;
  s.sensor = "nope";
  e = errorOf(hugeExr, s, &key);
  EXPECT_EQ(key, "sensor") << e;
  EXPECT_EQ(e.rfind(hugeExr.string(), 0), 0u) << e;
}

TEST(ExposeFile, IsoOutsideTheCalibratedRangeIsRefused) {
  TempDir dir;
  // The smartphone preset, renamed, with a measured ISO table of 50–800.
  std::string text = test::readFile(kLuts / "sensors" / "smartphone-1.4um.yaml");
  text.replace(text.find("name: smartphone-1.4um"), 22, "name: phone-table");
  text += "\niso_table:\n  - {iso: 50}\n  - {iso: 800}\n";
  const fs::path yaml = dir.path() / "phone-table.yaml";
  test::writeFile(yaml, text);
  const fs::path exr = writeLevels(dir.path(), rawMeta("phone-table", "RGGB", "1"));
  ExposeFileSettings s;
  s.sensor = yaml.string();
  EXPECT_EQ(errorOf(exr, s), "");  // the recorded ISO 400 is in range
  s.iso = 3200.0;
  std::string key;
  const std::string e = errorOf(exr, s, &key);
  EXPECT_EQ(key, "iso");
  EXPECT_NE(e.find("flat_raw.exr"), std::string::npos) << e;
  s.iso = -1.0;
  EXPECT_NE(errorOf(exr, s, &key), "");
  EXPECT_EQ(key, "iso");
}

// A sensor without an ISO table takes any ISO, within render's --iso range [1, 1e7] (found by
// probing: --iso 1e12 was exposed and written, the DNG's ISO clamped).
TEST(ExposeFile, IsoOutsideRendersRangeIsRefused) {
  TempDir dir;
  const fs::path exr = writeLevels(dir.path(), rawMeta("smartphone-1.4um", "RGGB", "1"));
  ExposeFileSettings s;
  for (const double iso : {1.0, 1e7}) {
    s.iso = iso;
    EXPECT_EQ(errorOf(exr, s), "") << iso;
  }
  for (const double iso : {0.5, 1.0000001e7, 1e12}) {
    s.iso = iso;
    std::string key;
    const std::string e = errorOf(exr, s, &key);
    EXPECT_EQ(key, "iso") << iso;
    EXPECT_NE(e.find("is outside [1, 1e+07]"), std::string::npos) << e;
  }
}

}  // namespace
}  // namespace camsim::expose_file_test
