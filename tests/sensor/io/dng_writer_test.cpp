// Tests for sensor/dng_writer: DNGs checked by an independent reader (LibRaw's raw-identify,
// unprocessed_raw and dcraw_emu, Debian package libraw-bin) and the least-squares colour fit.
#include "sensor/io/dng_writer.h"
#include "tests/support/scene_text.h"

#include <unistd.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <system_error>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/spectral_data.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

using test::onPath;

const std::filesystem::path kColorChecker =
    std::filesystem::path(CAMSIM_LUTS_DIR) / "spectra/colorchecker_classic_reflectance.csv";

// A fresh directory per test, removed afterwards.
class DngWriterTest : public testing::Test {
 protected:
  test::TempDir tmp_;
  std::filesystem::path dir_ = tmp_.path();
};

// The layout of a Bayer name ("RGGB": top-left R, top-right G, …) or "mono", built here so
// the test does not depend on CfaLayout::fromName.
CfaLayout layout(const std::string& name) {
  CfaLayout cfa;
  cfa.name = name;
  if (name == "mono") return cfa;
  cfa.width = cfa.height = 2;
  cfa.channels = {"R", "G", "B"};
  cfa.tile.clear();
  for (const char c : name) cfa.tile.push_back(c == 'R' ? 0 : c == 'G' ? 1 : 2);
  return cfa;
}

// A 12-bit gradient over [black, white], the last photosite exactly at the white level.
RawImage gradient(const std::string& cfaName, int width, int height) {
  RawImage raw;
  raw.width = width;
  raw.height = height;
  raw.cfa = layout(cfaName);
  raw.adcBits = 12;
  raw.blackLevelDn = 256.0;
  raw.whiteLevelDn = 4095.0;
  const int range = 4095 - 256 + 1;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      raw.dn.push_back(static_cast<std::uint16_t>(256 + (x * 7 + y * 131) % range));
  raw.dn.back() = 4095;
  return raw;
}

// stdout of a shell command.
std::string run(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen(command.c_str(), "r"), &::pclose);
  if (!pipe) return {};
  std::string out;
  std::array<char, 4096> buffer;
  size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe.get())) > 0)
    out.append(buffer.data(), n);
  return out;
}

std::string quoted(const std::filesystem::path& p) {
  return "'" + p.string() + "'";
}

// The value after "key: " on the line starting with key, "" if none.
std::string field(const std::string& text, const std::string& key) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line))
    if (line.rfind(key + ":", 0) == 0) {
      std::string value = line.substr(key.size() + 1);
      while (!value.empty() && value.front() == ' ') value.erase(0, 1);
      while (!value.empty() && (value.back() == ' ' || value.back() == '\r')) value.pop_back();
      return value;
    }
  return {};
}

// A binary 16-bit PGM or PPM (P5/P6, maxval > 255: big-endian samples), as LibRaw writes.
struct Pnm {
  int width = 0, height = 0, channels = 0;
  std::vector<std::uint16_t> values;  // interleaved
  std::uint16_t at(int x, int y, int c) const {
    return values[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) *
                      static_cast<size_t>(channels) +
                  static_cast<size_t>(c)];
  }
};
Pnm readPnm16(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  Pnm pnm;
  int maxval = 0;
  in >> magic >> pnm.width >> pnm.height >> maxval;
  in.get();  // the single whitespace before the samples
  pnm.channels = magic == "P5" ? 1 : magic == "P6" ? 3 : 0;
  if (pnm.channels == 0 || maxval < 256 || !in) return {};
  pnm.values.resize(static_cast<size_t>(pnm.width) * static_cast<size_t>(pnm.height) *
                    static_cast<size_t>(pnm.channels));
  for (auto& v : pnm.values) {
    const int hi = in.get(), lo = in.get();
    v = static_cast<std::uint16_t>((hi << 8) | lo);
  }
  return in ? pnm : Pnm{};
}

// The n lines after the line equal to header, "" if none.
std::string linesAfter(const std::string& text, const std::string& header, int n) {
  const size_t at = text.find("\n" + header + "\n");
  if (at == std::string::npos) return {};
  size_t end = at + header.size() + 2;
  for (int i = 0; i < n && end != std::string::npos; ++i) end = text.find('\n', end + 1);
  return text.substr(at + header.size() + 2, end - (at + header.size() + 2));
}

