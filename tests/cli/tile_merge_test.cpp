// One frame split across processes (camsim render --tiles k/M, camsim merge; cli/
// merge_command.h, integrator/capture/tile_parts.h), through the real binary: the merged
// parts are every file `camsim render --reproducible` writes, byte for byte — a scene with a
// sensor (full noise, auto-exposure and a bracket on the assembled film), ground truth with
// ID mattes, AOV previews; split in 3, in 1, and in more shares than tiles; a moving scene
// without a sensor. A missing, duplicate or foreign part, a changed scene file, a file that
// is no part: exit code 2, a message naming the file, nothing written. Captures that cannot
// be tiled are refused before a part is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cli/args.h"
#include "cli/merge_command.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;
using test::quote;
using test::RunResult;

// 40 × 24 px: 3 × 2 tiles of 16 px, the last column and row clipped.
const char* kSensorScene =
    "name: tiled\n"
    "camera: {position: [0, 0, 0], look_at: [0, 0, -1], resolution: [40, 24], f_number: 2.8,\n"
    "         focal_length_mm: 0.06}\n"
    "sensor: {model: smartphone-1.4um, iso: 100, noise: full, noise_seed: 2,\n"
    "         auto_exposure: {metering: mean}, bracket_ev: [-1, 0]}\n"
    "render: {spp: 2, max_depth: 2, aovs: [depth, normal, instance_id, class_id]}\n"
    "materials: {grey: {type: diffuse, reflectance: 0.5}, red: {type: plastic, reflectance: "
    "{rgb: [0.7, 0.1, 0.1]}, roughness: 0.3}}\n"
    "shapes:\n"
    "  - {name: lamp, type: sphere, centre: [0, 3, -3], radius: 0.5, emission: {luminance: "
    "2000}}\n"
    "  - {name: wall, type: rectangle, corner: [-5, -5, -4], edge_u: [10, 0, 0], edge_v: [0, 10, "
    "0], material: grey}\n"
    "  - {name: ball, class: ball, type: sphere, centre: [0.3, 0, -2.5], radius: 0.5, material: "
    "red}\n";

// A ball moving during the exposure, no sensor (the picture is exposed on the whole film);
// with `sensor` text the camera takes the sensor's pixel pitch.
std::string movingScene(const std::string& sensor = "") {
  return "name: moving\n"
         "camera: {position: [0, 0, 0], look_at: [0, 0, -1], resolution: [40, 24], f_number: "
         "2.8,\n" +
         std::string(sensor.empty() ? "  focal_length_mm: 6, sensor_width_mm: 5.6, "
                                      "sensor_height_mm: 3.36,\n"
                                    : "  focal_length_mm: 0.06,\n") +
         "  shutter: {open: 0, close: 0.05}}\n" + sensor +
         "render: {spp: 2, max_depth: 2, aovs: [instance_id]}\n"
         "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
         "shapes:\n"
         "  - {name: lamp, type: sphere, centre: [0, 3, -3], radius: 0.5, emission: {luminance: "
         "2000}}\n"
         "  - {name: wall, type: rectangle, corner: [-5, -5, -4], edge_u: [10, 0, 0], edge_v: [0, "
         "10, 0], material: grey}\n"
         "  - {name: ball, type: sphere, centre: [0, 0, -2.5], radius: 0.5, material: grey,\n"
         "     motion: [{time: 0, translate: [0, 0, 0]}, {time: 0.05, translate: [0.5, 0, 0]}]}\n";
}

// The command line's overrides every run of the sensor scene takes (recorded in the parts).
const std::string kOverrides = " --spp 3 --seed 5 --noise-seed 11 --exposure-time 0.0125";

// Name → bytes of every file in dir.
std::map<std::string, std::string> fileContents(const fs::path& dir) {
  std::map<std::string, std::string> files;
  if (!fs::exists(dir)) return files;
  for (const auto& f : fs::directory_iterator(dir))
    files[f.path().filename().string()] = test::readFile(f.path());
  return files;
}

