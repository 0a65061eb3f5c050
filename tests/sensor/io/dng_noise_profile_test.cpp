// Tests for the DNG tags of sensor/io/dng_writer that describe the shot rather than the
// layout: NoiseProfile (dngNoiseProfile from the sensor model at the frame's ISO),
// BaselineExposure, ExposureBiasValue and AsShotNeutral's max-1 scaling. Read back by
// exiftool (Debian package libimage-exiftool-perl) and LibRaw's raw-identify (libraw-bin),
// both installed by scripts/setup.sh; the expected numbers come from the sensor's own
// parameters (K = ISO / base ISO / conversion gain, σ_pre, σ_post), not from
// temporalVarianceLine.
#include "sensor/io/dng_writer.h"
#include "tests/support/scene_text.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"
#include "sensor/model/sensor_model.h"
#include "sensor/model/sensor_spec.h"
#include "tests/support/lut_paths.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim::dng_noise_profile_test {
namespace {

using test::onPath;

// 14 bit, black 512 (range r = 16383 − 512 = 15871 DN), K = ISO/100/2 DN/e⁻, σ_pre 3 e⁻,
// σ_post 1.5 DN: σ² = K·(μ − black) + 9K² + 2.25 DN².
constexpr double kRange = 16383.0 - 512.0;
const char* const kSensorYaml =
    "name: noisy\n"
    "pixel_pitch_um: 4.0\n"
    "cfa: RGGB\n"
    "qe: {curves: cameras/nikon_d850.csv, peak_qe: 0.5}\n"
    "full_well_e: 40000\n"
    "base_iso: 100\n"
    "conversion_gain_e_per_dn: 2\n"
    "read_noise_e: 3\n"
    "read_noise_post_dn: 1.5\n"
    "dark_current_e_per_s: 5\n"
    "adc_bits: 14\n"
    "black_level_dn: 512\n";

double expectedScale(double iso) {
  return iso / 100.0 / 2.0 / kRange;
}
double expectedOffset(double iso) {
  const double k = iso / 100.0 / 2.0;
  return (k * k * 3.0 * 3.0 + 1.5 * 1.5) / (kRange * kRange);
}

class DngNoiseProfileTest : public testing::Test {
 protected:
  void SetUp() override {
    test::writeFile(dir_ / "noisy.yaml", kSensorYaml);
    spec_ = loadSensorSpec((dir_ / "noisy.yaml").string(), test::kLuts);
  }

  // A small raw of the sensor (a ramp above the black level) in the given layout; LibRaw
  // takes nothing under 22 photosites a side for a raw.
  RawImage raw(bool mono) const {
    RawImage r;
    r.width = 32;
    r.height = 24;
    if (!mono) r.cfa = spec_.cfa;
    r.adcBits = spec_.adcBits;
    r.blackLevelDn = spec_.blackLevelDn;
    r.whiteLevelDn = spec_.whiteLevelDn();
    for (int i = 0; i < r.width * r.height; ++i)
      r.dn.push_back(static_cast<std::uint16_t>(512 + 20 * i));
    return r;
  }

  // exiftool's values (-n: numbers as stored, no units) of the tags, one "Tag: value" line each.
  std::string exif(const std::filesystem::path& dng, const std::string& tags) const {
    const test::RunResult r =
        test::runCommand("exiftool -s -n " + tags + " " + test::quote(dng.string()), dir_);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return r.out;
  }

  test::TempDir tmp_;
  std::filesystem::path dir_ = tmp_.path();
  SensorSpec spec_;
};

// The numbers after "Tag :" on exiftool's line for tag; empty if the tag is absent.
std::vector<double> values(const std::string& text, const std::string& tag) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string name = line.substr(0, colon);
    while (!name.empty() && name.back() == ' ') name.pop_back();
    if (name != tag) continue;
    std::istringstream in(line.substr(colon + 1));
    std::vector<double> out;
    for (double v = 0.0; in >> v;) out.push_back(v);
    return out;
  }
  return {};
}

