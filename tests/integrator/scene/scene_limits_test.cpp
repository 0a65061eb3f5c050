// Edge-case scenes from mutated examples (issue 34, items 2 and 3): each is refused at load
// with an InputError naming the file, line and key, or renders with finite pixels. None may
// reach an Embree assertion or an internal check (both abort the process).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "integrator/capture/capture.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "tests/integrator/scene/scene_limits_support.h"
#include "tests/support/scene_text.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

using test::errorOf;
using test::kBall;
using test::kHeader;
using test::kLimitsCamera;
using test::kMaterial;
using test::kSun;

struct Case {
  const char* name;
  std::string yaml;
  const char* key;  // the key the error names; "" when the scene must render
  int line;         // the line the error names (1-based)
};

std::vector<Case> cases() {
  return {
      {"up_zero",
       kHeader +
           "camera: {position: [0, 0, 5], look_at: [0, 0, 0], up: [0, 0, 0], resolution: [16, "
           "16]}\n" +
           kSun + kMaterial + "shapes:\n" + kBall,
       "camera.up", 3},
      {"up_tiny",
       kHeader +
           "camera: {position: [0, 0, 5], look_at: [0, 0, 0], up: [0, 1e-300, 0], "
           "resolution: [16, 16]}\n" +
           kSun + kMaterial + "shapes:\n" + kBall,
       "", 0},
      {"up_parallel",
       kHeader +
           "camera: {position: [0, 0, 5], look_at: [0, 0, 0], up: [0, 0, 1e-300], "
           "resolution: [16, 16]}\n" +
           kSun + kMaterial + "shapes:\n" + kBall,
       "camera.up", 3},
      {"camera_keyframe_far",
       kHeader +
           "camera: {position: [0, 0, 5], look_at: [0, 0, 0], resolution: [16, 16],\n"
           "  motion: [{time: 0, translate: [0, 0, 0]}, {time: 0.01, translate: [1e19, 0, 0]}]}\n" +
           kSun + kMaterial + "shapes:\n" + kBall,
       "camera.motion[1].translate", 4},
      {"bulb_1e-7",
       kHeader + kLimitsCamera + kMaterial + "shapes:\n" + kBall +
           "  - {type: sphere, centre: [0, 2, 0], radius: 1e-7, material: m, "
           "emission: {luminance: 1e12}}\n",
       "", 0},
      {"bulb_1e-18",
       kHeader + kLimitsCamera + kMaterial + "shapes:\n" + kBall +
           "  - {type: sphere, centre: [0, 2, 0], radius: 1e-18, material: m, "
           "emission: {luminance: 1000}}\n",
       "shapes[1].radius", 7},
      {"rectangle_light_huge",
       kHeader + kLimitsCamera + kMaterial + "shapes:\n" + kBall +
           "  - {type: rectangle, corner: [0, 3, 0], edge_u: [9.2e18, 0, 0], edge_v: [0, 0, 1], "
           "material: m, emission: {luminance: 1000}}\n",
       "shapes[1].edge_u", 7},
      {"checks_denormal",
       kHeader + kLimitsCamera + kSun +
           "materials: {m: {type: diffuse, reflectance: {checkerboard: {a: 0.8, b: 0.1, checks: "
           "5e-324}}}}\n"
           "shapes:\n" +
           kBall,
       "materials.m.reflectance.checkerboard.checks", 5},
      {"camera_inside_tiny_emitter",
       std::string("format: camsim-scene/1\nrender: {spp: 4, aovs: [depth]}\n") +
           "camera: {position: [0, 0, 0], look_at: [0, 0, -1], resolution: [16, 16]}\n" +
           kMaterial +
           "shapes:\n  - {type: sphere, centre: [0, 0, 0], radius: 1e-30, material: m, emission: "
           "{luminance: 1000}}\n",
       "shapes[0].radius", 6},
      {"sun_disc_tiny",
       kHeader + kLimitsCamera +
           "lights: [{type: distant, direction: [0, -1, -1], illuminance: 1000, "
           "angular_diameter: 1e-30}]\n" +
           kMaterial + "shapes:\n" + kBall,
       "lights[0].angular_diameter", 4},
      {"sun_disc_small",
       kHeader + kLimitsCamera +
           "lights: [{type: distant, direction: [0, -1, -1], illuminance: "
           "1000, angular_diameter: 0.001}]\n" +
           kMaterial + "shapes:\n" + kBall,
       "", 0},
      {"rectangle_far_from_camera",
       kHeader + "camera: {position: [0, 0, 1e9], look_at: [0, 0, 0], resolution: [16, 16]}\n" +
           kSun + kMaterial + "shapes:\n" + kBall +
           "  - {type: rectangle, corner: [0, 3, 0], edge_u: [1, 0, 0], edge_v: [0, 0, 1], "
           "material: m}\n",
       "shapes[1].corner", 8},
  };
}

