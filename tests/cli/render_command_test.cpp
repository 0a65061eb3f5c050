// Tests for the `camsim` command line (cli/args.cpp, cli/render_command.cpp, cli/main.cpp):
// parseArgs as a unit, then the real binary (CAMSIM_BINARY) run through the shell — exit
// codes, "file:line:col" error messages, no output at all after a bad scene, and a small
// render whose EXR carries the expected channels and metadata.
#include "cli/args.h"
#include "tests/support/temp_dir.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/render_command.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/fnv1a.h"
#include "sensor/io/exr_io.h"
#include "tests/support/run_command.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

using test::quote;
using test::readFile;
using test::runCommand;
using test::RunResult;
using test::writeFile;

namespace fs = std::filesystem;

// ---- parseArgs -------------------------------------------------------------------------

TEST(ParseArgs, RenderDefaults) {
  const Command cmd = parseArgs({"render"});
  EXPECT_EQ(cmd.kind, Command::Kind::kRender);
  EXPECT_FALSE(cmd.render.scene.has_value());
  EXPECT_EQ(cmd.render.outputDir, "out");
  EXPECT_FALSE(cmd.render.overrides.spp.has_value());
  EXPECT_FALSE(cmd.render.overrides.seed.has_value());
  EXPECT_EQ(cmd.render.threads, 0);
}

TEST(ParseArgs, AllOptions) {
  const Command cmd = parseArgs(
      {"render", "box.yaml", "-o", "dir", "--spp", "16", "--seed", "42", "--threads", "3"});
  EXPECT_EQ(cmd.kind, Command::Kind::kRender);
  EXPECT_EQ(cmd.render.scene, "box.yaml");
  EXPECT_EQ(cmd.render.outputDir, "dir");
  EXPECT_EQ(cmd.render.overrides.spp, 16);
  EXPECT_EQ(cmd.render.overrides.seed, 42);
  EXPECT_EQ(cmd.render.threads, 3);
  EXPECT_EQ(parseArgs({"render", "--output", "o2"}).render.outputDir, "o2");
  EXPECT_EQ(
      parseArgs({"render", "--spp", std::to_string(SceneLimits::kMaxSpp)}).render.overrides.spp,
      SceneLimits::kMaxSpp);
}

TEST(ParseArgs, HelpAndVersion) {
  EXPECT_EQ(parseArgs({"--help"}).kind, Command::Kind::kHelp);
  EXPECT_EQ(parseArgs({"-h"}).kind, Command::Kind::kHelp);
  EXPECT_EQ(parseArgs({"render", "--help"}).kind, Command::Kind::kHelp);
  EXPECT_EQ(parseArgs({"--version"}).kind, Command::Kind::kVersion);
  EXPECT_NE(usageText().find("Usage:"), std::string::npos);
}

TEST(ParseArgs, BadUsageThrows) {
  using Args = std::vector<std::string>;
  for (const Args& args :
       {Args{}, Args{"draw"}, Args{"render", "--bogus"}, Args{"render", "--spp", "abc"},
        Args{"render", "--spp", "12x"}, Args{"render", "--spp", ""}, Args{"render", "--spp", "0"},
        Args{"render", "--spp", std::to_string(SceneLimits::kMaxSpp + 1)},
        Args{"render", "--spp", "99999999999999999999"}, Args{"render", "--seed", "-1"},
        Args{"render", "--threads", "0"}, Args{"render", "--spp"}, Args{"render", "-o", ""},
        Args{"render", "a.yaml", "b.yaml"}}) {
    std::string joined;
    for (const auto& a : args) joined += "'" + a + "' ";
    EXPECT_THROW(parseArgs(args), UsageError) << joined;
  }
}

// ---- the binary ------------------------------------------------------------------------

using test::TempDir;

// Runs `program args` with stdout and stderr captured into files in logDir.
RunResult runProgram(const std::string& program, const std::string& args, const fs::path& logDir) {
  return runCommand(quote(program) + " " + args, logDir);
}

RunResult camsim(const std::string& args, const fs::path& logDir) {
  return test::runCamsim(args, logDir);
}

std::vector<std::string> filesUnder(const fs::path& dir) {
  std::vector<std::string> names;
  if (!fs::exists(dir)) return names;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    names.push_back(fs::relative(entry.path(), dir).string());
  return names;
}

