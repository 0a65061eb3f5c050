// The projection override (integrator/scene/overrides.h, key projection, scene key
// camera.projection): read and checked by the scene loader, applied as the loader applies
// the same block in a scene file, written to the tile-part text and read back, and through
// `camsim render --projection`, whose image must be black outside the fisheye's image
// circle where the scene's own pinhole sees the lamp everywhere.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "integrator/scene/overrides.h"
#include "integrator/scene/overrides_projection.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/io/exr_io.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

// 32×32 px, fx = 33.6/24 · 32 = 44.8 px: the pinhole sees ±19.6° off axis, all of it on
// the lamp (a sphere of radius 2 at 3 m subtends ±41.8°).
std::string sceneText(const std::string& cameraExtra = "") {
  return "name: lamp\nrender: {spp: 2}\n"
         "camera: {position: [0, 0, -3], look_at: [0, 0, 0], resolution: [32, 32], "
         "sensor_width_mm: 24, sensor_height_mm: 24, focal_length_mm: 33.6" +
         cameraExtra +
         "}\n"
         "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
         "shapes:\n"
         "  - {type: sphere, centre: [0, 0, 0], radius: 2, material: grey, "
         "emission: {luminance: 100}}\n";
}

Overrides projectionOverride(const std::string& text) {
  Overrides o;
  const OverrideSource source{SourceLocation{"", 0, 0}, "--projection"};
  setOverrideText(o, *findOverrideSetting("projection"), text, source);
  return o;
}

// The InputError's key when `f` throws one; "" when it does not throw.
template <typename F>
std::string errorKey(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.key();
  }
  return "";
}

TEST(ProjectionOverride, AppliesAsTheLoaderReadsTheSameBlock) {
  const char* block =
      "{model: kannala_brandt, k1: 0.02, k2: -0.003, k3: 0.0004, k4: -0.00005, "
      "max_field_angle_deg: 95, fx: 300.5, fy: 301, cx: 15.25, cy: 16}";
  SceneDescription d = loadSceneFromText(sceneText(), "lamp.yaml", ".");
  applyOverrides(d, projectionOverride(block), {"<command line>", 0, 0});
  const SceneDescription reference =
      loadSceneFromText(sceneText(std::string(", projection: ") + block), "lamp.yaml", ".");
  const Projection& p = d.camera.projection;
  const Projection& q = reference.camera.projection;
  EXPECT_EQ(p.model, ProjectionModel::kKannalaBrandt);
  EXPECT_FALSE(d.camera.intrinsicsFromLens);
  for (const auto& [got, want] : {std::pair{p.k1, q.k1},
                                  {p.k2, q.k2},
                                  {p.k3, q.k3},
                                  {p.k4, q.k4},
                                  {p.fx, q.fx},
                                  {p.fy, q.fy},
                                  {p.cx, q.cx},
                                  {p.cy, q.cy},
                                  {p.maxFieldAngle, q.maxFieldAngle}})
    EXPECT_EQ(got, want);
  EXPECT_EQ(p.k1, 0.02);
  EXPECT_EQ(p.fx, 300.5);
  // Without intrinsics they follow the lens again, and the whole block is replaced.
  applyOverrides(d, projectionOverride("{model: equidistant}"), {"<command line>", 0, 0});
  EXPECT_EQ(d.camera.projection.model, ProjectionModel::kEquidistant);
  EXPECT_TRUE(d.camera.intrinsicsFromLens);
  EXPECT_EQ(d.camera.projection.k1, 0.0);
}