class TileMerge : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    temp_ = std::make_unique<test::TempDir>();
    test::writeFile(dir() / "tiled.yaml", kSensorScene);
    test::writeFile(dir() / "moving.yaml", movingScene());
    RunResult r = render("tiled.yaml", "ref", " --reproducible --aov-previews" + kOverrides);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = render("moving.yaml", "ref_moving", " --reproducible");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    splitInto("tiled.yaml", "parts3", 3, kOverrides);
  }
  static void TearDownTestSuite() { temp_.reset(); }

  static const fs::path& dir() { return temp_->path(); }
  static RunResult render(const std::string& scene, const std::string& out,
                          const std::string& flags) {
    return test::runCamsim("render " + quote((dir() / scene).string()) + " -o " +
                               quote((dir() / out).string()) + flags,
                           dir());
  }
  // The M parts of scene into dir()/out, one process each.
  static void splitInto(const std::string& scene, const std::string& out, int m,
                        const std::string& flags) {
    for (int k = 0; k < m; ++k) {
      const RunResult r =
          render(scene, out,
                 " --threads 1 --tiles " + std::to_string(k) + "/" + std::to_string(m) + flags);
      ASSERT_EQ(r.exitCode, 0) << r.err;
    }
  }
  static std::string part(const std::string& out, const std::string& name, int k, int m) {
    return (dir() / out /
            (name + ".part-" + std::to_string(k) + "-of-" + std::to_string(m) + ".exr"))
        .string();
  }
  static RunResult merge(const std::vector<std::string>& parts, const std::string& out,
                         const std::string& flags = "") {
    std::string args = "merge";
    for (const std::string& p : parts) args += " " + quote(p);
    return test::runCamsim(args + " -o " + quote((dir() / out).string()) + flags, dir());
  }
  // The merge of parts 0 … m−1 of `name` in dir()/parts into dir()/out.
  static RunResult mergeAll(const std::string& parts, const std::string& name, int m,
                            const std::string& out, const std::string& flags = "") {
    std::vector<std::string> files;
    for (int k = 0; k < m; ++k) files.push_back(part(parts, name, k, m));
    return merge(files, out, flags);
  }
  static void expectSameFiles(const std::string& ref, const std::string& got) {
    const auto expected = fileContents(dir() / ref), actual = fileContents(dir() / got);
    ASSERT_GE(expected.size(), 3u);  // NAME.exr, .png, .json at least
    for (const auto& [name, bytes] : expected) {
      const auto it = actual.find(name);
      ASSERT_NE(it, actual.end()) << got << " has no " << name;
      EXPECT_TRUE(it->second == bytes)
          << name << " differs (" << it->second.size() << " vs " << bytes.size() << " bytes)";
    }
    EXPECT_EQ(actual.size(), expected.size()) << got;
  }
  // Exit code 2, the message names `file` (and says `what`), and `out` was not written.
  static void expectRefused(const RunResult& r, const std::string& file, const std::string& what,
                            const std::string& out) {
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir() / out)) << out << " was created";
  }

  static std::unique_ptr<test::TempDir> temp_;
};

std::unique_ptr<test::TempDir> TileMerge::temp_;