TEST_F(DngNoiseProfileTest, ProfileIsTheModelsVarianceLineInNormalisedUnits) {
  for (const double iso : {100.0, 800.0}) {
    SCOPED_TRACE("ISO " + std::to_string(iso));
    const std::optional<DngNoiseProfile> p =
        dngNoiseProfile(spec_, ExposureSettings{0.01, iso}, NoiseMode::kFull);
    ASSERT_TRUE(p.has_value());
    EXPECT_NEAR(p->scale, expectedScale(iso), 1e-12 * expectedScale(iso));
    EXPECT_NEAR(p->offset, expectedOffset(iso), 1e-12 * expectedOffset(iso));
    // Shot noise only: no offset. No noise at all: no profile.
    const auto photon = dngNoiseProfile(spec_, ExposureSettings{0.01, iso}, NoiseMode::kPhoton);
    ASSERT_TRUE(photon.has_value());
    EXPECT_EQ(photon->scale, p->scale);
    EXPECT_EQ(photon->offset, 0.0);
    EXPECT_FALSE(dngNoiseProfile(spec_, ExposureSettings{0.01, iso}, NoiseMode::kNone));
  }
  SensorSpec ideal = spec_;
  ideal.noiseless = true;
  EXPECT_FALSE(dngNoiseProfile(ideal, ExposureSettings{0.01, 100.0}, NoiseMode::kFull));
  EXPECT_THROW(dngNoiseProfile(spec_, ExposureSettings{0.01, 0.0}, NoiseMode::kFull), InputError);
}

// exiftool reads the profile back as written: 3 equal (S, O) pairs for R, G, B at each ISO,
// BaselineExposure 0 and AsShotNeutral; raw-identify still reads the file.
TEST_F(DngNoiseProfileTest, ExiftoolReadsTheProfileAtTwoIsos) {
  ASSERT_TRUE(onPath("exiftool"))
      << "exiftool is not installed (Debian package libimage-exiftool-perl; scripts/setup.sh)";
  ASSERT_TRUE(onPath("raw-identify")) << "raw-identify is not installed (libraw-bin)";
  DngColor color;
  color.asShotNeutral = {0.5, 1.0, 0.7};
  for (const double iso : {100.0, 800.0}) {
    SCOPED_TRACE("ISO " + std::to_string(iso));
    DngCapture capture{0.01, 4.0, 50.0, iso, "2000:01:01 00:00:00", {}, 0.0, {}};
    capture.noiseProfile = dngNoiseProfile(spec_, ExposureSettings{0.01, iso}, NoiseMode::kFull);
    const std::filesystem::path dng = dir_ / ("iso" + std::to_string(int(iso)) + ".dng");
    writeDng(dng, raw(false), color, {{"camsim:sensor", "noisy"}}, capture);
    const std::string out = exif(dng, "-NoiseProfile -BaselineExposure -AsShotNeutral -ISO");
    SCOPED_TRACE(out);
    std::printf("[exiftool -n, ISO %g]\n%s", iso, out.c_str());
    const std::vector<double> profile = values(out, "NoiseProfile");
    ASSERT_EQ(profile.size(), 6u);
    for (size_t plane = 0; plane < 3; ++plane) {
      // exiftool prints 15 significant digits.
      EXPECT_NEAR(profile[2 * plane], expectedScale(iso), 1e-13 * expectedScale(iso));
      EXPECT_NEAR(profile[2 * plane + 1], expectedOffset(iso), 1e-13 * expectedOffset(iso));
    }
    EXPECT_EQ(values(out, "BaselineExposure"), std::vector<double>{0.0});
    EXPECT_EQ(values(out, "ISO"), std::vector<double>{iso});
    const std::vector<double> neutral = values(out, "AsShotNeutral");
    ASSERT_EQ(neutral.size(), 3u);
    EXPECT_NEAR(neutral[0], 0.5, 1e-6);
    EXPECT_NEAR(neutral[1], 1.0, 1e-6);
    EXPECT_NEAR(neutral[2], 0.7, 1e-6);

    const test::RunResult id =
        test::runCommand("raw-identify -v " + test::quote(dng.string()), dir_);
    ASSERT_EQ(id.exitCode, 0) << id.err;
    SCOPED_TRACE(id.out + id.err);
    // LibRaw 0.20 reads the ISO, BaselineExposure and AsShotNeutral (as multipliers 1/n);
    // it does not print NoiseProfile.
    EXPECT_NE(id.out.find("\nISO speed: " + std::to_string(int(iso)) + "\n"), std::string::npos);
    EXPECT_NE(id.out.find("\nBaseline exposure: 0.000\n"), std::string::npos);
    EXPECT_NE(id.out.find("As shot                   2 1 1.42857 0"), std::string::npos);
    EXPECT_NE(id.out.find("\nFull size:     32 x 24\n"), std::string::npos);
  }
}