TEST(SceneLimits, EdgeCasesAreRefusedByKeyOrRenderFinite) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const std::string file = std::string(c.name) + ".yaml";
    if (*c.key) {
      try {
        const Scene scene(loadSceneFromText(c.yaml, file, "."));
        ADD_FAILURE() << "loaded; expected an error naming " << c.key;
      } catch (const InputError& e) {
        EXPECT_EQ(e.key(), c.key) << e.what();
        EXPECT_EQ(e.where().file, file);
        EXPECT_EQ(e.where().line, c.line) << e.what();
      }
      continue;
    }
    const Scene scene(loadSceneFromText(c.yaml, file, "."));
    RenderOptions options;
    options.spp = 4;
    const RenderResult r = render(scene, SpectralResponse::cieXyz(), options);
    EXPECT_EQ(r.stats.rejectedSamples, 0u);
    for (float v : r.image.pixels) ASSERT_TRUE(std::isfinite(v));
  }
}

// Geometry the loader cannot check point by point: a sphere whose keyframe scale takes its
// radius to 0 in float (CAMSIM_CHECK aborted), a mesh file scaled past ±1e15 m (Embree
// dropped it silently, and its light shone through everything). Both named by shape.
TEST(SceneLimits, ScaledShapesAreCheckedPerShape) {
  const test::TempDir dir;
  test::writeFile(dir.path() / "tri.obj", "v 0 0 0\nv 1e6 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::vector<std::pair<std::string, std::string>> shapes = {
      {"  - {type: sphere, centre: [0, 2, 0], radius: 1, material: m, motion: [{time: 0, scale: "
       "1e-300}, {time: 1, scale: 1}]}\n",
       "the sphere's radius times its keyframe scale is 0 m"},
      {"  - {type: mesh, file: tri.obj, scale: 1e12, material: m}\n", "the shape reaches 1e+18 m"},
  };
  for (const auto& [shape, message] : shapes) {
    try {
      const Scene scene(loadSceneFromText(
          kHeader + kLimitsCamera + kSun + kMaterial + "shapes:\n" + kBall + shape, "scaled.yaml",
          dir.path()));
      ADD_FAILURE() << "built: " << shape;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "shapes[1]") << e.what();
      EXPECT_EQ(e.where().file, "scaled.yaml");
      EXPECT_NE(e.message().find(message), std::string::npos) << e.what();
    }
  }
}

// The loader's smallest sphere radius, 1e-9 m (SceneLimits::kMinSphereRadius), builds and
// renders: it is stored as the float 9.99999972e-10, which the build's reach check once
// compared in double against 1e-9 and refused (found by fuzz_scene_render,
// fuzz/regressions/scene_render/sphere_min_radius.yaml). A keyframe scale of 0.5 takes it
// below the limit and is still refused by shape.
TEST(SceneLimits, SmallestSphereRadiusBuilds) {
  const std::string tiny =
      "  - {type: sphere, centre: [0, 2, 2], radius: 1e-9, material: m, emission: {luminance: "
      "1e6}}\n";
  const Scene scene(loadSceneFromText(
      kHeader + kLimitsCamera + kSun + kMaterial + "shapes:\n" + kBall + tiny, "tiny.yaml", "."));
  RenderOptions options;
  options.spp = 1;
  const RenderResult r = render(scene, SpectralResponse::cieXyz(), options);
  for (float v : r.image.pixels) ASSERT_TRUE(std::isfinite(v));
  try {
    const Scene halved(loadSceneFromText(
        kHeader + kLimitsCamera + kSun + kMaterial + "shapes:\n" + kBall +
            "  - {type: sphere, centre: [0, 2, 2], radius: 1e-9, material: m, motion: [{time: 0, "
            "scale: 0.5}]}\n",
        "tiny.yaml", "."));
    ADD_FAILURE() << "built a sphere of radius 5e-10 m";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "shapes[1]") << e.what();
    // The entry's line (found by probing: errors found after loading named no line).
    EXPECT_EQ(e.where().file, "tiny.yaml");
    EXPECT_GT(e.where().line, 0) << e.what();
    EXPECT_NE(e.message().find("the sphere's radius times its keyframe scale is "),
              std::string::npos)
        << e.what();
  }
}

