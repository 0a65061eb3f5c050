// Tests for `camsim expose` (cli/expose_command.cpp): argument parsing, then the real binary
// (CAMSIM_BINARY): a render's raw EXR exposed again reproduces the render's raw DN at its own
// seed, ISO and exposure; the same seed gives the same bytes, another seed other bytes; a
// moving scene's electrons are refused at another exposure (exit 2, saying why); bad input
// (missing file, no electrons layer, an ISO outside the calibrated range, --frames 0) exits
// 2 with the file and key named and nothing written.
#include "cli/expose_command.h"
#include "tests/support/temp_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli/args.h"
#include "sensor/io/exr_io.h"
#include "tests/support/run_command.h"
#include "tests/support/text_file.h"

namespace camsim::expose_command_test {
namespace {

namespace fs = std::filesystem;
using test::quote;
using test::readFile;
using test::RunResult;
using test::TempDir;

// A 24×24 sensor scene of a fraction of a second; `motion`: the camera slides 0.2 m during
// the 10 ms exposure.
std::string scene(const std::string& name, bool motion) {
  return "format: camsim-scene/1\nname: " + name +
         "\nrender: {spp: 2}\n"
         "camera: {position: [0, 0, -3], look_at: [0, 0, 0], resolution: [24, 24], "
         "focal_length_mm: 0.05, shutter: {open: 0, close: 0.01}" +
         (motion ? ", motion: [{time: 0, translate: [0, 0, 0]}, {time: 0.01, translate: [0.2, 0, "
                   "0]}]"
                 : "") +
         "}\n"
         "sensor: {model: smartphone-1.4um, iso: 200, noise: full, noise_seed: 9}\n"
         "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
         "shapes:\n"
         "  - {name: lamp, type: sphere, centre: [0, 2, 0], radius: 0.5, emission: {luminance: "
         "20000}}\n"
         "  - {name: ball, type: sphere, centre: [0, 0, 0], radius: 1, material: grey}\n";
}

// Renders scene(name, motion) into dir/render; returns its NAME_raw.exr.
fs::path renderRaw(const fs::path& dir, const std::string& name, bool motion) {
  const fs::path yaml = dir / (name + ".yaml");
  test::writeFile(yaml, scene(name, motion));
  const RunResult r = test::runCamsim(
      "render " + quote(yaml.string()) + " -o " + quote((dir / "render").string()), dir);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return dir / "render" / (name + "_raw.exr");
}

// A raw EXR's raw.DN channel (its other channels are the electrons).
std::vector<float> rawDn(const fs::path& rawExr) {
  const Image image = readExr(rawExr).image;
  const int c = image.channelIndex("raw.DN");
  EXPECT_GE(c, 0) << rawExr;
  return c < 0 ? std::vector<float>{} : image.channel(c).pixels;
}

std::size_t fileCount(const fs::path& dir) {
  std::size_t n = 0;
  if (fs::exists(dir))
    for (const auto& e : fs::directory_iterator(dir)) n += e.is_regular_file();
  return n;
}

TEST(ExposeArgs, ParsesTheOptions) {
  ExposeArgs a = parseExposeArgs({"expose", "x_raw.exr"});
  EXPECT_EQ(a.input, "x_raw.exr");
  EXPECT_EQ(a.outputDir, "out");
  EXPECT_EQ(a.settings.frames, 1);
  EXPECT_FALSE(a.settings.seed.has_value());
  EXPECT_FALSE(a.settings.iso.has_value());
  a = parseExposeArgs({"expose", "x_raw.exr", "--sensor", "s.yaml", "--iso", "800",
                       "--exposure-scale", "0.25", "--frames", "16", "--seed", "3", "--noise",
                       "photon", "-o", "d"});
  EXPECT_EQ(a.settings.sensor, "s.yaml");
  EXPECT_EQ(a.settings.iso, 800.0);
  EXPECT_EQ(a.settings.exposureScale, 0.25);
  EXPECT_EQ(a.settings.frames, 16);
  EXPECT_EQ(a.settings.seed, 3u);
  EXPECT_EQ(a.settings.noise, "photon");
  EXPECT_EQ(a.outputDir, "d");
  EXPECT_TRUE(parseExposeArgs({"expose", "--help"}).help);
  EXPECT_NE(exposeUsageText().find("electrons.<channel>"), std::string::npos);
  EXPECT_NE(usageText().find("expose"), std::string::npos);
  using Args = std::vector<std::string>;
  for (const Args& args : {Args{"expose"}, Args{"expose", "a", "b"}, Args{"expose", "a", "--x"},
                           Args{"expose", "a", "--frames", "two"},
                           Args{"expose", "a", "--seed", "-1"}, Args{"expose", "a", "-o", ""}})
    EXPECT_THROW(parseExposeArgs(args), UsageError) << args.back();
}

TEST(ExposeBinary, ReproducesTheRenderAndSeedsDecideTheBytes) {
  TempDir dir;
  const fs::path raw = renderRaw(dir.path(), "still", false);
  ASSERT_TRUE(fs::exists(raw));
  const fs::path a = dir.path() / "a", b = dir.path() / "b", c = dir.path() / "c";
  // The file's own seed, ISO and exposure: frame 0 is the render's raw, DN for DN.
  RunResult r =
      test::runCamsim("expose " + quote(raw.string()) + " -o " + quote(a.string()), dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(rawDn(a / "still_f0000_raw.exr"), rawDn(raw));
  // Four frames at another ISO and half the exposure, twice with seed 5, once with seed 6.
  const std::string opts = " --frames 4 --iso 400 --exposure-scale 0.5 --seed ";
  for (const auto& [out, seed] : {std::pair{a, "5"}, std::pair{b, "5"}, std::pair{c, "6"}}) {
    r = test::runCamsim(
        "expose " + quote(raw.string()) + opts + seed + " -o " + quote(out.string()), dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
  }
  EXPECT_NE(r.err.find("exposed 4 frames of 24x24"), std::string::npos) << r.err;
  for (const char* f : {"still_f0000.dng", "still_f0003.dng", "still_f0003_raw.exr"}) {
    EXPECT_EQ(readFile(a / f), readFile(b / f)) << f;
    EXPECT_NE(readFile(a / f), readFile(c / f)) << f;
  }
  EXPECT_NE(readFile(a / "still_f0000.dng"), readFile(a / "still_f0001.dng"));
  const ExrFile f3 = readExr(a / "still_f0003_raw.exr");
  bool scaled = false;
  for (const auto& [k, v] : f3.metadata)
    scaled = scaled || (k == "camsim:exposure_time_s" && v == "0.005");
  EXPECT_TRUE(scaled);
}

// The raw EXR records the frame's exposure time and ISO exactly, once each (found by
// probing: written with %f, 12.3456789 µs read back as 12 µs and 0.4 µs as 0, so expose's
// dark signal and EXIF ExposureTime were wrong; a second exposure_time_s entry shadowed the
// exact one).
TEST(ExposeBinary, RawHeaderKeepsTheExposureTimeAndIsoExactly) {
  TempDir dir;
  std::string text = scene("short", false);
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"close: 0.01", "close: 4e-7"},
                                 {"iso: 200", "iso: 123.456789"}})
    text.replace(text.find(from), from.size(), to);
  test::writeFile(dir.path() / "short.yaml", text);
  const RunResult r = test::runCamsim("render " + quote((dir.path() / "short.yaml").string()) +
                                          " -o " + quote((dir.path() / "render").string()),
                                      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::vector<std::string> times, isos;
  for (const auto& [k, v] : readExr(dir.path() / "render" / "short_raw.exr").metadata) {
    if (k == "camsim:exposure_time_s") times.push_back(v);
    if (k == "camsim:iso") isos.push_back(v);
  }
  EXPECT_EQ(times, std::vector<std::string>{"4e-07"});
  EXPECT_EQ(isos, std::vector<std::string>{"123.456789"});
}

// A sensor with dark frames: expose adds one per frame as the render does, so frame 0 is the
// render's raw (found by probing: expose drew the parametric noise instead).
TEST(ExposeBinary, DarkFramesAreAddedAsTheRenderAddsThem) {
  TempDir dir;
  const fs::path raw = renderRaw(dir.path(), "still", false);
  // Four dark frames: the render's electrons at a 1e-12 exposure, as DNGs.
  const fs::path dark = dir.path() / "dark";
  RunResult r =
      test::runCamsim("expose " + quote(raw.string()) +
                          " --exposure-scale 1e-12 --frames 4 --seed 99 -o " + quote(dark.string()),
                      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (int f = 0; f < 4; ++f) fs::remove(dark / ("still_f000" + std::to_string(f) + "_raw.exr"));
  std::string sensor = readFile(fs::path(CAMSIM_LUTS_DIR) / "sensors" / "smartphone-1.4um.yaml");
  sensor.replace(sensor.find("name: smartphone-1.4um"), 22, "name: phone-dark");
  const fs::path sensorFile = dir.path() / "dark_sensor.yaml";
  test::writeFile(sensorFile, sensor + "dark_frames: dark\n");
  std::string text = scene("df", false);
  const std::string from = "model: smartphone-1.4um";
  text.replace(text.find(from), from.size(), "model: dark_sensor.yaml");
  test::writeFile(dir.path() / "df.yaml", text);
  r = test::runCamsim("render " + quote((dir.path() / "df.yaml").string()) + " -o " +
                          quote((dir.path() / "render").string()),
                      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const fs::path dfRaw = dir.path() / "render" / "df_raw.exr";
  const auto exposedDn = [&](const std::string& options, const std::string& out) {
    const RunResult e = test::runCamsim(
        "expose " + quote(dfRaw.string()) + options + " -o " + quote((dir.path() / out).string()),
        dir.path());
    EXPECT_EQ(e.exitCode, 0) << e.err;
    return rawDn(dir.path() / out / "df_f0000_raw.exr");
  };
  const std::vector<float> rendered = rawDn(dfRaw);
  EXPECT_EQ(exposedDn(" --sensor " + quote(sensorFile.string()), "x"), rendered);
  // The same sensor without its dark frames draws other noise.
  test::writeFile(dir.path() / "plain_sensor.yaml", sensor);
  EXPECT_NE(exposedDn(" --sensor " + quote((dir.path() / "plain_sensor.yaml").string()), "plain"),
            rendered);
}

// A sensor description file named like a preset (found by probing: exposed without --sensor,
// the preset was used, its noise not the file's): the raw EXR says where the sensor came from
// (camsim:sensor_source), and expose then needs the file.
TEST(ExposeBinary, ASensorFileNamedLikeAPresetNeedsTheFile) {
  TempDir dir;
  const fs::path preset = renderRaw(dir.path(), "bypreset", false);
  const Metadata presetMeta = readExr(preset).metadata;
  ASSERT_NE(findMetadata(presetMeta, "camsim:sensor_source"), nullptr);
  EXPECT_EQ(*findMetadata(presetMeta, "camsim:sensor_source"), "preset");

  std::string sensor = readFile(fs::path(CAMSIM_LUTS_DIR) / "sensors" / "smartphone-1.4um.yaml");
  const std::string dark = "dark_current_e_per_s: 2.0";  // the preset's, here 2,500× higher
  ASSERT_NE(sensor.find(dark), std::string::npos);
  sensor.replace(sensor.find(dark), dark.size(), "dark_current_e_per_s: 5000");
  test::writeFile(dir.path() / "smartphone-1.4um.yaml", sensor);
  std::string text = scene("byfile", false);
  const std::string from = "model: smartphone-1.4um";
  text.replace(text.find(from), from.size(), "model: ./smartphone-1.4um.yaml");
  test::writeFile(dir.path() / "byfile.yaml", text);
  RunResult r = test::runCamsim("render " + quote((dir.path() / "byfile.yaml").string()) + " -o " +
                                    quote((dir.path() / "render").string()),
                                dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const fs::path raw = dir.path() / "render" / "byfile_raw.exr";
  const Metadata meta = readExr(raw).metadata;
  ASSERT_NE(findMetadata(meta, "camsim:sensor_source"), nullptr);
  EXPECT_EQ(*findMetadata(meta, "camsim:sensor_source"), "file");
  EXPECT_EQ(*findMetadata(meta, "camsim:sensor"), "smartphone-1.4um");

  const fs::path refused = dir.path() / "refused";
  r = test::runCamsim("expose " + quote(raw.string()) + " -o " + quote(refused.string()),
                      dir.path());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("byfile_raw.exr: key 'sensor': the recorded sensor 'smartphone-1.4um' "
                       "was read from a sensor description file, not a preset"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(fileCount(refused), 0u);
  // With the file: the render's own DN again, and the output records the file too.
  r = test::runCamsim("expose " + quote(raw.string()) + " --sensor " +
                          quote((dir.path() / "smartphone-1.4um.yaml").string()) + " -o " +
                          quote((dir.path() / "again").string()),
                      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const fs::path again = dir.path() / "again" / "byfile_f0000_raw.exr";
  EXPECT_EQ(rawDn(again), rawDn(raw));
  EXPECT_EQ(*findMetadata(readExr(again).metadata, "camsim:sensor_source"), "file");
}

TEST(ExposeBinary, MovingSceneIsRefusedAtAnotherExposure) {
  TempDir dir;
  const fs::path raw = renderRaw(dir.path(), "moving", true);
  ASSERT_TRUE(fs::exists(raw));
  const fs::path out = dir.path() / "out";
  RunResult r = test::runCamsim(
      "expose " + quote(raw.string()) + " --exposure-scale 2 -o " + quote(out.string()),
      dir.path());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("moving_raw.exr"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("key 'exposure_scale'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("moves during the exposure (pinhole, time (moving camera"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("depend on the shutter"), std::string::npos) << r.err;
  EXPECT_EQ(fileCount(out), 0u);
  // New noise at the recorded exposure is exact, moving or not.
  r = test::runCamsim("expose " + quote(raw.string()) + " --seed 1 -o " + quote(out.string()),
                      dir.path());
  EXPECT_EQ(r.exitCode, 0) << r.err;
}

TEST(ExposeBinary, BadInputExitsTwoNamingFileAndKeyAndWritesNothing) {
  TempDir dir;
  const fs::path raw = renderRaw(dir.path(), "still", false);
  const fs::path out = dir.path() / "out";
  const auto expose = [&](const std::string& args) {
    return test::runCamsim("expose " + args + " -o " + quote(out.string()), dir.path());
  };
  RunResult r = expose(quote((dir.path() / "nope_raw.exr").string()));
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("nope_raw.exr"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no such file"), std::string::npos) << r.err;
  // The main EXR has the film, not the electrons.
  r = expose(quote((dir.path() / "render" / "still.exr").string()));
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("still.exr: key 'electrons.<channel>'"), std::string::npos) << r.err;
  r = expose(quote(raw.string()) + " --frames 0");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("key 'frames': value 0 is out of range [1, 100000]"), std::string::npos)
      << r.err;
  // --threads with every command's range (command_line.h's addThreadsOption).
  r = expose(quote(raw.string()) + " --threads -3");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--threads must be in [1, 1024], got -3"), std::string::npos) << r.err;
  // A sensor calibrated from ISO 50 to 800 (the preset, renamed, with an iso_table).
  std::string text = readFile(fs::path(CAMSIM_LUTS_DIR) / "sensors" / "smartphone-1.4um.yaml");
  text += "\niso_table:\n  - {iso: 50}\n  - {iso: 800}\n";
  const fs::path yaml = dir.path() / "smartphone-1.4um.yaml";
  test::writeFile(yaml, text);
  r = expose(quote(raw.string()) + " --sensor " + quote(yaml.string()) + " --iso 3200");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("still_raw.exr: key 'iso'"), std::string::npos) << r.err;
  r = expose(quote(raw.string()) + " --sensor fullframe-d850");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("'fullframe-d850'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'smartphone-1.4um'"), std::string::npos) << r.err;
  r = expose(quote(raw.string()) + " --frames 2 --noise loud");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("key 'noise'"), std::string::npos) << r.err;
  EXPECT_EQ(fileCount(out), 0u);
}

}  // namespace
}  // namespace camsim::expose_command_test
