// One Scene per capture: auto-exposure and brackets on a moving scene render step 4 again
// on step 1's Scene (its shapes rebuilt over each stretched shutter, Scene::setCamera)
// instead of building a Scene per bracket, so no file is read twice; the frames are the
// same bytes as a Scene built for each bracket's shutter (what captures did before).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "integrator/capture/capture.h"
#include "integrator/scene/factory.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "integrator/textures/image_texture.h"

namespace camsim {
namespace {

// A ball rolling and an alpha-cut card turning before a textured wall and floor, lit by
// an environment map, seen by a rising camera; auto-exposed with three brackets. Files:
// scenes/textures/speckle.png (wall, floor, the card's alpha) and scenes/env/studio.exr.
SceneDescription movingTexturedScene(const std::string& brackets = "[-1, 0, 1.5]",
                                     bool motion = true) {
  const std::string turn =
      motion ? ", motion: [{time: 0, rotate: {axis: [0, 0, 1], angle_deg: 0}}, {time: 0.1, "
               "rotate: {axis: [0, 0, 1], angle_deg: 10}}, {time: 0.2, rotate: {axis: [0, 0, "
               "1], angle_deg: 20}}]"
             : "";
  const std::string roll =
      motion ? ", motion: [{time: 0, translate: [1, 0, 0]}, {time: 0.2, translate: [-0.6, 0, 0]}]"
             : "";
  const std::string text =
      "camera: {position: [0, 0.9, -1.5], look_at: [0, 0.6, 2.5], focal_length_mm: 4, "
      "f_number: 2.8, resolution: [32, 24], shutter: {open: 0, close: 0.02}, motion: [{time: "
      "0, translate: [0, 0, 0]}, {time: 0.2, translate: [0, 0.3, 0]}]}\n"
      "sensor: {model: smartphone-1.4um, iso: 200, noise: full, noise_seed: 7, auto_exposure: "
      "{metering: mean, target: 0.18}, bracket_ev: " +
      brackets +
      "}\n"
      "render: {spp: 4, seed: 3, max_depth: 3}\n"
      "materials:\n"
      "  wall: {type: diffuse, reflectance: {texture: textures/speckle.png, scale: 3}}\n"
      "  floor: {type: diffuse, reflectance: {texture: textures/speckle.png, scale: 4}}\n"
      "  red: {type: diffuse, reflectance: {rgb: [0.7, 0.06, 0.04]}}\n"
      "  leaf: {type: diffuse, reflectance: 0.4, alpha_cutout: {alpha: {texture: "
      "textures/speckle.png}, cutoff: 0.5}}\n"
      "shapes:\n"
      "  - {type: rectangle, corner: [-1.5, 2.6, 0.5], edge_u: [3, 0, 0], edge_v: [0, 0, 2], "
      "emission: {luminance: 3000}}\n"
      "  - {type: rectangle, material: floor, corner: [-3, 0, -1], edge_u: [0, 0, 5], edge_v: "
      "[6, 0, 0]}\n"
      "  - {type: rectangle, material: wall, corner: [3, 0, 4], edge_u: [-6, 0, 0], edge_v: [0, "
      "3, 0]}\n"
      "  - {type: sphere, centre: [0, 0.15, 2.3], radius: 0.15, material: red" +
      roll +
      "}\n"
      "  - {type: rectangle, material: leaf, corner: [-0.3, 0.4, 2], edge_u: [0.6, 0, 0], "
      "edge_v: [0, 0.6, 0]" +
      turn +
      "}\n"
      "lights:\n"
      "  - {type: environment, file: env/studio.exr, illuminance: 500}\n";
  return loadSceneFromText(text, "moving.yaml", std::string(CAMSIM_SOURCE_DIR) + "/scenes");
}

bool sameBytes(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.channels == b.channels &&
         a.pixels.size() == b.pixels.size() && !a.pixels.empty() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

// What a capture rendered for a bracket before one Scene per capture: a Scene of its own,
// built from the description at the stretched shutter T·k (k = auto-exposure · 2^EV).
Image freshBracketFilm(const SceneDescription& d, double k) {
  SceneDescription longer = d;
  longer.camera.shutter = d.camera.shutter.scaled(k);
  const Scene scene(longer);
  RenderOptions o;
  o.spp = d.render.spp;
  o.seed = d.render.seed;
  o.threads = 2;
  return render(scene, sensorResponse(d.sensor->spec), o).image;
}

// N brackets (and auto-exposure) of a moving scene: four renders on one Scene — the
// metering film, the metered 0 EV film and two brackets — and each file read only by the
// loader. The counters do count: a Scene built again from the captured description
// (decoded images released) reads speckle.png twice (wall and floor share one uplift, the
// card's alpha reads it raw) and the environment map once.
TEST(CaptureScene, BracketsOfAMovingSceneReadEachFileOnce) {
  const std::uint64_t texturesBefore = textureFilesRead();
  const SceneDescription d = movingTexturedScene();
  const std::uint64_t loaderReads = textureFilesRead() - texturesBefore;
  EXPECT_GE(loaderReads, 1u);
  const std::uint64_t sceneReadsBefore = sceneFilesRead();
  CaptureOptions options;
  options.threads = 2;
  const CaptureResult r = capture(d, options);
  ASSERT_FALSE(r.cancelled);
  ASSERT_TRUE(r.stats.modelled.time);
  ASSERT_NE(r.exposureScale, 1.0);
  ASSERT_EQ(r.frames.size(), 3u);
  EXPECT_EQ(textureFilesRead() - texturesBefore, loaderReads) << "a texture was read again";
  EXPECT_EQ(sceneFilesRead(), sceneReadsBefore) << "a Scene build read a file";

  const Scene again(r.description);  // the control: released images are read again
  EXPECT_EQ(sceneFilesRead() - sceneReadsBefore, 3u);
  EXPECT_EQ(textureFilesRead() - texturesBefore, loaderReads + 2);
}

// Every bracket's electrons are the bytes a Scene built for its own shutter renders: the
// rebuild over each stretched exposure window is what a fresh build makes.
TEST(CaptureScene, EachBracketIsTheFilmOfASceneBuiltForItsShutter) {
  const SceneDescription d = movingTexturedScene();
  CaptureOptions options;
  options.threads = 2;
  const CaptureResult r = capture(d, options);
  ASSERT_EQ(r.frames.size(), 3u);
  for (const CaptureFrame& f : r.frames) {
    SCOPED_TRACE("EV " + std::to_string(f.ev));
    const double k = r.exposureScale * std::exp2(f.ev);
    EXPECT_TRUE(sameBytes(f.electrons, freshBracketFilm(d, k)));
  }
  // Step 1's film is untouched by the re-renders that followed it on the same Scene.
  CaptureResult unbracketed = capture(movingTexturedScene("[0]"), options);
  EXPECT_TRUE(sameBytes(r.film, unbracketed.film));
  EXPECT_TRUE(sameBytes(r.sensorFilm, unbracketed.sensorFilm));
}

// A moving camera over static shapes: only Embree's time map follows the shutter.
TEST(CaptureScene, AMovingCameraOverStaticShapesRendersEachBracketAsAFreshScene) {
  const SceneDescription d = movingTexturedScene("[-1, 0, 1]", false);
  CaptureOptions options;
  options.threads = 2;
  const std::uint64_t sceneReadsBefore = sceneFilesRead();
  const CaptureResult r = capture(d, options);
  EXPECT_EQ(sceneFilesRead(), sceneReadsBefore);
  ASSERT_TRUE(r.stats.modelled.cameraMoves);
  ASSERT_EQ(r.frames.size(), 3u);
  for (const CaptureFrame& f : r.frames)
    EXPECT_TRUE(sameBytes(f.electrons, freshBracketFilm(d, r.exposureScale * std::exp2(f.ev))))
        << "EV " << f.ev;
}

// A Scene moved to another span says what a fresh build over it says, and back again.
TEST(CaptureScene, SetCameraOverAnotherSpanMatchesAFreshBuild) {
  const SceneDescription d = movingTexturedScene();
  Scene scene(d);
  const Scene original(d);
  SceneDescription longer = d;
  longer.camera.shutter = d.camera.shutter.scaled(6.0);
  const Scene fresh(longer);
  const auto expectSame = [](const Scene& a, const Scene& b) {
    EXPECT_EQ(a.exposureStart(), b.exposureStart());
    EXPECT_EQ(a.exposureEnd(), b.exposureEnd());
    EXPECT_EQ(a.modelled().describe(), b.modelled().describe());
    EXPECT_EQ(a.boundsCentre(), b.boundsCentre());
    EXPECT_EQ(a.boundsRadius(), b.boundsRadius());
    ASSERT_EQ(a.lightCount(), b.lightCount());
    for (std::size_t i = 0; i < a.lightCount(); ++i)
      EXPECT_EQ(a.lightDistribution().pmf(i), b.lightDistribution().pmf(i));
    EXPECT_EQ(a.infiniteLights(), b.infiniteLights());
    ASSERT_EQ(a.shapeCount(), b.shapeCount());
    for (int s = 0; s < static_cast<int>(a.shapeCount()); ++s)
      EXPECT_EQ(a.shape(s).timeSteps().count, b.shape(s).timeSteps().count);
  };
  scene.setCamera(longer.camera, d, exposureWindow(PhysicalCamera(longer.camera)));
  expectSame(scene, fresh);
  EXPECT_GT(scene.modelled().timeSteps, original.modelled().timeSteps);
  scene.setCamera(d.camera, d, exposureWindow(PhysicalCamera(d.camera)));
  expectSame(scene, original);
}

// A moving sequence with brackets: each frame's brackets re-render on the sequence's one
// Scene (over the bracket's window, then the sequence's again), read no file, and give
// the bytes of a Scene built for the frame's bracket; the frames' films are those of the
// same sequence without brackets.
TEST(CaptureScene, ASequenceRendersItsBracketsOnItsOneScene) {
  const auto sequence = [](const std::string& brackets) {
    SceneDescription d = movingTexturedScene(brackets);
    d.frames = FrameSequence{3, 20.0, 0, std::nullopt};
    return d;
  };
  const SceneDescription d = sequence("[-1, 0, 1]");
  CaptureOptions options;
  options.threads = 2;
  const auto run = [&](const SceneDescription& s) {
    std::vector<CaptureResult> frames;
    captureSequence(s, options, [&](CaptureResult&& r, int) { frames.push_back(std::move(r)); });
    return frames;
  };
  const std::uint64_t sceneReadsBefore = sceneFilesRead();
  const std::vector<CaptureResult> frames = run(d);
  EXPECT_EQ(sceneFilesRead(), sceneReadsBefore);
  const std::vector<CaptureResult> plain = run(sequence("[0]"));
  ASSERT_EQ(frames.size(), 3u);
  ASSERT_EQ(plain.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    const CaptureResult& r = frames[static_cast<size_t>(k)];
    ASSERT_TRUE(r.stats.modelled.time);
    EXPECT_TRUE(sameBytes(r.film, plain[static_cast<size_t>(k)].film));
    SceneDescription atFrame = d;
    atFrame.camera = d.frameCamera(k);
    ASSERT_EQ(r.frames.size(), 3u);
    for (const CaptureFrame& f : r.frames)
      EXPECT_TRUE(
          sameBytes(f.electrons, freshBracketFilm(atFrame, r.exposureScale * std::exp2(f.ev))))
          << "EV " << f.ev;
  }
}

}  // namespace
}  // namespace camsim
