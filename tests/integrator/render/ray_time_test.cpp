// Ray times against Embree's motion range, for any shutter position and length.
//
// Embree takes a ray's time as a fraction of the motion span, asserting it lies in [0, 1];
// camsim keeps the ray's time in double absolute seconds and maps it in double
// (EmbreeScene::embreeTime). Kept in float, a time near 10⁶ s was rounded to 0.0625 s and
// a 1 µs shutter there mapped tens of thousands of spans outside [0, 1] (Embree aborted).
//  - 10 000 random (open, length, keyframes) windows, 1 µs … 10⁶ s: the camera ray of
//    shutter samples from the open to the close is handed a time equal to its exact
//    fraction of the span within float rounding (1.2e-7), inside [0, 1];
//  - 300 of them, and the four windows, render a keyframed quad with finite pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "integrator/camera/physical_camera.h"
#include "integrator/capture/capture.h"
#include "integrator/geometry/embree_scene.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "tests/support/scene_text.h"

namespace camsim {
namespace {

using test::num;

struct Window {
  double open, length, key0, key1;  // s
};

// Log-uniform in [lo, hi].
double logUniform(std::mt19937_64& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(std::log(lo), std::log(hi));
  return std::exp(u(rng));
}

// A shutter opening in [1 µs, 10⁶ s), length in [1 µs, 10⁶ s) (kept within the loader's
// ±10⁶ s), keyframes before the open and after the close or inside the window.
Window randomWindow(std::mt19937_64& rng) {
  Window w;
  w.open = logUniform(rng, 1e-6, 9.9e5);
  w.length = std::min(logUniform(rng, 1e-6, 1e6), 1e6 - w.open);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  w.key0 = w.open - (u(rng) < 0.5 ? w.length * u(rng) : -0.5 * w.length * u(rng));
  w.key1 = w.open + w.length * (0.5 + u(rng));
  if (!(w.key1 > w.key0)) w.key1 = std::nextafter(w.key0, 1e300);
  return w;
}

std::string quadScene(const Window& w, const std::string& extra = "") {
  return "camera: {position: [0, 0, 5], look_at: [0, 0, 0], resolution: [8, 8], shutter: "
         "{open: " +
         num(w.open) + ", close: " + num(w.open + w.length) +
         "}}\n"
         "render: {spp: 1, max_depth: 1}\n"
         "lights: [{type: distant, direction: [0, 0, -1], illuminance: 1000}]\n"
         "materials: {m: {type: diffuse, reflectance: 0.5}}\n" +
         extra +
         "shapes:\n"
         "  - {type: mesh, material: m, vertices: [[-0.5, -0.5, 0], [0.5, -0.5, 0], [0.5, 0.5, "
         "0], [-0.5, 0.5, 0]], faces: [[0, 1, 2, 3]],\n"
         "     motion: [{time: " +
         num(w.key0) + ", translate: [0, 0, 0]}, {time: " + num(w.key1) +
         ", translate: [0, 2, 0]}]}\n";
}

void expectFinite(const Image& image) {
  for (float v : image.pixels) ASSERT_TRUE(std::isfinite(v));
}

TEST(RayTime, EveryShutterWindowMapsInsideEmbreesRange) {
  std::mt19937_64 rng(20261203);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const std::vector<std::unique_ptr<Shape>> noShapes;
  PhysicalCameraParams params;
  params.resolution = {8, 8};
  double worst = 0.0;
  for (int i = 0; i < 10000; ++i) {
    const Window w = randomWindow(rng);
    params.shutter = Shutter::box(w.open, w.open + w.length);
    const PhysicalCamera camera(params);
    const glm::dvec2 span = exposureWindow(camera);
    ASSERT_EQ(span.x, w.open);
    EmbreeScene embree(noShapes, span.x, span.y);
    for (float u : {0.0f, 0.5f, std::nextafter(1.0f, 0.0f), u01(rng), u01(rng)}) {
      CameraSample cs;
      cs.pFilm = {4.0f, 4.0f};
      cs.time = camera.shutter().sample(static_cast<double>(u));
      const std::optional<CameraRay> ray =
          camera.generateRay(cs, SampledWavelengths::sampleVisible(0.5f));
      ASSERT_TRUE(ray.has_value());
      const float handed = embree.embreeTime(ray->ray.time);
      const long double exact = (static_cast<long double>(cs.time) - span.x) / (span.y - span.x);
      ASSERT_GE(handed, 0.0f) << "window " << i;
      ASSERT_LE(handed, 1.0f) << "window " << i;
      const double error = static_cast<double>(std::abs(static_cast<long double>(handed) - exact));
      worst = std::max(worst, error);
      ASSERT_LE(error, 1.2e-7) << "window " << i << ": open " << w.open << " s, length " << w.length
                               << " s, u " << u;
    }
  }
  std::printf("10000 windows: worst |embree time - exact fraction| %.3g\n", worst);
}

TEST(RayTime, KeyframedQuadRendersForRandomShutterWindows) {
  std::mt19937_64 rng(7);
  RenderOptions options;
  options.spp = 1;
  options.threads = 1;
  for (int i = 0; i < 300; ++i) {
    const Window w = randomWindow(rng);
    const Scene scene(loadSceneFromText(quadScene(w), "window.yaml", "."));
    const RenderResult r = render(scene, SpectralResponse::cieXyz(), options);
    EXPECT_EQ(r.stats.rejectedSamples, 0u) << "window " << i;
    expectFinite(r.image);
  }
}

// The reproducers: a short shutter after 0 over a keyframed quad, a 1e-45 s one,
// 1 µs at 10⁶ s between keyframes 1.5 µs apart, and a 24 fps sequence from frame 36 with
// an 8.64° shutter (1 ms at 1.5 s).
TEST(RayTime, ShortShuttersAfterZeroRender) {
  for (const Window& w :
       {Window{1.5, 0.001, 1.25, 2.5}, Window{1.5625, 0.001, 1.25, 2.5},
        Window{0.0, 1e-45, -1.0, 1.0}, Window{1e6 - 1e-6, 1e-6, 1e6 - 1.5e-6, 1e6}}) {
    SceneDescription d = loadSceneFromText(quadScene(w), "short_shutter.yaml", ".");
    d.render.spp = 16;
    const CaptureResult r = capture(std::move(d));
    expectFinite(r.film);
    const int y = r.film.channelIndex("Y");
    double sum = 0.0;
    for (int j = 0; j < r.film.height; ++j)
      for (int k = 0; k < r.film.width; ++k) sum += static_cast<double>(r.film.at(k, j, y));
    // The quad is seen (a 1e-45 s exposure's energy is below float's range: 0).
    if (w.length > 1e-30) {
      EXPECT_GT(sum, 0.0) << "open " << w.open;
    }
  }
  const std::string frames =
      "frames: {first: 36, count: 2, rate_hz: 24, shutter_angle_deg: 8.64}\n";
  SceneDescription seq =
      loadSceneFromText(quadScene({0.0, 0.01, 1.25, 2.5}, frames), "sequence.yaml", ".");
  int written = 0;
  captureSequence(std::move(seq), {}, [&](CaptureResult&& frame, int) {
    expectFinite(frame.film);
    ++written;
  });
  EXPECT_EQ(written, 2);
}

}  // namespace
}  // namespace camsim