TEST(ProjectionOverride, ErrorsAreTheLoadersNamingTheKey) {
  EXPECT_EQ(errorKey([] { projectionOverride("{model: fisheye9}"); }), "camera.projection.model");
  EXPECT_EQ(errorKey([] { projectionOverride("{model: opencv, k1: 2000}"); }),
            "camera.projection.k1");
  EXPECT_EQ(errorKey([] { projectionOverride("{model: opencv, kk: 1}"); }), "camera.projection.kk");
  EXPECT_EQ(errorKey([] { projectionOverride("{k1: 0.1}"); }), "camera.projection.model");
  EXPECT_EQ(errorKey([] { projectionOverride("{model: opencv, fx: 1, fy: 1, cx: 1}"); }),
            "camera.projection");
  EXPECT_EQ(errorKey([] { projectionOverride("{model: opencv"); }), "camera.projection");
  EXPECT_EQ(errorKey([] { projectionOverride("equidistant"); }), "camera.projection");
  // Filled by hand, checked again when applied.
  SceneDescription d = loadSceneFromText(sceneText(), "lamp.yaml", ".");
  Overrides o;
  o.projection = ProjectionOverride{"equidistant", {{"max_field_angle_deg", 181.0}}};
  EXPECT_EQ(errorKey([&] {
              applyOverrides(d, o, {"<override>", 0, 0});
            }),
            "camera.projection.max_field_angle_deg");
  // The loader's pupil rule, which the probe cannot see: a flat pupil is opencv's only.
  SceneDescription flat =
      loadSceneFromText(sceneText(", aperture: {pupil: flat}"), "lamp.yaml", ".");
  EXPECT_EQ(errorKey([&] {
              applyOverrides(flat, projectionOverride("{model: equidistant}"), {"<o>", 0, 0});
            }),
            "camera.projection.model");
  EXPECT_EQ(flat.camera.projection.model, ProjectionModel::kOpenCv);  // unchanged
  EXPECT_EQ(errorKey([&] {
              applyOverrides(flat, projectionOverride("{model: opencv, k1: 0.1}"), {"<o>", 0, 0});
            }),
            "");
  EXPECT_EQ(flat.camera.projection.k1, 0.1);
  // The exports' rule (found by probing: BOP's cam_K was written as a pinhole for a fisheye).
  std::string text = sceneText();
  text.replace(text.find("render:"), 0, "exports: [bop, kitti]\n");
  SceneDescription bop = loadSceneFromText(text, "lamp.yaml", ".");
  for (const char* refused : {"{model: equidistant}", "{model: opencv, k1: 0.1}"}) {
    try {
      applyOverrides(bop, projectionOverride(refused), {"<command line>", 0, 0});
      ADD_FAILURE() << refused;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "camera.projection") << e.what();
      EXPECT_NE(e.message().find("export 'bop'"), std::string::npos) << e.what();
    }
    EXPECT_EQ(bop.camera.projection.model, ProjectionModel::kOpenCv);
  }
  applyOverrides(bop, projectionOverride("{model: opencv, fx: 40, fy: 40, cx: 15.5, cy: 15.5}"),
                 {"<command line>", 0, 0});
  EXPECT_EQ(bop.camera.projection.fx, 40.0);
  // Intrinsics that image none of the scene's 32 × 32 pixels (cx 300 px: θ ≥ 26 rad there).
  SceneDescription far = loadSceneFromText(sceneText(), "lamp.yaml", ".");
  EXPECT_EQ(errorKey([&] {
              applyOverrides(far,
                             projectionOverride("{model: equidistant, fx: 10, fy: 10, cx: 300, "
                                                "cy: 16}"),
                             {"<o>", 0, 0});
            }),
            "camera.projection");
}

// A block in any YAML form becomes one line of JSON that reads back to the same doubles.
TEST(ProjectionOverride, TextFormIsOneLineAndRoundTrips) {
  const Overrides o = projectionOverride(
      "model: double_sphere\nxi: -0.2\nalpha: 0.6\n"
      "max_field_angle_deg: 99.123456789012345\n");
  ASSERT_TRUE(o.projection);
  const Overrides third = projectionOverride("{model: ftheta, k1: 0.30000000000000004}");
  EXPECT_EQ(overridesText(third),
            "projection={\"model\": \"ftheta\", \"k1\": 0.30000000000000004}\n");
  const std::string text = overridesText(o);
  EXPECT_EQ(text.find('\n'), text.size() - 1) << text;
  const Overrides back = parseOverridesText(text, "part.exr");
  ASSERT_TRUE(back.projection);
  EXPECT_EQ(back.projection->model, "double_sphere");
  EXPECT_EQ(back.projection->values, o.projection->values);
  EXPECT_EQ(overridesText(back), text);
  EXPECT_THROW(parseOverridesText("projection={\"model\": \"none\"}\n", "part.exr"), InputError);
}

