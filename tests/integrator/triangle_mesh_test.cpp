// Tests for integrator/triangle_mesh.cpp: a moving, emitting mesh's light samples carry
// the density pdf() gives the same point (sample() reuses the area pointOn computed; pdf()
// computes it from the triangle at the point's time).
#include "integrator/triangle_mesh.h"

#include <gtest/gtest.h>

#include <random>

#include "integrator/scene.h"
#include "integrator/scene_loader.h"

namespace camsim {
namespace {

TEST(TriangleMesh, MovingEmitterSamplesCarryThePdfOfTheirPoint) {
  // Two triangles of different sizes, growing and turning over the 10 ms shutter.
  const Scene scene(loadSceneFromText(
      "camera: {position: [0, 0, -3], look_at: [0, 0, 0], shutter: {open: 0, close: 0.01}}\n"
      "shapes:\n"
      "  - type: mesh\n"
      "    vertices: [[-1, -1, 0], [1, -1, 0], [0, 1, 0], [2, 0, 0], [3, 0, 0], [2, 0.3, 0]]\n"
      "    faces: [[0, 1, 2], [3, 4, 5]]\n"
      "    emission: {luminance: 100}\n"
      "    motion: [{time: 0}, {time: 0.01, translate: [0.2, 0, 0.5], scale: 2,\n"
      "              rotate: {axis: [0, 1, 0], angle_deg: 40}}]\n",
      "moving_light.yaml", "."));
  const Shape& mesh = scene.shape(0);
  ASSERT_NE(dynamic_cast<const TriangleMesh*>(&mesh), nullptr);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const glm::vec3 ref(0.3f, 0.2f, -2.0f);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const float time = 0.01f * u01(rng);
    const std::optional<ShapeSample> s = mesh.sample(ref, u01(rng), {u01(rng), u01(rng)}, time);
    if (!s) continue;
    const float pdf = mesh.pdf(ref, s->point);
    ASSERT_GT(pdf, 0.0f);
    EXPECT_NEAR(s->pdf / pdf, 1.0f, 1e-5f) << "sample " << i << " time " << time;
    ++checked;
  }
  EXPECT_GT(checked, 1900);
}

}  // namespace
}  // namespace camsim