// A keyframe or placement scale so small that Embree, moving a ray into the shape's space
// with the inverse transform, meets coordinates past its ±1.8e18 m: it aborted on its own
// assertion (ray.valid()) during the render; a shadow ray towards a far point light did the
// same through its long direction. Below a determinant of FLT_MIN Embree's float inverse
// fails and the instance vanished silently (a uniform 1e-13). And a tiny keyframe outside
// this exposure's window (a sequence's later frame) must be refused before anything is
// written. All refused when the scene is built, naming the shape; a millimetre-to-metre
// scale (1e-3) and a small but traceable one (1e-9) still build and render finite.
TEST(SceneLimits, ScalesTooSmallForEmbreeAreRefusedByShape) {
  const std::string triangle = "vertices: [[-1, -1, 2], [1, -1, 2], [0, 1, 2]], faces: [[0, 1, 2]]";
  const auto moving = [&](const std::string& scale, const std::string& time = "0.01") {
    return "  - {type: mesh, " + triangle +
           ", material: m, motion: [{time: 0, scale: 1}, {time: " + time + ", scale: " + scale +
           "}]}\n";
  };
  const auto instanced = [&](const std::string& scale) {
    return "  - {type: mesh, " + triangle + ", material: m, instances: [{scale: " + scale +
           "}, {translate: [1, 0, 0]}]}\n";
  };
  const std::string farLamp =
      "lights: [{type: point, position: [1e12, 0, 3e11], intensity: 1e20}]\n";
  const struct {
    std::string lights, shape;
  } refused[] = {
      {kSun, moving("1e-30")},
      {kSun, moving("1e-20")},
      {kSun, instanced("[1, 1, 1e-20]")},
      {kSun, instanced("1e-13")},             // |det| 1e-39: vanished
      {farLamp, instanced("[3, 3, 1e-13]")},  // the shadow ray's direction
      {kSun, moving("1e-20", "1000")},        // outside the exposure window
  };
  for (const auto& c : refused) {
    SCOPED_TRACE(c.lights + c.shape);
    try {
      const Scene scene(loadSceneFromText(
          kHeader + kLimitsCamera + c.lights + kMaterial + "shapes:\n" + kBall + c.shape,
          "tiny.yaml", "."));
      ADD_FAILURE() << "built";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key().rfind("shapes[1]", 0), 0u) << e.what();
      EXPECT_EQ(e.where().file, "tiny.yaml");
      EXPECT_NE(e.message().find("too small for the tracer"), std::string::npos) << e.what();
    }
  }
  for (const std::string& shape : {moving("1e-3"), moving("1e-9"), instanced("1e-3")}) {
    SCOPED_TRACE(shape);
    const Scene scene(
        loadSceneFromText(kHeader + kLimitsCamera + kSun + kMaterial + "shapes:\n" + kBall + shape,
                          "small.yaml", "."));
    RenderOptions options;
    options.spp = 2;
    const RenderResult r = render(scene, SpectralResponse::cieXyz(), options);
    for (float v : r.image.pixels) ASSERT_TRUE(std::isfinite(v));
  }
}

// A bulb of radius 1e-7 m lights the ball as a point light of the same intensity
// I = L π r² does (0.0314 cd for 1e12 cd/m²), within 2 % of the image sum at 64 spp: the
// sample on a tiny sphere is placed from its centre, not from the shading point, whose
// coordinates round by more than the radius (before, the sample's normal was NaN).
TEST(SceneLimits, TinyBulbLightsLikeItsPointLight) {
  const auto imageSum = [](const std::string& lights, const std::string& shapes) {
    const Scene scene(loadSceneFromText(
        kHeader + kLimitsCamera + kMaterial + lights + "shapes:\n" + kBall + shapes, "bulb.yaml",
        "."));
    RenderOptions options;
    options.spp = 64;
    const RenderResult r = render(scene, SpectralResponse::cieXyz(), options);
    double sum = 0.0;
    const int y = r.image.channelIndex("Y");
    for (int j = 0; j < r.image.height; ++j)
      for (int i = 0; i < r.image.width; ++i) sum += static_cast<double>(r.image.at(i, j, y));
    return sum;
  };
  const double intensity = 1e12 * M_PI * 1e-7 * 1e-7;  // cd
  const double bulb = imageSum("",
                               "  - {type: sphere, centre: [0, 2, 2], radius: 1e-7, "
                               "material: m, emission: {luminance: 1e12}}\n");
  const double point = imageSum(
      "lights: [{type: point, position: [0, 2, 2], intensity: " + test::num(intensity) + "}]\n",
      "");
  ASSERT_GT(point, 0.0);
  EXPECT_NEAR(bulb / point, 1.0, 0.02);
}