// The lamp fills the pinhole's view; an equidistant fisheye imaging up to 15° (an image
// circle of radius 44.8 · 0.262 = 11.7 px about the centre) leaves the corners and the
// middles of the edges black.
TEST(ProjectionOverride, CommandLineRendersThroughTheModel) {
  const test::TempDir dir;
  test::writeFile(dir.path() / "lamp.yaml", sceneText());
  const std::string base = "render " + test::quote((dir.path() / "lamp.yaml").string()) + " -o ";
  const auto red = [](const Image& im, int x, int y) {
    for (std::size_t c = 0; c < im.channels.size(); ++c)
      if (im.channels[c] == "R") return im.at(x, y, static_cast<int>(c));
    return -1.0f;
  };
  test::RunResult r =
      test::runCamsim(base + test::quote((dir.path() / "own").string()), dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = test::runCamsim(base + test::quote((dir.path() / "fisheye").string()) +
                          " --projection '{model: equidistant, max_field_angle_deg: 15}'",
                      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Image own = readExr(dir.path() / "own" / "lamp.exr").image;
  const Image fisheye = readExr(dir.path() / "fisheye" / "lamp.exr").image;
  for (const auto& [x, y] : {std::pair{0, 0}, {31, 0}, {0, 31}, {31, 31}, {0, 16}, {16, 0}}) {
    EXPECT_GT(red(own, x, y), 0.0f) << x << "," << y;
    EXPECT_EQ(red(fisheye, x, y), 0.0f) << x << "," << y;
  }
  EXPECT_GT(red(fisheye, 16, 16), 0.0f);
  EXPECT_GT(red(fisheye, 16, 22), 0.0f);  // 6.5 px off centre: inside the circle
  // A bad model: exit 2 naming the flag and the key, nothing written.
  r = test::runCamsim(
      base + test::quote((dir.path() / "bad").string()) + " --projection '{model: fisheye9}'",
      dir.path());
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("--projection: key 'camera.projection.model': unknown projection model "
                       "'fisheye9'"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "bad" / "lamp.exr"));
  r = test::runCamsim("render --help", dir.path());
  EXPECT_NE(r.out.find("--projection MAP"), std::string::npos) << r.out;
}

// Tile parts record the projection (one JSON line of camsim:overrides) and merge applies it
// again: the merged frame is the whole render's, byte for byte.
TEST(ProjectionOverride, TilePartsMergeToTheWholeRender) {
  const test::TempDir dir;
  test::writeFile(dir.path() / "lamp.yaml", sceneText());
  const std::string render = "render " + test::quote((dir.path() / "lamp.yaml").string()) +
                             " --reproducible --projection " +
                             test::quote(
                                 "{model: kannala_brandt, k1: 0.1, max_field_angle_deg: "
                                 "15.000000000000002}") +
                             " -o ";
  for (const char* tile : {"0/2", "1/2"}) {
    const test::RunResult r = test::runCamsim(
        render + test::quote((dir.path() / "parts").string()) + " --tiles " + tile, dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
  }
  test::RunResult r = test::runCamsim(
      "merge " + test::quote((dir.path() / "parts" / "lamp.part-0-of-2.exr").string()) + " " +
          test::quote((dir.path() / "parts" / "lamp.part-1-of-2.exr").string()) + " -o " +
          test::quote((dir.path() / "merged").string()),
      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = test::runCamsim(render + test::quote((dir.path() / "whole").string()), dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string whole = test::readFile(dir.path() / "whole" / "lamp.exr");
  EXPECT_FALSE(whole.empty());
  EXPECT_EQ(test::readFile(dir.path() / "merged" / "lamp.exr"), whole);
  const Metadata meta = readExr(dir.path() / "parts" / "lamp.part-0-of-2.exr").metadata;
  bool recorded = false;
  for (const auto& [key, value] : meta)
    if (key == "camsim:overrides")
      recorded = value ==
                 "projection={\"model\": \"kannala_brandt\", \"k1\": 0.1, "
                 "\"max_field_angle_deg\": 15.000000000000002}\n";
  EXPECT_TRUE(recorded);
}

}  // namespace
}  // namespace camsim