TEST_F(DngNoiseProfileTest, MonoHasOnePairAndNoProfileIsNoTag) {
  ASSERT_TRUE(onPath("exiftool")) << "exiftool is not installed (libimage-exiftool-perl)";
  DngCapture capture;
  capture.noiseProfile = dngNoiseProfile(spec_, ExposureSettings{0.01, 400.0}, NoiseMode::kFull);
  writeDng(dir_ / "mono.dng", raw(true), DngColor{}, {}, capture);
  const std::vector<double> mono = values(exif(dir_ / "mono.dng", "-NoiseProfile"), "NoiseProfile");
  ASSERT_EQ(mono.size(), 2u);
  EXPECT_NEAR(mono[0], expectedScale(400.0), 1e-13 * expectedScale(400.0));
  EXPECT_NEAR(mono[1], expectedOffset(400.0), 1e-13 * expectedOffset(400.0));

  capture.noiseProfile = dngNoiseProfile(spec_, ExposureSettings{0.01, 400.0}, NoiseMode::kNone);
  writeDng(dir_ / "none.dng", raw(false), DngColor{}, {}, capture);
  const std::string none = exif(dir_ / "none.dng", "-NoiseProfile -BaselineExposure");
  EXPECT_TRUE(values(none, "NoiseProfile").empty()) << none;
  EXPECT_EQ(values(none, "BaselineExposure"), std::vector<double>{0.0}) << none;
}

// A bracket's offset goes in ExposureBiasValue (exiftool: ExposureCompensation); a baseline
// other than 0 is written as given; AsShotNeutral is written scaled to max 1.
TEST_F(DngNoiseProfileTest, ExposureTagsAndNeutralScaling) {
  ASSERT_TRUE(onPath("exiftool")) << "exiftool is not installed (libimage-exiftool-perl)";
  DngCapture capture;
  capture.exposureBiasEv = -2.0;
  capture.baselineExposureEv = 0.5;
  DngColor color;
  color.asShotNeutral = {1.2, 1.0, 0.4};  // R above G: written as (1, 1/1.2, 1/3)
  writeDng(dir_ / "bias.dng", raw(false), color, {}, capture);
  const std::string out =
      exif(dir_ / "bias.dng", "-ExposureCompensation -BaselineExposure -AsShotNeutral");
  SCOPED_TRACE(out);
  EXPECT_EQ(values(out, "ExposureCompensation"), std::vector<double>{-2.0});
  EXPECT_EQ(values(out, "BaselineExposure"), std::vector<double>{0.5});
  const std::vector<double> neutral = values(out, "AsShotNeutral");
  ASSERT_EQ(neutral.size(), 3u);
  EXPECT_NEAR(neutral[0], 1.0, 1e-6);
  EXPECT_NEAR(neutral[1], 1.0 / 1.2, 1e-6);
  EXPECT_NEAR(neutral[2], 0.4 / 1.2, 1e-6);
  // Without a bracket no ExposureBiasValue.
  writeDng(dir_ / "plain.dng", raw(false), color, {}, DngCapture{});
  EXPECT_TRUE(
      values(exif(dir_ / "plain.dng", "-ExposureCompensation"), "ExposureCompensation").empty());
}

// ISOSpeedRatings is 16 bits: an ISO of 65535 or more is written as Exif 2.3 says, 65535
// there and the value in ISOSpeed with SensitivityType 3 (found by probing: ISO 204800 was
// written as 65535, the real value nowhere in the file). Below 65535 the tag alone.
TEST_F(DngNoiseProfileTest, AnIsoAbove65535IsInIsoSpeed) {
  ASSERT_TRUE(onPath("exiftool")) << "exiftool is not installed (libimage-exiftool-perl)";
  const std::string tags = "-ISO -ISOSpeed -SensitivityType";
  for (const double iso : {204800.0, 65535.0, 6400.0}) {
    DngCapture capture;
    capture.iso = iso;
    writeDng(dir_ / "iso.dng", raw(false), DngColor{}, {}, capture);
    const std::string out = exif(dir_ / "iso.dng", tags);
    SCOPED_TRACE(out);
    EXPECT_EQ(values(out, "ISO"), std::vector<double>{std::min(iso, 65535.0)});
    if (iso >= 65535.0) {
      EXPECT_EQ(values(out, "ISOSpeed"), std::vector<double>{iso});
      EXPECT_EQ(values(out, "SensitivityType"), std::vector<double>{3.0});
    } else {
      EXPECT_TRUE(values(out, "ISOSpeed").empty());
      EXPECT_TRUE(values(out, "SensitivityType").empty());
    }
  }
}

}  // namespace
}  // namespace camsim::dng_noise_profile_test
