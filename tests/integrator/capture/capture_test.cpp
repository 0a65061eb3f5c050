// capture(): the sequence auto-exposure → brackets → (re-render if moving) → expose →
// develop, as one call that writes nothing; and writeCapture() writing what it produced.
#include "integrator/capture/capture.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <string>

#include "integrator/capture/capture_writer.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/io/exr_io.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

// A lit diffuse 1 cm square 2 m before the camera, in a view 2.2 cm wide; `extra` adds keys
// to the sensor block, `motion` moves the square 8 mm sideways during the 1/30 s exposure
// (then it stays: a longer exposure sees it longer where it stopped).
SceneDescription plane(const std::string& extra, bool motion = false) {
  const std::string text =
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [32, 24], "
      "focal_length_mm: 4, f_number: 2, shutter: {open: 0, close: 0.0333}}\n"
      "sensor: {model: smartphone-1.4um, iso: 100, noise: full, noise_seed: 5" +
      extra +
      "}\n"
      "render: {spp: 4, max_depth: 1}\n"
      "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
      "shapes:\n"
      "  - {type: rectangle, corner: [-0.005, -0.005, 2], edge_u: [0, 0.01, 0], edge_v: [0.01, 0, "
      "0], "
      "material: grey" +
      std::string(motion ? ", motion: [{time: 0, translate: [-0.004, 0, 0]}, {time: 0.0333, "
                           "translate: [0.004, 0, 0]}]"
                         : "") +
      "}\n"
      "lights:\n"
      "  - {type: point, position: [0, 0.5, 0], intensity: 20}\n";
  return loadSceneFromText(text, "plane.yaml", ".");
}

double mean(const Image& image) {
  double s = 0.0;
  for (float v : image.pixels) s += static_cast<double>(v);
  return s / static_cast<double>(image.pixels.size());
}

// Brackets of a static scene scale the metered film: frame k has exactly 2^EV times the
// reference electrons, at T·k_ae·2^EV; the 0 EV frame is the one developed.
TEST(Capture, BracketsOfAStaticSceneScaleTheMeteredFilm) {
  const CaptureResult r =
      capture(plane(", auto_exposure: {metering: mean, target: 0.18}, bracket_ev: [-1, 0, 2]"));
  ASSERT_FALSE(r.cancelled);
  ASSERT_EQ(r.frames.size(), 3u);
  EXPECT_EQ(r.referenceFrame, 1u);
  EXPECT_FALSE(r.stats.modelled.time);
  const double t = r.description.camera.shutter.effectiveTime();
  const SensorSpec& spec = r.description.sensor->spec;
  EXPECT_NEAR(mean(r.frames[1].electrons), 0.18 * spec.saturationElectrons(100.0),
              1e-4 * spec.saturationElectrons(100.0));
  const double evs[] = {-1.0, 0.0, 2.0};
  for (std::size_t i = 0; i < 3; ++i) {
    const CaptureFrame& f = r.frames[i];
    EXPECT_EQ(f.ev, evs[i]);
    EXPECT_DOUBLE_EQ(f.exposureTimeS, t * r.exposureScale * std::exp2(evs[i]));
    EXPECT_EQ(f.frameIndex, i);
    ASSERT_EQ(f.raws.size(), 1u);
    EXPECT_EQ(f.whiteBalanceGains.size(), 3u);
    EXPECT_NEAR(mean(f.electrons) / mean(r.frames[1].electrons), std::exp2(evs[i]), 1e-6);
  }
  EXPECT_GT(r.frames[2].clippedFraction, r.frames[0].clippedFraction);
  ASSERT_TRUE(r.developed.has_value());
  EXPECT_EQ(r.developed->whiteBalance, r.frames[1].whiteBalanceGains);
  EXPECT_EQ(r.picture.channelCount(), 3);
  EXPECT_EQ(r.picture.width, 32);
}

// A moving scene's motion blur depends on the exposure time: each bracket is rendered
// again with the shutter stretched. Twice the exposure collects twice the energy (the
// plane stays in view), but the image is not 2× the 0 EV one: the blur is longer.
TEST(Capture, AMovingSceneRendersEachBracketAgain) {
  const CaptureResult r = capture(plane(", bracket_ev: [0, 1]", true));
  ASSERT_TRUE(r.stats.modelled.time);
  ASSERT_EQ(r.frames.size(), 2u);
  const Image& e0 = r.frames[0].electrons;
  const Image& e1 = r.frames[1].electrons;
  EXPECT_NEAR(mean(e1) / mean(e0), 2.0, 0.2);
  int differ = 0;
  for (std::size_t p = 0; p < e0.pixels.size(); ++p)
    differ += std::abs(e1.pixels[p] - 2.0f * e0.pixels[p]) > 1e-3f * (1.0f + e1.pixels[p]);
  EXPECT_GT(differ, 50);
}

// The same scene and seeds give the same raw DN for any thread count.
TEST(Capture, TheSameRawsForAnyThreadCount) {
  CaptureOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const CaptureResult a = capture(plane(", bracket_ev: [0, 1]"), one);
  const CaptureResult b = capture(plane(", bracket_ev: [0, 1]"), two);
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (std::size_t i = 0; i < a.frames.size(); ++i)
    EXPECT_EQ(a.frames[i].raws.front().dn, b.frames[i].raws.front().dn) << i;
  EXPECT_EQ(a.picture.pixels, b.picture.pixels);
}