TEST(CamsimBinary, HelpAndVersion) {
  TempDir dir;
  RunResult r = camsim("--help", dir.path());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("Usage:"), std::string::npos) << r.out;
  // Every command is listed (issue 35: dataset was missing).
  for (const char* command : {"render", "merge", "dataset", "ptc", "bench"})
    EXPECT_NE(r.out.find(std::string("  ") + command + " "), std::string::npos) << command << r.out;
  // Each command's --help comes from its option table: every override flag, with its range.
  r = camsim("render --help", dir.path());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  for (const OverrideSetting& s : overrideSettings())
    EXPECT_NE(r.out.find(overrideFlag(s)), std::string::npos) << s.key << r.out;
  EXPECT_NE(r.out.find("[0.5, 10000]"), std::string::npos) << r.out;
  for (const char* command : {"merge", "dataset", "ptc"}) {
    r = camsim(std::string(command) + " --help", dir.path());
    EXPECT_EQ(r.exitCode, 0) << command << r.err;
    EXPECT_NE(r.out.find(std::string("camsim ") + command), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("--output"), std::string::npos) << r.out;
  }
  r = camsim("--version", dir.path());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.out, "camsim 0.1.0\n");
}

TEST(CamsimBinary, BadUsageExitsTwo) {
  TempDir dir;
  RunResult r = camsim("render --bogus", dir.path());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("unknown option '--bogus'"), std::string::npos) << r.err;
  // A misspelt option with its value, after or before the scene: the option is named, alone
  // (CLI11's own message listed every extra, reversed: "unexpected argument 'x.exr --out'").
  for (const char* args : {"render s.yaml --out x.exr", "render --out=x.exr s.yaml"}) {
    r = camsim(args, dir.path());
    EXPECT_EQ(r.exitCode, 2) << args;
    EXPECT_NE(r.err.find("camsim: unknown option '--out' (try 'camsim render --help')"),
              std::string::npos)
        << args << ": " << r.err;
  }
  r = camsim("render a.yaml b.yaml", dir.path());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("unexpected argument 'b.yaml'"), std::string::npos) << r.err;
  r = camsim("frobnicate", dir.path());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("unknown command 'frobnicate'"), std::string::npos) << r.err;
  r = camsim("", dir.path());
  EXPECT_EQ(r.exitCode, 2);
  r = camsim("render --spp 0", dir.path());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--spp"), std::string::npos) << r.err;
}

