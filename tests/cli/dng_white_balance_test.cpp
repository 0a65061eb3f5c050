// The DNG of `camsim render` read by the real tools users develop it with: a grey card
// under CIE illuminant A, developed with `isp: {illuminant: A}`, comes out of `dcraw -w`
// (the DNG's own white balance, AsShotNeutral) neutral within 2 %, and exiftool reads the
// exposure tags (ExposureTime, FNumber, ISO, DateTimeOriginal) and both calibration
// illuminants. dcraw and exiftool are installed by scripts/setup.sh (Debian packages dcraw,
// libimage-exiftool-perl): the test fails, naming the package, when one is missing.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/support/run_command.h"
#include "tests/support/scene_text.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

using test::onPath;

// A camera inside a dome that glows with illuminant A: every photosite sees the A white
// (a grey card under A, up to a constant). Noise off, so the card is exactly uniform.
std::string greyUnder(const std::string& illuminant) {
  return "name: card\n"
         "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [64, 48], "
         "focal_length_mm: 8,\n"
         "         f_number: 4, shutter: {open: 0, close: 0.01}}\n"
         "sensor: {model: fullframe-d850, iso: 200, noise: none,\n"
         "         auto_exposure: {metering: mean, target: 0.3}}\n"
         "isp: {white_balance: illuminant, illuminant: " +
         illuminant +
         "}\n"
         "render: {spp: 4, max_depth: 0}\n"
         "shapes:\n"
         "  - {type: sphere, centre: [0, 0, 0], radius: 10,\n"
         "     emission: {luminance: 100, spectrum: {illuminant: " +
         illuminant + "}, two_sided: true}}\n";
}

// Mean of each channel of a 16-bit binary PPM (P6), dcraw's output with -4 -c.
std::vector<double> ppmMeans(const std::string& bytes) {
  int w = 0, h = 0, maxv = 0, consumed = 0;
  if (std::sscanf(bytes.c_str(), "P6 %d %d %d%n", &w, &h, &maxv, &consumed) != 3) return {};
  const size_t start = static_cast<size_t>(consumed) + 1;
  if (maxv != 65535 || bytes.size() < start + static_cast<size_t>(w) * h * 6) return {};
  std::vector<double> sum(3, 0.0);
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + start);
  for (int i = 0; i < w * h; ++i)
    for (int c = 0; c < 3; ++c)
      sum[static_cast<size_t>(c)] += p[6 * i + 2 * c] * 256 + p[6 * i + 2 * c + 1];
  for (double& s : sum) s /= w * h;
  return sum;
}

TEST(DngWhiteBalance, DcrawDevelopsAGreyCardUnderIlluminantANeutral) {
  ASSERT_TRUE(onPath("dcraw")) << "dcraw is not installed (Debian package dcraw; scripts/setup.sh)";
  ASSERT_TRUE(onPath("exiftool"))
      << "exiftool is not installed (Debian package libimage-exiftool-perl; scripts/setup.sh)";
  test::TempDir dir;
  test::writeFile(dir.path() / "card.yaml", greyUnder("A"));
  const test::RunResult r =
      test::runCamsim("render " + test::quote((dir.path() / "card.yaml").string()) + " -o " +
                          test::quote((dir.path() / "out").string()),
                      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string dng = (dir.path() / "out" / "card.dng").string();
  // The raw EXR says what it holds (DN and electrons, not the film's lm·s).
  const std::string rawExr = test::readFile(dir.path() / "out" / "card_raw.exr");
  EXPECT_NE(rawExr.find("raw.DN: raw digital numbers"), std::string::npos);
  EXPECT_EQ(rawExr.find("lm*s"), std::string::npos);

  // -w: the camera's white balance (AsShotNeutral); -4: linear 16 bit; -c: to stdout.
  const test::RunResult dev = test::runCommand("dcraw -w -4 -c " + test::quote(dng), dir.path());
  ASSERT_EQ(dev.exitCode, 0) << dev.err;
  const std::vector<double> m = ppmMeans(dev.out);
  ASSERT_EQ(m.size(), 3u) << "dcraw did not write a 16-bit PPM";
  std::printf("[measured] dcraw -w, grey card under A: R/G %.4f B/G %.4f\n", m[0] / m[1],
              m[2] / m[1]);
  EXPECT_GT(m[1], 1000.0);
  EXPECT_NEAR(m[0] / m[1], 1.0, 0.02);
  EXPECT_NEAR(m[2] / m[1], 1.0, 0.02);

  const test::RunResult exif = test::runCommand(
      "exiftool -s -ExposureTime -FNumber -ISO -DateTimeOriginal -FocalLength "
      "-CalibrationIlluminant1 -CalibrationIlluminant2 " +
          test::quote(dng),
      dir.path());
  ASSERT_EQ(exif.exitCode, 0) << exif.err;
  SCOPED_TRACE(exif.out);
  EXPECT_NE(exif.out.find("ExposureTime"), std::string::npos);
  EXPECT_NE(exif.out.find("FNumber                         : 4.0"), std::string::npos);
  EXPECT_NE(exif.out.find("ISO                             : 200"), std::string::npos);
  EXPECT_NE(exif.out.find("DateTimeOriginal                : 2000:01:01 00:00:00"),
            std::string::npos);
  EXPECT_NE(exif.out.find("FocalLength                     : 8.0 mm"), std::string::npos);
  EXPECT_NE(exif.out.find("CalibrationIlluminant1          : Standard Light A"), std::string::npos);
  EXPECT_NE(exif.out.find("CalibrationIlluminant2          : D65"), std::string::npos);
}

}  // namespace
}  // namespace camsim