TEST_F(TileMerge, ThreePartsMergeToTheRenderByteForByte) {
  const auto parts = fileContents(dir() / "parts3");
  ASSERT_EQ(parts.size(), 3u);  // the parts and nothing else
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(parts.count("tiled.part-" + std::to_string(k) + "-of-3.exr")) << k;
    std::printf("tiled.part-%d-of-3.exr: %zu bytes\n", k,
                parts.at("tiled.part-" + std::to_string(k) + "-of-3.exr").size());
  }
  const RunResult r = merge(
      {part("parts3", "tiled", 2, 3), part("parts3", "tiled", 0, 3), part("parts3", "tiled", 1, 3)},
      "merged3", " --aov-previews");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("merged 3 parts of tiled"), std::string::npos) << r.err;
  expectSameFiles("ref", "merged3");
  // exr, png, json, acescg, 2 × (dng, raw exr), 4 previews (depth, normal, instance, class)
  EXPECT_EQ(fileContents(dir() / "merged3").size(), 12u);
  // The bracket's DNG, the raw EXRs, the ACEScg EXR, previews: all compared.
  EXPECT_TRUE(fs::exists(dir() / "merged3" / "tiled_ev-1.dng"));
  EXPECT_TRUE(fs::exists(dir() / "merged3" / "tiled_instance.png"));
}

TEST_F(TileMerge, OnePartMergesToTheRender) {
  splitInto("tiled.yaml", "parts1", 1, kOverrides);
  const RunResult r = merge({part("parts1", "tiled", 0, 1)}, "merged1", " --aov-previews");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectSameFiles("ref", "merged1");
}

TEST_F(TileMerge, MoreSharesThanTilesMergeToo) {
  splitInto("tiled.yaml", "parts8", 8, kOverrides);  // 6 tiles: parts 6 and 7 hold none
  const RunResult r = mergeAll("parts8", "tiled", 8, "merged8", " --aov-previews");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectSameFiles("ref", "merged8");
}

TEST_F(TileMerge, MovingSceneWithoutSensorMerges) {
  splitInto("moving.yaml", "parts_moving", 2, "");
  const RunResult r = mergeAll("parts_moving", "moving", 2, "merged_moving");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectSameFiles("ref_moving", "merged_moving");
}

// Found by probing: the parts of a guided render carried no guide statistics, so the
// merged NAME.json lacked render.guide and was not the render's bytes.
TEST_F(TileMerge, GuidedSceneMergesWithItsGuide) {
  ASSERT_EQ(render("moving.yaml", "ref_guided", " --reproducible --guiding 1 --spp 8").exitCode, 0);
  splitInto("moving.yaml", "parts_guided", 2, " --guiding 1 --spp 8");
  const RunResult r = mergeAll("parts_guided", "moving", 2, "merged_guided");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectSameFiles("ref_guided", "merged_guided");
  const std::string json = fileContents(dir() / "merged_guided").at("moving.json");
  EXPECT_NE(json.find("\"guide\": {"), std::string::npos) << json;
}

// Nothing run-dependent is left in a reproducible render: the thread count does not show.
TEST_F(TileMerge, ReproducibleRenderIsTheSameBytesOnOneThread) {
  const RunResult r = render("tiled.yaml", "ref_1thread",
                             " --reproducible --aov-previews --threads 1" + kOverrides);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectSameFiles("ref", "ref_1thread");
}

TEST_F(TileMerge, MissingPartIsAnError) {
  const RunResult r =
      merge({part("parts3", "tiled", 0, 3), part("parts3", "tiled", 2, 3)}, "out_missing");
  expectRefused(r, "tiled.part-1-of-3.exr", "part 1 of 3 is missing", "out_missing");
}

TEST_F(TileMerge, DuplicatePartIsAnError) {
  const RunResult r = merge({part("parts3", "tiled", 0, 3), part("parts3", "tiled", 1, 3),
                             part("parts3", "tiled", 1, 3), part("parts3", "tiled", 2, 3)},
                            "out_duplicate");
  expectRefused(r, part("parts3", "tiled", 1, 3), "given twice", "out_duplicate");
}

TEST_F(TileMerge, PartOfAnotherSeedIsAnError) {
  ASSERT_EQ(render("tiled.yaml", "parts_seed", " --tiles 2/3 --spp 3 --seed 6").exitCode, 0);
  const RunResult r = merge({part("parts3", "tiled", 0, 3), part("parts3", "tiled", 1, 3),
                             part("parts_seed", "tiled", 2, 3)},
                            "out_seed");
  expectRefused(r, part("parts_seed", "tiled", 2, 3), "not a part of the same render", "out_seed");
  EXPECT_NE(r.err.find("camsim:seed"), std::string::npos) << r.err;
}