DngColor someColor() {
  DngColor color;
  color.calibration1.xyzToCamera = glm::dmat3(0.9, -0.3, 0.05, -0.4, 1.2, 0.2, -0.05, 0.1, 0.8);
  color.asShotNeutral = {0.5, 1.0, 0.7};
  return color;
}

class DngLayoutTest : public DngWriterTest, public testing::WithParamInterface<std::string> {};

// LibRaw 0.20 (Debian 12 libraw-bin) as the independent reader. raw-identify -v prints the
// layout and black level but not the white level ("maximum"); the white level is checked
// through dcraw_emu's scaling instead, and the DNs through unprocessed_raw.
TEST_P(DngLayoutTest, LibRawReadsDimensionsPatternLevelsAndValues) {
  const std::string name = GetParam();
  const bool mono = name == "mono";
  const RawImage raw = gradient(name, 64, 48);
  const std::filesystem::path path = dir_ / ("gradient_" + name + ".dng");
  writeDng(path, raw, someColor(),
           {{"camsim:sensor", "test-" + name}, {"camsim:scene", "gradient"}},
           DngCapture{1.0 / 125.0, 5.6, 35.0, 400.0, "2000:01:01 00:00:00", {}, 0.0, {}});
  ASSERT_TRUE(std::filesystem::exists(path));
  EXPECT_GT(std::filesystem::file_size(path), 64u * 48u * 2u);
  ASSERT_TRUE(onPath("raw-identify"))
      << "raw-identify (Debian package libraw-bin, installed by scripts/setup.sh) is not on PATH: "
         "the DNG was written but cannot be checked by an independent reader";

  const std::string info = run("raw-identify -v " + quoted(path) + " 2>&1");
  SCOPED_TRACE(info);
  // LibRaw prints Make + Model with the make removed from the model, then a camera id.
  EXPECT_EQ(field(info, "Camera").rfind("camsim test-" + name, 0), 0u);
  EXPECT_EQ(field(info, "UniqueCameraModel"), "=camsim test-" + name + "=");
  EXPECT_EQ(field(info, " DNG Version"), "1.4.0.0");
  EXPECT_EQ(field(info, "Full size"), "64 x 48");
  EXPECT_EQ(field(info, "Image flip"), "0");
  EXPECT_EQ(field(info, "black"), "256");
  EXPECT_EQ(field(info, "BlackLevelRepeatDim"), "1 x 1");
  // The EXIF IFD, as LibRaw reports it.
  EXPECT_EQ(field(info, "ISO speed"), "400");
  EXPECT_EQ(field(info, "Shutter"), "1/125.0");
  EXPECT_EQ(field(info, "Aperture"), "f/5.6");
  EXPECT_EQ(field(info, "Focal length"), "35.0 mm");
  if (mono) {
    EXPECT_EQ(field(info, "Raw colors"), "1");
    EXPECT_EQ(field(info, "Filter pattern"), "");
    EXPECT_EQ(info.find("DNG color matrix"), std::string::npos);
  } else {
    EXPECT_EQ(field(info, "Raw colors"), "3");
    // dcraw's 2×8 filter word as 16 letters (rows 0 and 1 of an 8-wide tile, 2 rows each).
    EXPECT_EQ(field(info, "Filter pattern"), name + name + name + name);
    EXPECT_EQ(field(info, "DNG Illuminant 1"), "D65");
    EXPECT_EQ(linesAfter(info, "DNG color matrix 1:", 3),
              "0.9000\t-0.4000\t-0.0500\n-0.3000\t1.2000\t0.1000\n0.0500\t0.2000\t0.8000");
    // White-balance multipliers = 1 / AsShotNeutral (0.5, 1, 0.7), printed with 6 digits.
    EXPECT_NE(info.find("As shot                   2 1 1.42857 0"), std::string::npos);
  }

  ASSERT_TRUE(onPath("unprocessed_raw")) << "unprocessed_raw (libraw-bin) is not on PATH";
  {
    // The unscaled raw values (black not subtracted), written next to the input as FILE.pgm.
    run("unprocessed_raw -q " + quoted(path) + " 2>&1");
    const Pnm pnm = readPnm16(path.string() + ".pgm");
    ASSERT_EQ(pnm.width, raw.width);
    ASSERT_EQ(pnm.height, raw.height);
    EXPECT_EQ(pnm.values, raw.dn);
  }
  ASSERT_TRUE(onPath("dcraw_emu")) << "dcraw_emu (libraw-bin) is not on PATH";
  // Linear 16-bit, raw colour, unit white balance, no maximum adjustment, bilinear
  // demosaic (each photosite keeps its own channel): out = (DN − black)·65535/(white − black).
  const std::filesystem::path scaled = dir_ / "scaled.pnm";
  const std::string log = run("dcraw_emu -4 -o 0 -r 1 1 1 1 -c 0 -q 0 -Z " + quoted(scaled) + " " +
                              quoted(path) + " 2>&1");
  const Pnm pnm = readPnm16(scaled);
  ASSERT_EQ(pnm.width, raw.width) << log;
  ASSERT_EQ(pnm.height, raw.height);
  ASSERT_EQ(pnm.channels, mono ? 1 : 3);
  const double scale = 65535.0 / (raw.whiteLevelDn - raw.blackLevelDn);
  int saturated = 0;
  for (int y = 0; y < raw.height; ++y)
    for (int x = 0; x < raw.width; ++x) {
      const int c = mono ? 0 : raw.cfa.channelAt(x, y);
      const double expected = (raw.at(x, y) - raw.blackLevelDn) * scale;
      ASSERT_NEAR(pnm.at(x, y, c), expected, 1.0)
          << "(" << x << ", " << y << ") DN " << raw.at(x, y);
      saturated += pnm.at(x, y, c) == 65535;
    }
  EXPECT_GT(saturated, 0);  // the gradient reaches the white level
}