// A phone sensor over a grey card lit by the sun; `light` its illuminance (lx).
std::string sensorScene(const std::string& resolution, double light, const std::string& isp) {
  return "format: camsim-scene/1\nrender: {spp: 2}\n"
         "camera: {position: [0, 0, 5], look_at: [0, 0, 0], resolution: " +
         resolution +
         ", focal_length_mm: 4}\n"
         "sensor: {model: smartphone-1.4um, iso: 100, noise: none}\n" +
         isp + "lights: [{type: distant, direction: [0, 0, -1], illuminance: " + test::num(light) +
         "}]\n" + kMaterial + "shapes:\n" + kBall;
}

// The white balance's refusals name the scene's isp keys and their lines: at load when the
// settings cannot suit the image (a region outside it; grey world on an image smaller than
// one CFA tile), after rendering when the raw has no usable white (a black image). They
// named "<input>" and 'region' / 'white_balance' before.
TEST(SceneLimits, WhiteBalanceRefusalsNameTheSceneKey) {
  const InputError outside = errorOf([] {
    loadSceneFromText(
        sensorScene("[32, 32]", 1000, "isp: {white_balance: region, region: [30, 30, 10, 10]}\n"),
        "wb.yaml", ".");
  });
  EXPECT_EQ(outside.key(), "isp.region");
  EXPECT_EQ(outside.where().file, "wb.yaml");
  EXPECT_EQ(outside.where().line, 5) << outside.what();

  const InputError tiny = errorOf([] {
    loadSceneFromText(sensorScene("[3, 1]", 1000, "isp: {white_balance: grey_world}\n"), "wb.yaml",
                      ".");
  });
  EXPECT_EQ(tiny.key(), "isp.white_balance");
  EXPECT_EQ(tiny.where().line, 5) << tiny.what();

  const InputError dark = errorOf([] {
    capture(loadSceneFromText(sensorScene("[16, 16]", 1e-30, "isp:\n  white_balance: grey_world\n"),
                              "wb.yaml", "."));
  });
  EXPECT_EQ(dark.key(), "isp.white_balance");
  EXPECT_EQ(dark.where().file, "wb.yaml");
  EXPECT_EQ(dark.where().line, 6) << dark.what();

  // Grey world on a fully clipped raw: the region code's refusal names the white balance.
  const InputError clipped = errorOf([] {
    capture(loadSceneFromText(sensorScene("[16, 16]", 1e9, "isp:\n  white_balance: grey_world\n"),
                              "wb.yaml", "."));
  });
  EXPECT_EQ(clipped.key(), "isp.white_balance") << clipped.what();
  EXPECT_EQ(clipped.where().line, 6) << clipped.what();
}

// A spectral table that is not a table, or a sensor file that is not a sensor, names its
// own place and the scene key that named it (before: only its own place).
TEST(SceneLimits, TableErrorsNameTheSceneKeyThatNamedTheFile) {
  const test::TempDir dir;
  test::writeFile(dir.path() / "notes.csv", "hello world\nthis is not, a table\n");
  const InputError e = errorOf([&] {
    loadSceneFromText(kHeader + kLimitsCamera + kSun +
                          "materials: {m: {type: diffuse, reflectance: {csv: notes.csv}}}\n"
                          "shapes:\n" +
                          kBall,
                      "table.yaml", dir.path());
  });
  EXPECT_EQ(e.where().file, (dir.path() / "notes.csv").string());
  EXPECT_EQ(e.where().line, 1);
  EXPECT_NE(std::string(e.what()).find(
                "in the file named by table.yaml:5:51, key 'materials.m.reflectance.csv'"),
            std::string::npos)
      << e.what();

  // Likewise a sensor file that is not a sensor description.
  test::writeFile(dir.path() / "notes.yaml", "format: camsim-sensor/1\nhello: 1\n");
  const InputError s = errorOf([&] {
    loadSceneFromText(kHeader + kLimitsCamera + "sensor: {model: notes.yaml}\n" + kSun + kMaterial +
                          "shapes:\n" + kBall,
                      "sensor.yaml", dir.path());
  });
  EXPECT_EQ(s.where().file, (dir.path() / "notes.yaml").string());
  EXPECT_NE(std::string(s.what()).find("in the file named by sensor.yaml:4:17, key 'sensor.model'"),
            std::string::npos)
      << s.what();
}

}  // namespace
}  // namespace camsim