TEST(CamsimBinary, NonexistentSceneExitsTwo) {
  TempDir dir;
  const fs::path scene = dir.path() / "no_such_scene.yaml";
  const fs::path out = dir.path() / "out";
  const RunResult r =
      camsim("render " + quote(scene.string()) + " -o " + quote(out.string()), dir.path());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find(scene.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cannot open scene file"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

// Lines 1–7; the shape is on line 8 (the value of radius at column 47).
const std::string kPrefix =
    "camera:\n  position: [0, 0, -1]\n  look_at: [0, 0, 0]\n  resolution: [8, 8]\n"
    "materials:\n  m: {type: diffuse}\nshapes:\n";

struct BadScene {
  const char* name;
  std::string text;
  std::string location;  // ":line:col"
  std::string key;       // "" when none applies
};

const BadScene kBadScenes[] = {
    {"SyntaxError", kPrefix + "  - {type: sphere, centre: [0, 0, 0], radius: 1, material: m\n",
     ":8:5", ""},
    {"UnknownKey",
     kPrefix + "  - {type: sphere, centre: [0, 0, 0], radius: 1, material: m}\nfoo: 1\n", ":9:1",
     "foo"},
    {"NegativeSize", kPrefix + "  - {type: sphere, centre: [0, 0, 0], radius: -2, material: m}\n",
     ":8:47", "shapes[0].radius"},
    {"MissingMeshFile", kPrefix + "  - type: mesh\n    material: m\n    file: nowhere.obj\n",
     ":10:11", "shapes[0].file"},
    {"NaN", kPrefix + "  - {type: sphere, centre: [0, .nan, 0], radius: 1, material: m}\n", ":8:32",
     "shapes[0].centre[1]"},
    {"WrongType", kPrefix + "  - {type: sphere, centre: [0, 0, 0], radius: big, material: m}\n",
     ":8:47", "shapes[0].radius"},
    {"ZeroResolution",
     "camera:\n  position: [0, 0, -1]\n  look_at: [0, 0, 0]\n  resolution: [8, 0]\n"
     "shapes:\n  - {type: sphere, centre: [0, 0, 0], radius: 1}\n",
     ":4:19", "camera.resolution[1]"},
};

void PrintTo(const BadScene& s, std::ostream* os) {
  *os << s.name;
}

class CamsimBadScene : public ::testing::TestWithParam<BadScene> {};

TEST_P(CamsimBadScene, ExitsTwoWithLocationAndWritesNothing) {
  const BadScene& c = GetParam();
  TempDir dir;
  const fs::path scene = dir.path() / "BAD.yaml";
  writeFile(scene, c.text);
  const fs::path out = dir.path() / "out";
  fs::create_directories(out);
  const RunResult r =
      camsim("render " + quote(scene.string()) + " -o " + quote(out.string()), dir.path());
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find(scene.string() + c.location + ": "), std::string::npos)
      << "expected " << c.location << " in: " << r.err;
  if (!c.key.empty()) {
    EXPECT_NE(r.err.find("key '" + c.key + "'"), std::string::npos) << r.err;
  }
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_TRUE(filesUnder(out).empty()) << "left behind: " << filesUnder(out).front();
  // A directory that did not exist is not created for a scene that fails to load.
  const fs::path fresh = dir.path() / "fresh";
  EXPECT_EQ(camsim("render " + quote(scene.string()) + " -o " + quote(fresh.string()), dir.path())
                .exitCode,
            2);
  EXPECT_FALSE(fs::exists(fresh));
}

INSTANTIATE_TEST_SUITE_P(Scenes, CamsimBadScene, ::testing::ValuesIn(kBadScenes),
                         [](const ::testing::TestParamInfo<BadScene>& param) {
                           return std::string(param.param.name);
                         });

// The Cornell box scene at 32×32 px, written next to the test's other files.
std::string smallCornellBox() {
  std::string text = readFile(fs::path(CAMSIM_SOURCE_DIR) / "scenes" / "cornell_box.yaml");
  const std::string from = "resolution: [512, 512]";
  const size_t at = text.find(from);
  if (at == std::string::npos) return "";
  return text.replace(at, from.size(), "resolution: [32, 32]");
}

// The sidecar lists the files the scene loader read (input_files), in the order read.
TEST(CamsimBinary, SidecarListsTheFilesTheSceneRead) {
  TempDir dir;
  writeFile(dir.path() / "grey.csv", "wavelength_nm,r\n360,0.5\n830,0.5\n");
  writeFile(dir.path() / "tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
  writeFile(dir.path() / "files.yaml",
            "camera: {position: [0, 0, -2], look_at: [0, 0, 0], resolution: [8, 8]}\n"
            "materials: {grey: {type: diffuse, reflectance: {csv: grey.csv}}}\n"
            "shapes:\n  - {type: mesh, file: tri.obj, material: grey}\n"
            "  - {type: sphere, centre: [0, 2, -1], radius: 0.3, emission: {luminance: 1000}}\n");
  const fs::path out = dir.path() / "out";
  const RunResult r = camsim("render " + quote((dir.path() / "files.yaml").string()) + " -o " +
                                 quote(out.string()) + " --spp 1",
                             dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string json = readFile(out / "files.json");
  const std::string expected = "\"input_files\": [\"" + (dir.path() / "grey.csv").string() +
                               "\", \"" + (dir.path() / "tri.obj").string() + "\"]";
  EXPECT_NE(json.find(expected), std::string::npos) << expected << "\n" << json;
}

// Issue 34: a file named through `..` was listed as the loader opened it
// (DIR/scenes/../grey.csv); it is listed lexically normal, DIR/grey.csv.
TEST(CamsimBinary, SidecarListsInputFilesWithoutDotDot) {
  TempDir dir;
  writeFile(dir.path() / "grey.csv", "wavelength_nm,r\n360,0.5\n830,0.5\n");
  writeFile(dir.path() / "tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
  fs::create_directories(dir.path() / "scenes");
  writeFile(dir.path() / "scenes" / "files.yaml",
            "camera: {position: [0, 0, -2], look_at: [0, 0, 0], resolution: [8, 8]}\n"
            "materials: {grey: {type: diffuse, reflectance: {csv: ../grey.csv}}}\n"
            "shapes:\n  - {type: mesh, file: ./../tri.obj, material: grey}\n"
            "  - {type: sphere, centre: [0, 2, -1], radius: 0.3, emission: {luminance: 1000}}\n");
  const fs::path out = dir.path() / "out";
  // The scene named relative to the working directory: its inputs stay relative.
  const RunResult r =
      runCommand("cd " + quote(dir.path().string()) + " && " + quote(CAMSIM_BINARY) +
                     " render scenes/files.yaml -o " + quote(out.string()) + " --spp 1",
                 dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string json = readFile(out / "files.json");
  const std::string expected = "\"input_files\": [\"grey.csv\", \"tri.obj\"]";
  EXPECT_NE(json.find(expected), std::string::npos) << expected << "\n" << json;
}

// Issue 34: focus at infinity (no focus_distance_m) was written as a focus distance of 0 m.
TEST(CamsimBinary, SidecarWritesNullForFocusAtInfinity) {
  TempDir dir;
  for (const std::string focus : {"", ", focus_distance_m: 3"}) {
    writeFile(dir.path() / "focus.yaml",
              "camera: {position: [0, 0, -2], look_at: [0, 0, 0], resolution: [8, 8], f_number: "
              "2" +
                  focus +
                  "}\n"
                  "shapes: [{type: sphere, centre: [0, 0, 0], radius: 0.5, emission: "
                  "{luminance: 1000}}]\n");
    const fs::path out = dir.path() / "out";
    const RunResult r = camsim("render " + quote((dir.path() / "focus.yaml").string()) + " -o " +
                                   quote(out.string()) + " --spp 1",
                               dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string json = readFile(out / "focus.json");
    const std::string expected =
        focus.empty() ? "\"focus_distance_m\": null," : "\"focus_distance_m\": 3,";
    EXPECT_NE(json.find(expected), std::string::npos) << expected << "\n" << json;
  }
}

TEST(CamsimBinary, RendersSmallSceneToExrAndPng) {
  TempDir dir;
  const std::string text = smallCornellBox();
  ASSERT_FALSE(text.empty()) << "scenes/cornell_box.yaml no longer has resolution [512, 512]";
  const fs::path scene = dir.path() / "small_box.yaml";
  writeFile(scene, text);
  const fs::path out = dir.path() / "out" / "nested";  // created by camsim
  const RunResult r = camsim("render " + quote(scene.string()) + " -o " + quote(out.string()) +
                                 " --spp 2 --seed 5 --threads 2",
                             dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("rendered cornell_box: 32x32, 2 spp"), std::string::npos) << r.err;

  std::vector<std::string> files = filesUnder(out);
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files,
            (std::vector<std::string>{"cornell_box.exr", "cornell_box.json", "cornell_box.png"}));
  const std::string json = readFile(out / "cornell_box.json");
  EXPECT_NE(json.find("\"display\": \"sRGB\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"view\": \"ACES 1.0 - SDR Video\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"spp\": 2"), std::string::npos) << json;
  EXPECT_NE(json.find("\"input_files\": []"), std::string::npos) << json;  // reads no file
  const std::string png = readFile(out / "cornell_box.png");
  ASSERT_GE(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");

  const ExrFile exr = readExr(out / "cornell_box.exr");
  EXPECT_EQ(exr.image.width, 32);
  EXPECT_EQ(exr.image.height, 32);
  EXPECT_EQ(exr.image.channelCount(), 6);
  for (const char* ch : {"R", "G", "B", "XYZ.X", "XYZ.Y", "XYZ.Z"})
    EXPECT_GE(exr.image.channelIndex(ch), 0) << ch;
  auto meta = [&](const std::string& key) -> std::string {
    for (const auto& [k, v] : exr.metadata)
      if (k == key) return v;
    ADD_FAILURE() << "no metadata " << key;
    return "";
  };
  EXPECT_EQ(meta("camsim:spp"), "2");
  EXPECT_EQ(meta("camsim:seed"), "5");
  EXPECT_EQ(meta("camsim:version"), "0.1.0");
  EXPECT_EQ(meta("camsim:scene_fnv1a64"), fnv1aHex(text));
  const std::string seconds = meta("camsim:render_seconds");
  EXPECT_FALSE(seconds.empty());
  EXPECT_GE(std::atof(seconds.c_str()), 0.0);
  EXPECT_TRUE(exr.chromaticities.has_value());

  // Absolute units: the luminance of the lit scene is positive and finite everywhere.
  const int y = exr.image.channelIndex("XYZ.Y");
  ASSERT_GE(y, 0);
  double sum = 0.0;
  for (int py = 0; py < 32; ++py)
    for (int px = 0; px < 32; ++px) {
      const float v = exr.image.at(px, py, y);
      ASSERT_TRUE(std::isfinite(v));
      sum += static_cast<double>(v);
    }
  EXPECT_GT(sum, 0.0);

  // (e) OpenEXR's own tool reads the file, when installed.
  if (std::system("command -v exrheader >/dev/null 2>&1") != 0) GTEST_SKIP() << "no exrheader";
  const RunResult h =
      runProgram("exrheader", quote((out / "cornell_box.exr").string()), dir.path());
  EXPECT_EQ(h.exitCode, 0) << h.err;
  EXPECT_NE(h.out.find("camsim:spp"), std::string::npos) << h.out;
}

}  // namespace
}  // namespace camsim

namespace camsim {
namespace {

TEST(ParseArgsExposure, ExposureOverridesParseAndValidate) {
  const Command c = parseArgs({"render", "s.yaml", "--exposure-time", "0.004", "--f-number", "2.8",
                               "--iso", "800", "--noise", "photon", "--noise-seed", "5"});
  EXPECT_DOUBLE_EQ(*c.render.overrides.exposureTimeS, 0.004);
  EXPECT_DOUBLE_EQ(*c.render.overrides.fNumber, 2.8);
  EXPECT_DOUBLE_EQ(*c.render.overrides.iso, 800.0);
  EXPECT_EQ(*c.render.overrides.noise, NoiseMode::kPhoton);
  EXPECT_EQ(*c.render.overrides.noiseSeed, 5);
  for (const auto& bad : std::vector<std::vector<std::string>>{{"render", "--exposure-time", "0"},
                                                               {"render", "--f-number", "-2"},
                                                               {"render", "--iso", "abc"},
                                                               {"render", "--noise", "loud"}})
    EXPECT_THROW(parseArgs(bad), UsageError);
}

}  // namespace
}  // namespace camsim

namespace camsim {
namespace {

// A user OCIO config on the command line is used (and named in the sidecar); a bad
// display fails with exit code 2 before rendering, writing nothing.
TEST(CamsimBinary, UserOcioConfigIsUsedAndBadDisplayIsRejected) {
  TempDir dir;
  writeFile(dir.path() / "small_box.yaml", smallCornellBox());
  writeFile(dir.path() / "user.ocio",
            "ocio_profile_version: 2.1\n"
            "roles: {scene_linear: lin, default: lin}\n"
            "file_rules: [!<Rule> {name: Default, colorspace: lin}]\n"
            "displays: {Studio: [!<View> {name: Plain, colorspace: out}]}\n"
            "colorspaces:\n"
            "  - !<ColorSpace> {name: lin, aliases: [ACEScg]}\n"
            "  - !<ColorSpace> {name: out, from_scene_reference: !<ExponentTransform> {value: 2.2, "
            "direction: inverse}}\n");
  const fs::path out = dir.path() / "out";
  const std::string scene = quote((dir.path() / "small_box.yaml").string());
  const RunResult ok =
      camsim("render " + scene + " -o " + quote(out.string()) + " --spp 1 --ocio-config " +
                 quote((dir.path() / "user.ocio").string()) + " --display Studio --view Plain",
             dir.path());
  ASSERT_EQ(ok.exitCode, 0) << ok.err;
  const std::string json = readFile(out / "cornell_box.json");
  EXPECT_NE(json.find("user.ocio"), std::string::npos) << json;
  EXPECT_NE(json.find("\"display\": \"Studio\""), std::string::npos) << json;

  // Refused after the output folder was made: the folders the run made are removed again
  // (out2/a/b was left behind, empty).
  const fs::path out2 = dir.path() / "out2";
  const RunResult bad = camsim(
      "render " + scene + " -o " + quote((out2 / "a" / "b").string()) + " --spp 1 --display Nope",
      dir.path());
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("Nope"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(out2));
}

}  // namespace
}  // namespace camsim