INSTANTIATE_TEST_SUITE_P(Layouts, DngLayoutTest,
                         testing::Values("RGGB", "BGGR", "GRBG", "GBRG", "mono"),
                         [](const testing::TestParamInfo<std::string>& p) { return p.param; });

TEST_F(DngWriterTest, NonRgbCfaIsAnInputError) {
  RawImage raw = gradient("RGGB", 4, 4);
  raw.cfa.channels = {"R", "G", "W"};
  raw.cfa.name = "RGGW";
  EXPECT_THROW(writeDng(dir_ / "rggw.dng", raw, someColor(), {}), InputError);
}

TEST_F(DngWriterTest, UnwritablePathThrows) {
  const RawImage raw = gradient("RGGB", 4, 4);
  EXPECT_THROW(writeDng(dir_ / "missing_dir" / "x.dng", raw, someColor(), {}), std::runtime_error);
}

// QE_k = cmf_k(λ) · λ₀/λ: photo-electrons exactly proportional to X, Y, Z.
std::vector<Spectrum> idealXyzQe(bool photonCorrected) {
  const Cie1931& cie = Cie1931::get();
  std::vector<Spectrum> qe = {cie.x, cie.y, cie.z};
  if (photonCorrected)
    for (auto& s : qe)
      for (int i = 0; i < kSpectrumSamples; ++i)
        s.sample(i) *= static_cast<float>(555.0 / (kLambdaMinNm + i));
  return qe;
}

TEST(DngColorFromQe, IdealXyzSensorGivesTheNormalisedIdentity) {
  const Spectrum d65 = cieIlluminant("D65");
  const DngColor color = dngColorFromQe(idealXyzQe(true), "D65", kColorChecker);
  EXPECT_EQ(color.calibration1.lightSource, 21);
  EXPECT_FALSE(color.calibration2.has_value());
  // Identity scaled so that the D65 white (Y = 1) has max component 1: the largest of
  // X, Y, Z = (0.9505, 1, 1.089) is Z, so the scale is 1 / Z_D65.
  const glm::dvec3 white = reflectanceToXyz(Spectrum::constant(1.0), d65);
  const double scale = 1.0 / std::max({white.x, white.y, white.z});
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(color.calibration1.xyzToCamera[c][r], r == c ? scale : 0.0, 1e-3)
          << "row " << r << " col " << c;
  // The D65 white maps to max component 1 exactly.
  const glm::dvec3 w = color.calibration1.xyzToCamera * white;
  EXPECT_NEAR(std::max({w.x, w.y, w.z}), 1.0, 1e-12);
  // AsShotNeutral under D65 = XYZ of the D65 white scaled to max 1 (Z is the largest).
  EXPECT_NEAR(color.asShotNeutral.x, white.x / white.z, 1e-6);
  EXPECT_NEAR(color.asShotNeutral.y, 1.0 / white.z, 1e-6);
  EXPECT_DOUBLE_EQ(color.asShotNeutral.z, 1.0);
}