TEST_F(TileMerge, PartOfAnotherSceneIsAnError) {
  test::writeFile(dir() / "other" / "tiled.yaml", std::string(kSensorScene) + "# another\n");
  ASSERT_EQ(render("other/tiled.yaml", "parts_other", " --tiles 1/3" + kOverrides).exitCode, 0);
  const RunResult r = merge({part("parts3", "tiled", 0, 3), part("parts_other", "tiled", 1, 3),
                             part("parts3", "tiled", 2, 3)},
                            "out_other");
  expectRefused(r, part("parts_other", "tiled", 1, 3), "not a part of the same render",
                "out_other");
  EXPECT_NE(r.err.find("camsim:scene"), std::string::npos) << r.err;
}

TEST_F(TileMerge, PartOfAnotherSplitIsAnError) {
  ASSERT_EQ(render("tiled.yaml", "parts_m2", " --tiles 1/2" + kOverrides).exitCode, 0);
  const RunResult r = merge({part("parts3", "tiled", 0, 3), part("parts3", "tiled", 1, 3),
                             part("parts3", "tiled", 2, 3), part("parts_m2", "tiled", 1, 2)},
                            "out_m2");
  expectRefused(r, part("parts_m2", "tiled", 1, 2), "camsim:tile_count", "out_m2");
}

TEST_F(TileMerge, ChangedSceneFileIsAnError) {
  test::writeFile(dir() / "changing" / "tiled.yaml", kSensorScene);
  ASSERT_EQ(render("changing/tiled.yaml", "parts_changing", " --tiles 0/1").exitCode, 0);
  test::writeFile(dir() / "changing" / "tiled.yaml", std::string(kSensorScene) + "# edited\n");
  const RunResult r = merge({part("parts_changing", "tiled", 0, 1)}, "out_changing");
  expectRefused(r, (dir() / "changing" / "tiled.yaml").string(), "changed since", "out_changing");
}

TEST_F(TileMerge, NotAPartIsAnError) {
  const RunResult r = merge({(dir() / "ref" / "tiled.exr").string()}, "out_notpart");
  expectRefused(r, (dir() / "ref" / "tiled.exr").string(), "not a camsim tile part", "out_notpart");
}

