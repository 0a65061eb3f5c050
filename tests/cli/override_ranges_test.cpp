// Every override's boundary values through every front end (issue 35, "settings defined
// once"): for each ranged setting of integrator/scene/overrides.h's table, lo, hi and the
// nearest values just outside them (for an open bound: lo itself, refused, and the next
// double above, accepted) go to
//   - the library: setOverrideText + applyOverrides on a scene with a sensor,
//   - the CLI's argument parser (parseArgs) and the camsim binary itself,
//   - a dataset manifest (`set:` of the scene key; resolveItem loads it as the runner does),
// and each must accept exactly the values in the table's range. python/tests/
// test_override_ranges.py feeds the same table (camsim.override_settings()) to Python.
// The binary runs with --max-memory-gb 1e-9: an accepted value passes the overrides and
// stops at the memory guard (exit 2, "estimated"), a refused one stops at the flag (exit
// 2, naming the flag and the range), so no render runs.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "cli/args.h"
#include "integrator/dataset/dataset_item.h"
#include "integrator/dataset/manifest.h"
#include "integrator/scene/overrides.h"
#include "integrator/scene/scene_loader.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

const char* kOverrideScene =
    "name: probe\nrender: {spp: 1}\n"
    "camera: {position: [0, 0, -3], look_at: [0, 0, 0], resolution: [8, 8], "
    "focal_length_mm: 0.01, shutter: {open: 0, close: 0.01}}\n"
    "sensor: {model: smartphone-1.4um}\n"
    "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
    "shapes:\n"
    "  - {type: sphere, centre: [0, 2, 0], radius: 0.5, emission: {luminance: 100}}\n"
    "  - {type: sphere, centre: [0, 0, 0], radius: 1, material: grey}\n";

std::string shortest(double v) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, r.ptr);
}

struct Case {
  const OverrideSetting* setting;
  std::string text;  // the value as a command line or a manifest writes it
  bool accepted;     // by the table's range
};

// lo, hi and their nearest neighbours outside (inside, for an open lower bound).
std::vector<Case> boundaryCases() {
  std::vector<Case> out;
  for (const OverrideSetting& s : overrideSettings()) {
    if (s.type == OverrideType::kInteger) {
      const IntegerRange r = s.integers;
      out.push_back({&s, std::to_string(r.lo), true});
      out.push_back({&s, std::to_string(r.hi), true});
      out.push_back({&s, std::to_string(r.lo - 1), false});  // lo ≥ 0: no overflow
      // hi + 1 as text (hi may be INT64_MAX).
      std::string above = std::to_string(r.hi);
      for (std::size_t i = above.size(); i-- > 0;) {
        if (above[i] != '9') {
          ++above[i];
          break;
        }
        above[i] = '0';
        if (i == 0) above.insert(above.begin(), '1');
      }
      out.push_back({&s, above, false});
    } else if (s.type == OverrideType::kNumber) {
      const SettingRange r = s.numbers;
      const double inf = std::numeric_limits<double>::infinity();
      out.push_back({&s, shortest(r.lo), !r.loOpen});
      if (r.loOpen)
        out.push_back({&s, shortest(std::nextafter(r.lo, inf)), true});
      else
        out.push_back({&s, shortest(std::nextafter(r.lo, -inf)), false});
      out.push_back({&s, shortest(r.hi), true});
      out.push_back({&s, shortest(std::nextafter(r.hi, inf)), false});
    }
  }
  return out;
}

std::string describe(const Case& c) {
  return std::string(c.setting->key) + " = " + c.text + " (expected " +
         (c.accepted ? "accepted" : "refused") + ")";
}

SceneDescription probeScene() {
  return loadSceneFromText(kOverrideScene, "probe.yaml", ".");
}

TEST(OverrideRanges, TableHasEveryRangedSetting) {
  std::vector<std::string> keys;
  for (const Case& c : boundaryCases())
    if (keys.empty() || keys.back() != c.setting->key) keys.emplace_back(c.setting->key);
  EXPECT_EQ(keys, (std::vector<std::string>{"spp", "seed", "target_error", "time_limit_s",
                                            "adaptive_threshold", "exposure_time_s", "f_number",
                                            "iso", "noise_seed", "guiding"}));
  EXPECT_EQ(boundaryCases().size(), 40u);
}

TEST(OverrideRanges, LibraryApplyAgreesWithTheTable) {
  for (const Case& c : boundaryCases()) {
    SceneDescription d = probeScene();
    bool accepted = true;
    try {
      Overrides o;
      const OverrideSource source{SourceLocation{"", 0, 0}, std::string(c.setting->key)};
      setOverrideText(o, *c.setting, c.text, source);
      applyOverrides(d, o, {"<test>", 0, 0});
    } catch (const InputError& e) {
      accepted = false;
      EXPECT_NE(e.message().find(overrideRangeText(*c.setting)), std::string::npos) << e.what();
    }
    EXPECT_EQ(accepted, c.accepted) << describe(c);
  }
}