TEST(DngColorFromQe, PlainCmfQeIsCloseToButNotExactlyTheIdentity) {
  // QE = x̄ȳz̄ counts photons (∝ energy·λ): the fit absorbs the λ weighting, not exactly.
  const DngColor color = dngColorFromQe(idealXyzQe(false), "D65", kColorChecker);
  const glm::dmat3& m = color.calibration1.xyzToCamera;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      if (r == c) continue;
      EXPECT_LT(std::abs(m[c][r]), 0.2 * m[r][r]) << "row " << r << " col " << c;
    }
}

TEST(DngColorFromQe, CalibrationsAndAsShotNeutralFollowTheIlluminant) {
  const auto qe = idealXyzQe(true);
  const DngColor a = dngColorFromQe(qe, "A", kColorChecker);
  const DngColor d65 = dngColorFromQe(qe, "D65", kColorChecker);
  // Illuminant A (EXIF 17) is calibration 1, D65 calibration 2 with the D65-only matrix.
  EXPECT_EQ(a.calibration1.lightSource, 17);
  ASSERT_TRUE(a.calibration2.has_value());
  EXPECT_EQ(a.calibration2->lightSource, 21);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      EXPECT_DOUBLE_EQ(a.calibration2->xyzToCamera[c][r], d65.calibration1.xyzToCamera[c][r]);
  // The A matrix maps the A white to a camera value of largest component 1.
  const glm::dvec3 wA =
      a.calibration1.xyzToCamera * reflectanceToXyz(Spectrum::constant(1.0), cieIlluminant("A"));
  EXPECT_NEAR(std::max({wA.x, wA.y, wA.z}), 1.0, 1e-12);
  // No EXIF code: D65 alone.
  EXPECT_FALSE(dngColorFromQe(qe, "ACES_D60", kColorChecker).calibration2.has_value());
  EXPECT_EQ(exifLightSource("F11"), 14);
  EXPECT_EQ(exifLightSource("D50"), 23);
  EXPECT_EQ(exifLightSource("ACES_D60"), 0);
  const glm::dvec3 whiteA = reflectanceToXyz(Spectrum::constant(1.0), cieIlluminant("A"));
  // Tungsten is red: X_A ≈ 1.0985 is the largest, so the neutral is XYZ_A / X_A.
  EXPECT_DOUBLE_EQ(a.asShotNeutral.x, 1.0);
  EXPECT_NEAR(a.asShotNeutral.y, 1.0 / whiteA.x, 1e-6);
  EXPECT_NEAR(a.asShotNeutral.z, whiteA.z / whiteA.x, 1e-6);
}

TEST(DngColorFromQe, NeedsThreeCurves) {
  const auto qe = idealXyzQe(true);
  EXPECT_THROW(dngColorFromQe({qe[0], qe[1]}, "D65", kColorChecker), InputError);
  EXPECT_THROW(dngColorFromQe(qe, "D65", "/nonexistent/chart.csv"), InputError);
}

TEST(DngColorFromQe, NeutralFromGainsIsTheirInverse) {
  const glm::dvec3 n = dngNeutralFromGains({2.0, 1.0, 1.25});
  EXPECT_DOUBLE_EQ(n.x, 0.5);
  EXPECT_DOUBLE_EQ(n.y, 1.0);
  EXPECT_DOUBLE_EQ(n.z, 0.8);
  // R gain below 1 (R responds more than G): 1/g = (2, 1, 0.5), scaled to max 1.
  const glm::dvec3 red = dngNeutralFromGains({0.5, 1.0, 2.0});
  EXPECT_DOUBLE_EQ(red.x, 1.0);
  EXPECT_DOUBLE_EQ(red.y, 0.5);
  EXPECT_DOUBLE_EQ(red.z, 0.25);
}

}  // namespace
}  // namespace camsim