// A re-render after metering needs the whole film; a sequence is one capture per frame.
TEST_F(TileMerge, CapturesThatCannotBeTiledAreRefused) {
  const std::string sensor = "sensor: {model: smartphone-1.4um, ";
  struct UntileableCase {
    std::string name, text, key;
  } cases[] = {
      {"auto", movingScene(sensor + "auto_exposure: {metering: mean}}\n"), "sensor.auto_exposure"},
      {"bracket", movingScene(sensor + "bracket_ev: [0, 1]}\n"), "sensor.bracket_ev"},
      {"sequence", movingScene() + "frames: {count: 2, rate_hz: 20}\n", "frames"},
  };
  for (const UntileableCase& c : cases) {
    test::writeFile(dir() / (c.name + ".yaml"), c.text);
    const RunResult r = render(c.name + ".yaml", "parts_" + c.name, " --tiles 0/2");
    EXPECT_EQ(r.exitCode, 2) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find(c.name + ".yaml"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.key), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("cannot be split into tiles"), std::string::npos) << r.err;
    EXPECT_TRUE(fileContents(dir() / ("parts_" + c.name)).empty()) << c.name;
  }
  // Without the re-render (a fixed exposure, or a 0 EV bracket only) the moving scene tiles.
  test::writeFile(dir() / "fixed.yaml", movingScene(sensor + "bracket_ev: [0]}\n"));
  const RunResult fixed = render("fixed.yaml", "parts_fixed", " --tiles 0/2");
  EXPECT_EQ(fixed.exitCode, 0) << fixed.err;
  // Adaptive sampling scales its checks by the whole image's mean. Refused by the flag that
  // asked for it (found by probing: the scene file was named, which has no such key)...
  const RunResult adaptive =
      render("fixed.yaml", "parts_adaptive", " --tiles 0/2 --adaptive-threshold 0.1");
  EXPECT_EQ(adaptive.exitCode, 2) << adaptive.err;
  EXPECT_NE(adaptive.err.find("<command line>: key '--adaptive-threshold'"), std::string::npos)
      << adaptive.err;
  EXPECT_EQ(adaptive.err.find("fixed.yaml"), std::string::npos) << adaptive.err;
  EXPECT_NE(adaptive.err.find("cannot be split into tiles"), std::string::npos) << adaptive.err;
  EXPECT_TRUE(fileContents(dir() / "parts_adaptive").empty());
  // ... or by the scene file's key when the file asked for it.
  std::string inFile = movingScene();
  const std::string renderKeys = "render: {spp: 2, ";
  inFile.replace(inFile.find(renderKeys), renderKeys.size(),
                 "render: {spp: 2, adaptive_threshold: 0.1, ");
  test::writeFile(dir() / "adaptive.yaml", inFile);
  const RunResult fromFile = render("adaptive.yaml", "parts_adaptive", " --tiles 0/2");
  EXPECT_EQ(fromFile.exitCode, 2) << fromFile.err;
  EXPECT_NE(fromFile.err.find("adaptive.yaml: key 'render.adaptive_threshold'"), std::string::npos)
      << fromFile.err;
}

TEST(TileMergeArgs, TilesAndReproducibleParse) {
  const Command cmd = parseArgs({"render", "s.yaml", "--tiles", "2/5", "--reproducible"});
  ASSERT_TRUE(cmd.render.tiles.has_value());
  EXPECT_EQ(cmd.render.tiles->index, 2);
  EXPECT_EQ(cmd.render.tiles->count, 5);
  EXPECT_TRUE(cmd.render.reproducible);
  EXPECT_FALSE(parseArgs({"render"}).render.tiles.has_value());
  EXPECT_FALSE(parseArgs({"render"}).render.reproducible);
  for (const char* bad : {"5/5", "-1/3", "1", "1/0", "a/3", "1/3x", "/3", "1/"})
    EXPECT_THROW(parseArgs({"render", "--tiles", bad}), UsageError) << bad;
  // The picture's flags belong to the merge.
  EXPECT_THROW(parseArgs({"render", "--tiles", "0/2", "--aov-previews"}), UsageError);
  EXPECT_THROW(parseArgs({"render", "--tiles", "0/2", "--view", "Un-tone-mapped"}), UsageError);
  EXPECT_NE(usageText().find("merge"), std::string::npos);
  EXPECT_NE(renderUsageText().find("--tiles k/M"), std::string::npos);

  const MergeArgs m = parseMergeArgs({"merge", "a.exr", "b.exr", "-o", "d", "--scene", "s.yaml",
                                      "--display", "sRGB", "--aov-previews"});
  EXPECT_EQ(m.parts, (std::vector<std::string>{"a.exr", "b.exr"}));
  EXPECT_EQ(m.outputDir, "d");
  EXPECT_EQ(m.scene, "s.yaml");
  EXPECT_EQ(m.display, "sRGB");
  EXPECT_TRUE(m.aovPreviews);
  EXPECT_THROW(parseMergeArgs({"merge"}), UsageError);
  EXPECT_THROW(parseMergeArgs({"merge", "a.exr", "--bogus"}), UsageError);
  EXPECT_TRUE(parseMergeArgs({"merge", "--help"}).help);
}

}  // namespace
}  // namespace camsim