// Cancelled before the first tile: nothing after the render ran, and writeCapture
// writes no file at all.
TEST(Capture, ACancelledCaptureHasNoFramesAndWritesNothing) {
  const std::atomic<bool> cancel{true};
  CaptureOptions options;
  options.cancel = &cancel;
  const CaptureResult r = capture(plane(""), options);
  EXPECT_TRUE(r.cancelled);
  EXPECT_TRUE(r.frames.empty());
  EXPECT_FALSE(r.developed.has_value());
  camsim::test::TempDir dir;
  const WrittenCapture w = writeCapture(r, {dir.path() / "out", {}});
  EXPECT_TRUE(w.files.empty());
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out"));
}

// Cancelled while a moving scene's bracket is rendered again (step 4): the capture is
// cancelled, with no frame — not frames whose electrons lack the re-render's tiles.
TEST(Capture, ACancelDuringTheReRenderOfABracketCancelsTheCapture) {
  std::atomic<bool> cancel{false};
  CaptureOptions options;
  options.threads = 1;
  options.cancel = &cancel;
  // The main render's last tile: cancel from then on (its progress; the re-render has none).
  options.progress = [&](int done, int total) {
    if (done == total) cancel = true;
  };
  const CaptureResult r = capture(plane(", bracket_ev: [0, 1]", true), options);
  EXPECT_TRUE(r.cancelled);
  EXPECT_EQ(r.tilesDone, r.tilesTotal);  // the main film is whole
  EXPECT_TRUE(r.frames.empty());
  EXPECT_FALSE(r.developed.has_value());
}

// Without a sensor the picture is the XYZ film in ACEScg with the mean luminance at 0.18.
TEST(Capture, WithoutASensorThePictureIsTheFilmExposedToMidGrey) {
  SceneDescription d = plane("");
  d.sensor.reset();
  const CaptureResult r = capture(d);
  EXPECT_TRUE(r.frames.empty());
  EXPECT_TRUE(r.sensorFilm.pixels.empty());
  const double meanY = mean(r.film.channel(1));
  EXPECT_NEAR(r.displayExposure, 0.18 / meanY, 1e-9 / meanY);
  EXPECT_EQ(r.picture.channelCount(), 3);
}

// Ground truth asked for lands in NAME.exr beside the image, which keeps its bytes.
TEST(Capture, AovsAreLayersOfTheFilmExr) {
  SceneDescription d = plane("");
  d.render.aovs = {Aov::kDepth, Aov::kNormal};
  const CaptureResult r = capture(d);
  camsim::test::TempDir dir;
  writeCapture(r, {dir.path(), {}});
  const ExrFile exr = readExr(dir.path() / (r.description.name + ".exr"));
  for (const char* c : {"R", "XYZ.Y", "coverage.A", "depth.Z", "N.X", "Ng_cam.Z"})
    EXPECT_GE(exr.image.channelIndex(c), 0) << c;
  EXPECT_EQ(exr.image.channelCount(), 6 + 1 + 1 + 12);
  // The centre pixel sees the square 2 m away.
  EXPECT_FLOAT_EQ(exr.image.at(16, 12, exr.image.channelIndex("depth.Z")), 2.0f);
  const std::string json = camsim::test::readFile(dir.path() / (r.description.name + ".json"));
  EXPECT_NE(json.find("\"aovs\": [\"depth\", \"normal\"]"), std::string::npos) << json;
}

// Adaptive sampling: each pixel's sample count is the `spp` channel of NAME.exr, between the
// minimum and the scene's spp, averaging the render's mean_spp.
TEST(Capture, AnAdaptiveRendersSampleCountsAreALayerOfTheFilmExr) {
  SceneDescription d = plane("");
  d.render.spp = 32;
  d.render.adaptiveThreshold = 0.05;
  d.render.adaptiveMinSpp = 4;
  const CaptureResult r = capture(d);
  camsim::test::TempDir dir;
  writeCapture(r, {dir.path(), {}});
  const ExrFile exr = readExr(dir.path() / (r.description.name + ".exr"));
  const int c = exr.image.channelIndex("spp");
  ASSERT_GE(c, 0);
  double sum = 0.0;
  float lo = 1e9f, hi = 0.0f;
  for (int y = 0; y < exr.image.height; ++y)
    for (int x = 0; x < exr.image.width; ++x) {
      const float n = exr.image.at(x, y, c);
      sum += double{n};
      lo = std::min(lo, n);
      hi = std::max(hi, n);
    }
  EXPECT_GE(lo, 4.0f);
  EXPECT_LE(hi, 32.0f);
  EXPECT_LT(lo, hi) << "the plane's edge and its flat inside take different counts";
  EXPECT_NEAR(sum / (exr.image.width * exr.image.height), r.stats.meanSpp, 1e-6);
  const std::string json = camsim::test::readFile(dir.path() / (r.description.name + ".json"));
  EXPECT_NE(json.find("\"min_spp\": 4,"), std::string::npos) << json;
  // Found by probing: a minimum above spp was recorded as min_spp, though every pixel took
  // spp; the sidecar says what the pixels took.
  SceneDescription above = d;
  above.render.spp = 8;
  above.render.adaptiveMinSpp = 64;
  const CaptureResult all = capture(above);
  camsim::test::TempDir dir2;
  writeCapture(all, {dir2.path(), {}});
  EXPECT_EQ(all.stats.meanSpp, 8.0);
  const std::string json2 = camsim::test::readFile(dir2.path() / (all.description.name + ".json"));
  EXPECT_NE(json2.find("\"min_spp\": 8,"), std::string::npos) << json2;
  // A fixed render has no such layer.
  d.render.adaptiveThreshold.reset();
  const CaptureResult fixed = capture(d);
  EXPECT_TRUE(fixed.sampleCounts.pixels.empty());
}

}  // namespace
}  // namespace camsim
