// Tests for `camsim psf` (cli/psf_command.cpp): argument parsing and range checks naming the
// option; the real binary (CAMSIM_BINARY) on scenes/lens_double_gauss.yaml writes one EXR
// (channel Y, sum 1) and PNG per (field, wavelength) and a psf.json that parses (python3's
// json) with one entry each; bad input exits 2 naming the option, with nothing written.
// The PSF's numbers are tested against analytic references in
// tests/integrator/camera/psf_image_test.cpp.
#include "cli/psf_command.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cli/args.h"
#include "sensor/io/exr_io.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace psf_command_test {

namespace fs = std::filesystem;
using test::quote;
using test::RunResult;
using test::TempDir;

const fs::path kScene = fs::path(CAMSIM_SOURCE_DIR) / "scenes" / "lens_double_gauss.yaml";

TEST(PsfArgs, ParsesListsAndOptions) {
  PsfArgs a = parsePsfArgs({"psf", "s.yaml"});
  EXPECT_EQ(a.scene, "s.yaml");
  EXPECT_EQ(a.fields, std::vector<double>{0.0});
  EXPECT_EQ(a.wavelengthsNm, std::vector<double>{550.0});
  EXPECT_EQ(a.settings.size, 32);
  EXPECT_EQ(a.settings.oversample, 4);
  EXPECT_EQ(a.outputDir, "out");
  a = parsePsfArgs({"psf", "s.yaml", "--field", "0,0.5,1.2", "--wavelength", "450,650", "--size",
                    "16", "--oversample", "8", "--rays", "5000", "--seed", "7", "--object-distance",
                    "2.5", "-o", "d"});
  EXPECT_EQ(a.fields, (std::vector<double>{0.0, 0.5, 1.2}));
  EXPECT_EQ(a.wavelengthsNm, (std::vector<double>{450.0, 650.0}));
  EXPECT_EQ(a.settings.size, 16);
  EXPECT_EQ(a.settings.oversample, 8);
  EXPECT_EQ(a.settings.rays, 5000);
  EXPECT_EQ(a.settings.seed, 7u);
  EXPECT_DOUBLE_EQ(a.settings.objectDistance, 2.5);
  EXPECT_EQ(a.outputDir, "d");
  EXPECT_TRUE(parsePsfArgs({"psf", "--help"}).help);
  EXPECT_NE(psfUsageText().find("camsim psf"), std::string::npos);
  EXPECT_NE(usageText().find("psf"), std::string::npos);  // listed by camsim --help
  EXPECT_EQ(psfEntryName(0.5, 550.0), "psf_f0.5_550nm");
  EXPECT_EQ(psfEntryName(0.0, 587.6), "psf_f0_587.6nm");
}

TEST(PsfArgs, BadValuesNameTheirOption) {
  using Args = std::vector<std::string>;
  const std::vector<std::pair<Args, std::string>> cases = {
      {{"psf"}, "scene"},
      {{"psf", "s.yaml", "--field", "0,x"}, "--field"},
      {{"psf", "s.yaml", "--field", "2"}, "--field"},
      {{"psf", "s.yaml", "--field", "0,-0.5"}, "--field"},
      {{"psf", "s.yaml", "--wavelength", "200"}, "--wavelength"},
      {{"psf", "s.yaml", "--size", "1000"}, "--size"},
      {{"psf", "s.yaml", "--oversample", "0"}, "--oversample"},
      {{"psf", "s.yaml", "--rays", "10"}, "--rays"},
      {{"psf", "s.yaml", "--object-distance", "-3"}, "--object-distance"},
      // Values that name the same files (%g): the second write failed after the first's
      // files were in place (exit 1; found by probing).
      {{"psf", "s.yaml", "--field", "0,0"}, "--field: 0 is given twice"},
      {{"psf", "s.yaml", "--wavelength", "550,550.0000001"}, "--wavelength: 550 is given twice"},
      // -0 is 0 (it named files "f-0" beside "f0"); integers past their range name it (the
      // message gave the parser's ±2^62 bounds; found by probing).
      {{"psf", "s.yaml", "--field", "0,-0"}, "--field: 0 is given twice"},
      {{"psf", "s.yaml", "--rays", "9223372036854775807"}, "--rays must be in [1000, 100000000]"},
      {{"psf", "s.yaml", "--size", "99999999999"}, "--size must be in [4, 512]"},
  };
  for (const auto& [args, name] : cases) {
    try {
      parsePsfArgs(args);
      ADD_FAILURE() << name << " accepted";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

TEST(PsfBinary, WritesImagesAndJson) {
  TempDir dir;
  const fs::path out = dir.path() / "psf";
  const RunResult r = test::runCamsim("psf " + quote(kScene.string()) +
                                          " --field 0,0.5 --wavelength 550 --size 4 "
                                          "--oversample 8 --rays 20000 -o " +
                                          quote(out.string()),
                                      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("psf_f0.5_550nm: field 0.5 (h 10.817 mm), 550 nm: centroid"),
            std::string::npos)
      << r.out;
  for (const char* name : {"psf_f0_550nm", "psf_f0.5_550nm"}) {
    const ExrFile exr = readExr(out / (std::string(name) + ".exr"));
    ASSERT_EQ(exr.image.channels, std::vector<std::string>{"Y"});
    EXPECT_EQ(exr.image.width, 32);
    double sum = 0.0;
    for (float v : exr.image.pixels) sum += static_cast<double>(v);
    EXPECT_NEAR(sum, 1.0, 1e-4) << name;
    EXPECT_TRUE(fs::is_regular_file(out / (std::string(name) + ".png")));
  }
  const RunResult json = test::runCommand(
      "/usr/bin/python3 -c \"import json, sys; d = json.load(open(sys.argv[1])); "
      "e = d['entries']; assert len(e) == 2 and e[1]['field'] == 0.5, e; "
      "print(e[1]['image_height_mm'], e[1]['lost_fraction'] > e[0]['lost_fraction'])\" " +
          quote((out / "psf.json").string()),
      dir.path());
  ASSERT_EQ(json.exitCode, 0) << json.err;
  // The EXR header's field as the JSON's (std::to_string wrote 1e-7 as "0.000000").
  const auto meta = readExr(out / "psf_f0.5_550nm.exr").metadata;
  const auto field = std::find_if(meta.begin(), meta.end(),
                                  [](const auto& kv) { return kv.first == "camsim:psf_field"; });
  ASSERT_NE(field, meta.end());
  EXPECT_EQ(field->second, "0.5");
  // Half of the 36 × 24 mm sensor's diagonal: 10.8167 mm.
  EXPECT_EQ(json.out.substr(0, 5), "10.81") << json.out;
  EXPECT_NE(json.out.find("True"), std::string::npos) << json.out;
}

TEST(PsfBinary, BadFieldExitsTwoAndWritesNothing) {
  TempDir dir;
  const fs::path out = dir.path() / "psf";
  // The last is refused against the camera, once the scene has loaded: it said "<input>: key
  // 'object_distance'".
  for (const std::string bad :
       {"--field 1.7", "--field 0,abc", "--wavelength 900", "--object-distance 0.001"}) {
    const RunResult r = test::runCamsim(
        "psf " + quote(kScene.string()) + " " + bad + " -o " + quote(out.string()), dir.path());
    EXPECT_EQ(r.exitCode, 2) << bad;
    EXPECT_NE(r.err.find(bad.substr(0, bad.find(' '))), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << bad;
  }
}

}  // namespace psf_command_test
}  // namespace camsim
