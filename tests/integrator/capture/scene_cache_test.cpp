// SceneCache: a capture that reuses the Scene built by an earlier one (camera, exposure,
// f-number, ISO, sensor, seed, spp changed) gives the same bytes as a capture that builds
// its own; keyframed motion over another exposure window rebuilds only the shapes and the
// BVH of the kept Scene; what the Scene depends on otherwise (the render origin, the
// shapes, another scene) is rebuilt whole, with the same bytes.
#include "integrator/capture/scene_cache.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>

#include "integrator/capture/capture.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/luts_directory.h"

namespace camsim {
namespace {

// A lit diffuse square and a ball before a wall, with a sensor, brackets and ground truth;
// `motion` moves the ball sideways during the 1/30 s exposure, `cameraMotion` the camera.
SceneDescription box(bool motion = false, bool cameraMotion = false) {
  const std::string text =
      std::string(
          "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [24, 16], "
          "focal_length_mm: 4, f_number: 2, shutter: {open: 0, close: 0.0333}") +
      (cameraMotion ? ", motion: [{time: 0, translate: [0, 0, 0]}, {time: 0.1, translate: "
                      "[0.01, 0, 0]}]"
                    : "") +
      "}\n"
      "sensor: {model: smartphone-1.4um, iso: 100, noise: full, noise_seed: 5, "
      "bracket_ev: [-1, 0]}\n"
      "render: {spp: 2, seed: 1, max_depth: 3, aovs: [depth, normal, instance_id]}\n"
      "materials: {grey: {type: diffuse, reflectance: 0.5}, red: {type: diffuse, reflectance: "
      "{rgb: [0.6, 0.1, 0.1]}}}\n"
      "shapes:\n"
      "  - {type: rectangle, corner: [-0.01, -0.01, 2], edge_u: [0, 0.02, 0], edge_v: [0.02, 0, "
      "0], material: grey}\n"
      "  - {type: sphere, centre: [0.004, 0, 1.9], radius: 0.003, material: red" +
      std::string(motion ? ", motion: [{time: 0, translate: [-0.002, 0, 0]}, {time: 0.0333, "
                           "translate: [0.002, 0, 0]}]"
                         : "") +
      "}\n"
      "  - {type: rectangle, corner: [-0.002, 0.008, 1.95], edge_u: [0.004, 0, 0], edge_v: [0, "
      "0, 0.004], emission: {luminance: 5000}}\n"
      "lights:\n"
      "  - {type: point, position: [0, 0.5, 0], intensity: 20}\n";
  return loadSceneFromText(text, "box.yaml", ".");
}

bool sameImageBytes(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.channels == b.channels &&
         a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

// Every film, frame and picture of two captures, byte for byte.
void expectSameCapture(const CaptureResult& a, const CaptureResult& b) {
  EXPECT_TRUE(sameImageBytes(a.film, b.film));
  EXPECT_TRUE(sameImageBytes(a.sensorFilm, b.sensorFilm));
  EXPECT_TRUE(sameImageBytes(a.aovs, b.aovs));
  EXPECT_TRUE(sameImageBytes(a.picture, b.picture));
  EXPECT_EQ(a.stats.modelled.describe(), b.stats.modelled.describe());
  EXPECT_EQ(a.exposureScale, b.exposureScale);
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (std::size_t i = 0; i < a.frames.size(); ++i) {
    EXPECT_TRUE(sameImageBytes(a.frames[i].electrons, b.frames[i].electrons));
    ASSERT_EQ(a.frames[i].raws.size(), b.frames[i].raws.size());
    for (std::size_t p = 0; p < a.frames[i].raws.size(); ++p)
      EXPECT_EQ(a.frames[i].raws[p].dn, b.frames[i].raws[p].dn);
  }
}

// FNV-1a over the films and raws: whether a change changed the capture at all.
std::uint64_t digest(const CaptureResult& r) {
  std::uint64_t h = 1469598103934665603ull;
  const auto add = [&h](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  for (const Image* image : {&r.film, &r.sensorFilm, &r.aovs})
    add(image->pixels.data(), image->pixels.size() * sizeof(float));
  for (const CaptureFrame& f : r.frames)
    for (const RawImage& raw : f.raws) add(raw.dn.data(), raw.dn.size() * sizeof(std::uint16_t));
  return h;
}

// The capture of d through the cache against a capture that builds its own Scene; returns
// the digest of the fresh one.
std::uint64_t captureBoth(SceneCache& cache, const SceneDescription& d, bool expectReused,
                          const std::string& what) {
  SCOPED_TRACE(what);
  CaptureOptions options;
  options.threads = 2;
  CaptureOptions cached = options;
  cached.sceneCache = &cache;
  const CaptureResult reused = capture(d, cached);
  const CaptureResult fresh = capture(d, options);
  EXPECT_EQ(reused.sceneReused, expectReused);
  EXPECT_EQ(cache.reused(), expectReused);
  EXPECT_FALSE(fresh.sceneReused);
  const auto lit = [](const Image& film) {
    return std::any_of(film.pixels.begin(), film.pixels.end(), [](float v) { return v > 0.0f; });
  };
  EXPECT_TRUE(lit(fresh.film));  // not a trivially equal black picture
  expectSameCapture(reused, fresh);
  return digest(fresh);
}

void moveCamera(SceneDescription& d) {
  d.camera.worldFromCamera[3] += glm::dvec4(0.002, -0.001, 0.05, 0.0);
}

void useSensor(SceneDescription& d, const std::string& preset) {
  d.sensor->spec = loadSensorSpec(preset, lutsDirectory());
  d.sensor->iso = d.sensor->spec.baseIso;
  d.camera.sensorSize = glm::dvec2(d.camera.resolution) * d.sensor->spec.pixelPitchM;
  d.camera.fillFactor = d.sensor->spec.fillFactor;
}

// Each non-geometric change in turn on one cache: reused every time, same bytes.
TEST(SceneCache, NonGeometricChangesReuseTheSceneWithTheSameBytes) {
  SceneCache cache;
  SceneDescription d = box();
  std::uint64_t before = captureBoth(cache, d, false, "first capture: built");
  const std::pair<const char*, std::function<void(SceneDescription&)>> changes[] = {
      {"pose", moveCamera},
      {"exposure time",
       [](SceneDescription& s) { s.camera.shutter = s.camera.shutter.scaled(2.5); }},
      {"f-number", [](SceneDescription& s) { s.camera.fNumber = 4.0; }},
      {"iso", [](SceneDescription& s) { s.sensor->iso = 800.0; }},
      {"sensor", [](SceneDescription& s) { useSensor(s, "fullframe-d850"); }},
      {"seed", [](SceneDescription& s) { s.render.seed = 99; }},
      {"noise seed", [](SceneDescription& s) { s.sensor->noiseSeed = 12; }},
      {"spp", [](SceneDescription& s) { s.render.spp = 5; }},
      {"all at once",
       [](SceneDescription& s) {
         moveCamera(s);
         s.camera.shutter = s.camera.shutter.scaled(0.3);
         s.render.spp = 3;
         s.render.seed = 7;
         useSensor(s, "smartphone-1.4um");
       }},
  };
  for (const auto& [what, change] : changes) {
    change(d);
    const std::uint64_t after = captureBoth(cache, d, true, what);
    EXPECT_NE(after, before) << what << " changed nothing: the test would not see a stale Scene";
    before = after;
  }
}

// Something moves: a new pose keeps the exposure window, so the motion built over it is
// reused; a new exposure time is another window: the kept Scene rebuilds its shapes over
// it (Scene::setCamera) and reads no file.
TEST(SceneCache, KeyframedMotionOverAnotherExposureWindowRebuildsOnlyTheShapes) {
  SceneCache cache;
  SceneDescription d = box(true);
  captureBoth(cache, d, false, "first capture: built");
  moveCamera(d);
  captureBoth(cache, d, true, "pose");
  d.render.seed = 4;
  captureBoth(cache, d, true, "seed");
  d.camera.shutter = d.camera.shutter.scaled(2.0);
  captureBoth(cache, d, true, "exposure time: another motion span");
  d.render.spp = 3;
  captureBoth(cache, d, true, "spp, after the rebuild");
  d.camera.shutter = d.camera.shutter.scaled(0.25);
  captureBoth(cache, d, true, "a shorter exposure time");
}

// A moving camera over static shapes: the shapes do not depend on the exposure window.
TEST(SceneCache, AMovingCameraOverStaticShapesIsReusedAcrossExposureTimes) {
  SceneCache cache;
  SceneDescription d = box(false, true);
  captureBoth(cache, d, false, "first capture: built");
  d.camera.shutter = d.camera.shutter.scaled(2.0);
  captureBoth(cache, d, true, "exposure time");
  moveCamera(d);
  captureBoth(cache, d, true, "pose");
}

// What the Scene holds otherwise is not reused: the render origin, the render settings
// besides spp and seed, the shapes, another scene.
TEST(SceneCache, GeometricChangesAreRebuilt) {
  SceneCache cache;
  SceneDescription d = box();
  captureBoth(cache, d, false, "first capture: built");

  SceneDescription origin = d;
  origin.renderOrigin += glm::dvec3(0.01, 0.0, 0.0);
  captureBoth(cache, origin, false, "render origin");

  SceneDescription fewer = d;
  fewer.shapes.pop_back();
  captureBoth(cache, fewer, false, "a shape fewer");

  SceneDescription depth = d;
  depth.render.maxDepth = 1;
  captureBoth(cache, depth, false, "max depth");

  SceneDescription aovs = d;
  aovs.render.aovs.pop_back();
  captureBoth(cache, aovs, false, "another AOV list");

  SceneDescription moving = box(true);
  captureBoth(cache, moving, false, "another scene (the moving ball)");
  captureBoth(cache, moving, true, "the same again");

  cache.clear();
  EXPECT_TRUE(cache.empty());
  captureBoth(cache, moving, false, "after clear()");
}

// The cache is checked directly too: the retargeted Scene says what a fresh build says.
TEST(SceneCache, RetargetSetsWhatAFreshBuildSets) {
  SceneDescription a = box(false, true);
  SceneDescription b = a;
  b.camera.shutter = b.camera.shutter.scaled(3.0);
  b.render.spp = 9;
  b.render.seed = 11;
  Scene scene(a);
  ASSERT_TRUE(scene.canRetarget(b));
  scene.retarget(b);
  const Scene fresh(b);
  EXPECT_EQ(scene.exposureStart(), fresh.exposureStart());
  EXPECT_EQ(scene.exposureEnd(), fresh.exposureEnd());
  EXPECT_EQ(scene.settings().spp, 9);
  EXPECT_EQ(scene.settings().seed, 11u);
  EXPECT_EQ(scene.modelled().describe(), fresh.modelled().describe());
  EXPECT_TRUE(scene.modelled().cameraMoves);
  SceneDescription moving = box(true);
  Scene movingScene(moving);
  moving.camera.shutter = moving.camera.shutter.scaled(2.0);
  ASSERT_TRUE(movingScene.canRetarget(moving));
  movingScene.retarget(moving);
  const Scene movingFresh(moving);
  EXPECT_EQ(movingScene.exposureEnd(), movingFresh.exposureEnd());
  EXPECT_EQ(movingScene.modelled().describe(), movingFresh.modelled().describe());
  EXPECT_EQ(movingScene.boundsRadius(), movingFresh.boundsRadius());
}

}  // namespace
}  // namespace camsim
