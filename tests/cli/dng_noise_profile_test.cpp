// The DNGs of `camsim render` carry the noise the sensor model drew at the scene's ISO: a
// sensor written here (14 bit, black 512, base ISO 100, 2 e⁻/DN, σ_pre 3 e⁻, σ_post 1.5 DN),
// rendered at ISO 800 with two brackets, read back by exiftool (Debian package
// libimage-exiftool-perl; scripts/setup.sh). Expected, with K = 800/100/2 = 4 DN/e⁻ and
// r = 16383 − 512: NoiseProfile S = K/r, O = (K²·3² + 1.5²)/r² for each of R, G, B;
// BaselineExposure 0; ExposureBiasValue = the bracket's EV; AsShotNeutral = 1/g of the ISP's
// gains, which dcraw reads back as its camera multipliers.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/run_command.h"
#include "tests/support/scene_text.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim::dng_noise_profile_test {
namespace {

using test::onPath;

const char* const kSensor =
    "name: noisy\n"
    "pixel_pitch_um: 4.0\n"
    "cfa: RGGB\n"
    "qe: {curves: cameras/nikon_d850.csv, peak_qe: 0.5}\n"
    "full_well_e: 40000\n"
    "base_iso: 100\n"
    "conversion_gain_e_per_dn: 2\n"
    "read_noise_e: 3\n"
    "read_noise_post_dn: 1.5\n"
    "adc_bits: 14\n"
    "black_level_dn: 512\n";

// A camera inside a glowing D65 dome, the sensor above at ISO 800, brackets −1 and 0 EV.
const char* const kScene =
    "name: dome\n"
    "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [32, 24], "
    "focal_length_mm: 8,\n"
    "         f_number: 4, shutter: {open: 0, close: 0.01}}\n"
    "sensor: {model: noisy.yaml, iso: 800, bracket_ev: [-1, 0]}\n"
    "render: {spp: 1, max_depth: 0}\n"
    "shapes:\n"
    "  - {type: sphere, centre: [0, 0, 0], radius: 10,\n"
    "     emission: {luminance: 10, spectrum: {illuminant: D65}, two_sided: true}}\n";

// The numbers after the tag on the line "Tag : …" (exiftool -s -n) or "Tag: …" (dcraw -i -v,
// tag with its colon), empty if absent.
std::vector<double> values(const std::string& text, const std::string& tag) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind(tag + " ", 0) != 0) continue;
    std::istringstream in(line.substr(line.find(':', tag.size() - 1) + 1));
    std::vector<double> out;
    for (double v = 0.0; in >> v;) out.push_back(v);
    return out;
  }
  return {};
}

TEST(DngNoiseProfile, RenderWritesTheSensorsNoiseAtTheScenesIso) {
  ASSERT_TRUE(onPath("exiftool"))
      << "exiftool is not installed (Debian package libimage-exiftool-perl; scripts/setup.sh)";
  test::TempDir dir;
  test::writeFile(dir.path() / "noisy.yaml", kSensor);
  test::writeFile(dir.path() / "dome.yaml", kScene);
  const test::RunResult r =
      test::runCamsim("render " + test::quote((dir.path() / "dome.yaml").string()) + " -o " +
                          test::quote((dir.path() / "out").string()),
                      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const double k = 800.0 / 100.0 / 2.0, range = 16383.0 - 512.0;
  const double scale = k / range, offset = (k * k * 9.0 + 2.25) / (range * range);
  // The ISP's white-balance gains, from the sidecar's isp.derived.white_balance_gains.
  const std::string sidecar = test::readFile(dir.path() / "out" / "dome.json");
  const size_t at = sidecar.find("\"white_balance_gains\"");
  ASSERT_NE(at, std::string::npos);
  std::string list = sidecar.substr(sidecar.find('[', at) + 1);
  list = list.substr(0, list.find(']'));
  for (char& c : list) c = c == ',' ? ' ' : c;
  const std::vector<double> gains = values("g : " + list, "g");
  ASSERT_TRUE(onPath("dcraw")) << "dcraw is not installed (Debian package dcraw; scripts/setup.sh)";
  for (const char* ev : {"-1", "+0"}) {
    SCOPED_TRACE(ev);
    const std::string dng = (dir.path() / "out" / (std::string("dome_ev") + ev + ".dng")).string();
    const test::RunResult exif = test::runCommand(
        "exiftool -s -n -NoiseProfile -BaselineExposure -ExposureCompensation -ISO "
        "-AsShotNeutral " +
            test::quote(dng),
        dir.path());
    ASSERT_EQ(exif.exitCode, 0) << exif.err;
    SCOPED_TRACE(exif.out);
    std::printf("[exiftool -s -n dome_ev%s.dng]\n%s", ev, exif.out.c_str());
    const std::vector<double> profile = values(exif.out, "NoiseProfile");
    ASSERT_EQ(profile.size(), 6u);
    for (size_t plane = 0; plane < 3; ++plane) {
      EXPECT_NEAR(profile[2 * plane], scale, 1e-13 * scale);
      EXPECT_NEAR(profile[2 * plane + 1], offset, 1e-13 * offset);
    }
    EXPECT_EQ(values(exif.out, "BaselineExposure"), std::vector<double>{0.0});
    EXPECT_EQ(values(exif.out, "ExposureCompensation"),
              std::vector<double>{std::string(ev) == "-1" ? -1.0 : 0.0});
    EXPECT_EQ(values(exif.out, "ISO"), std::vector<double>{800.0});
    // The camera's response to D65, 1/g of the ISP's gains (the sidecar's), largest
    // component 1 (G for this sensor); dcraw reads the same gains back as its multipliers.
    const std::vector<double> neutral = values(exif.out, "AsShotNeutral");
    ASSERT_EQ(neutral.size(), 3u);
    ASSERT_EQ(gains.size(), 3u);
    EXPECT_DOUBLE_EQ(neutral[1], 1.0);
    for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(neutral[c] * gains[c], 1.0, 1e-6) << c;
    const test::RunResult dcraw = test::runCommand("dcraw -i -v " + test::quote(dng), dir.path());
    ASSERT_EQ(dcraw.exitCode, 0) << dcraw.err;
    const std::vector<double> multipliers = values(dcraw.out, "Camera multipliers:");
    ASSERT_EQ(multipliers.size(), 4u) << dcraw.out;
    for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(multipliers[c], gains[c], 1e-5) << dcraw.out;
  }
}

}  // namespace
}  // namespace camsim::dng_noise_profile_test