TEST(OverrideRanges, CommandLineParserAgreesWithTheTable) {
  for (const Case& c : boundaryCases()) {
    const std::string flag = overrideFlag(*c.setting);
    bool accepted = true;
    try {
      const Command cmd = parseArgs({"render", flag, c.text});
      SceneDescription d = probeScene();
      applyOverrides(d, cmd.render.overrides, {"<command line>", 0, 0});
    } catch (const UsageError& e) {
      accepted = false;
      const std::string what = e.what();
      EXPECT_NE(what.find(flag), std::string::npos) << what;
      EXPECT_NE(what.find(overrideRangeText(*c.setting)), std::string::npos) << what;
    }
    EXPECT_EQ(accepted, c.accepted) << describe(c);
  }
}

TEST(OverrideRanges, ManifestAgreesWithTheTable) {
  const test::TempDir dir;
  test::writeFile(dir.path() / "base.yaml", kOverrideScene);
  for (const Case& c : boundaryCases()) {
    // The scene key a manifest sets; an exposure time T is a shutter open from 0 to T.
    const std::string key = c.setting->key == "exposure_time_s" ? "camera.shutter.close"
                                                                : std::string(c.setting->sceneKey);
    const std::string text =
        "format: camsim-dataset/1\nscene: base.yaml\nseeds: fixed\n"
        "items:\n  - {" +
        key + ": " + c.text + "}\n";
    bool accepted = true;
    try {
      const Manifest m = parseManifest(text, "m.yaml", dir.path());
      ASSERT_EQ(m.items.size(), 1u);
      (void)resolveItem(m, m.items[0], "");
    } catch (const InputError& e) {
      accepted = false;
      EXPECT_NE(std::string(e.what()).find("m.yaml"), std::string::npos) << e.what();
    }
    EXPECT_EQ(accepted, c.accepted) << describe(c);
  }
}

TEST(OverrideRanges, BinaryAgreesWithTheTable) {
  const test::TempDir dir;
  test::writeFile(dir.path() / "probe.yaml", kOverrideScene);
  for (const Case& c : boundaryCases()) {
    const std::string flag = overrideFlag(*c.setting);
    const test::RunResult r =
        test::runCamsim("render " + test::quote((dir.path() / "probe.yaml").string()) + " -o " +
                            test::quote((dir.path() / "out").string()) + " --max-memory-gb 1e-9 " +
                            flag + " " + test::quote(c.text),
                        dir.path());
    EXPECT_EQ(r.exitCode, 2) << describe(c) << r.err;
    const bool accepted = r.err.find("estimated") != std::string::npos;
    EXPECT_EQ(accepted, c.accepted) << describe(c) << "\n" << r.err;
    if (!c.accepted) {
      EXPECT_NE(r.err.find(flag), std::string::npos) << r.err;
      EXPECT_NE(r.err.find(overrideRangeText(*c.setting)), std::string::npos) << r.err;
    }
  }
}

// The issue's examples, as a new user types them.
TEST(OverrideRanges, IssueExamplesExitTwoNamingFlagAndRange) {
  const test::TempDir dir;
  test::writeFile(dir.path() / "probe.yaml", kOverrideScene);
  for (const auto& [flag, value, range] :
       {std::tuple<std::string, std::string, std::string>{"--f-number", "0.3", "[0.5, 10000]"},
        {"--iso", "0.5", "[1, 10000000]"}}) {
    const test::RunResult r =
        test::runCamsim("render " + test::quote((dir.path() / "probe.yaml").string()) + " -o " +
                            test::quote((dir.path() / "out").string()) + " " + flag + " " + value,
                        dir.path());
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find(flag + ": value " + value + " is out of range " + range),
              std::string::npos)
        << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "probe.exr"));
}

// Found by probing: --spp above the scene's render.max_spp rendered (the sidecar then said
// "stopped by max_spp" at more than max_spp), while the same spp in the file is refused.
TEST(OverrideRanges, SppAboveTheScenesMaxSppIsRefused) {
  const SceneDescription base = loadSceneFromText(
      [] {
        std::string yaml = kOverrideScene;
        const std::string from = "render: {spp: 1}";
        return yaml.replace(yaml.find(from), from.size(),
                            "render: {spp: 8, max_spp: 16, target_error: 0.01}");
      }(),
      "probe.yaml", ".");
  for (const std::int64_t spp : {8, 16, 17, 1 << 20}) {
    SceneDescription d = base;
    Overrides o;
    o.spp = spp;
    if (spp <= 16) {
      applyOverrides(d, o, {"<test>", 0, 0});
      EXPECT_EQ(d.render.spp, spp);
      continue;
    }
    try {
      applyOverrides(d, o, {"<test>", 0, 0});
      ADD_FAILURE() << "took spp " << spp;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "render.spp");
      EXPECT_NE(e.message().find("above the scene's render.max_spp 16"), std::string::npos)
          << e.what();
    }
  }
}

// A sequence's exposure override (found by probing): with frames.shutter_angle_deg it
// changed the camera's curve, which the frames do not use, and nothing happened; it now sets
// the angle. Either way an exposure longer than the frame period is refused, as the loader
// refuses it in the file.
TEST(OverrideRanges, ExposureOfASequenceSetsItsAngleWithinTheFramePeriod) {
  const std::string yaml = kOverrideScene;
  const SceneDescription byCurve =
      loadSceneFromText(yaml + "frames: {count: 2, rate_hz: 24}\n", "probe.yaml", ".");
  const SceneDescription byAngle = loadSceneFromText(
      yaml + "frames: {count: 2, rate_hz: 24, shutter_angle_deg: 180}\n", "probe.yaml", ".");
  for (const SceneDescription* base : {&byCurve, &byAngle}) {
    SceneDescription d = *base;
    Overrides o;
    o.exposureTimeS = 0.005;
    applyOverrides(d, o, {"<test>", 0, 0});
    const Shutter s = d.frameCamera(1).shutter;
    EXPECT_NEAR(s.effectiveTime(), 0.005, 1e-15);
    EXPECT_NEAR(s.open(), 1.0 / 24.0, 1e-15);
    if (base == &byAngle) {
      EXPECT_NEAR(*d.frames->shutterAngleDeg, 43.2, 1e-12);
    }
    d = *base;
    o.exposureTimeS = 0.05;
    try {
      applyOverrides(d, o, {"<test>", 0, 0});
      ADD_FAILURE() << "took a 0.05 s exposure at 24 Hz";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "camera.shutter");
      EXPECT_NE(e.message().find("longer than the frame period"), std::string::npos) << e.what();
    }
  }
  // Below the angle's range: 1e-9 s at 24 Hz is 8.64e-6°.
  SceneDescription d = byAngle;
  Overrides o;
  o.exposureTimeS = 1e-9;
  EXPECT_THROW(applyOverrides(d, o, {"<test>", 0, 0}), InputError);
}

// An error a later stage finds in a value an override gave names the override, not the
// scene file (found by probing: `--tiles 0/2 --target-error 0.1` named the scene file's
// render.target_error, a key the file did not have). Other errors keep their place.
TEST(OverrideRanges, LaterErrorsNameTheOverrideThatGaveTheValue) {
  Overrides o;
  EXPECT_TRUE(o.empty());
  for (const OverrideSetting& s : overrideSettings()) EXPECT_FALSE(overrideIsSet(o, s)) << s.key;
  o.targetError = 0.1;
  EXPECT_FALSE(o.empty());
  EXPECT_TRUE(overrideIsSet(o, *findOverrideSetting("target_error")));
  const SourceLocation commandLine{"<command line>", 0, 0};
  const InputError later({"scene.yaml", 0, 0}, "render.target_error", "cannot be tiled");
  const InputError named = namedByOverride(later, o, commandLine, overrideFlag);
  EXPECT_EQ(named.where().file, "<command line>");
  EXPECT_EQ(named.key(), "--target-error");
  EXPECT_EQ(named.message(), "cannot be tiled");
  // Python names the keyword: the same table, another name.
  EXPECT_EQ(namedByOverride(later, o, {"<python>", 0, 0},
                            [](const OverrideSetting& s) { return std::string(s.key); })
                .key(),
            "target_error");
  // Another key, or the key without its override set, stays where it was found.
  const InputError other({"scene.yaml", 4, 2}, "render.time_limit_s", "m");
  EXPECT_EQ(namedByOverride(other, o, commandLine, overrideFlag).where().file, "scene.yaml");
  EXPECT_EQ(namedByOverride(later, Overrides{}, commandLine, overrideFlag).key(),
            "render.target_error");
}

// Tile parts keep the overrides as data: the text form reads back to the same values.
TEST(OverrideRanges, TextFormRoundTrips) {
  Overrides o;
  o.spp = 7;
  o.seed = std::numeric_limits<std::int64_t>::max();
  o.exposureTimeS = 0.1 + 0.2;  // not a short decimal
  o.fNumber = 2.8;
  o.iso = 800;
  o.noise = NoiseMode::kPhoton;
  o.noiseSeed = 3;
  o.sensor = "a sensor file with spaces.yaml";
  o.pose = PoseOverride{std::nullopt, {1, 2, 3}, {0, 0, 0}, {0, 1, 0}};
  o.projection = ProjectionOverride{"kannala_brandt", {{"k1", 0.1 + 0.2}, {"k2", -1e-5}}};
  const std::string text = overridesText(o);
  const Overrides back = parseOverridesText(text, "part.exr");
  EXPECT_EQ(overridesText(back), text);
  EXPECT_EQ(back.exposureTimeS, o.exposureTimeS);
  EXPECT_EQ(back.sensor, o.sensor);
  ASSERT_TRUE(back.projection);
  EXPECT_EQ(back.projection->values, o.projection->values);
  EXPECT_THROW(parseOverridesText("f_number=0.3\n", "part.exr"), InputError);
  EXPECT_THROW(parseOverridesText("spp 4\n", "part.exr"), InputError);
  EXPECT_THROW(parseOverridesText("colour=red\n", "part.exr"), InputError);
}

}  // namespace
}  // namespace camsim
