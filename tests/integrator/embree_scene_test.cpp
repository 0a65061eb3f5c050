// EmbreeScene with moving shapes: rigidly moving shapes are traced as motion-blurred
// instances of their first pose, the rest as motion-blurred geometry. Either way Embree's
// hit must be the point the shape itself puts at the ray's time (the shading, light
// sampling and error bounds all use the shape's own poses), and rays spawned from a hit
// must not hit the same surface again.
#include "integrator/embree_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "integrator/scene.h"
#include "integrator/scene_loader.h"
#include "integrator/sphere.h"
#include "integrator/triangle_mesh.h"

namespace camsim {
namespace {

constexpr float kExposure = 0.01f;  // s

// Three shapes 2 m apart, 3 m in front of the camera, all moving during [0, 10 ms]:
//  0: a 1 m × 0.2 m blade turning 120° about a tilting axis while translating (rigid);
//  1: a sphere of radius 0.1 m translating (rigid);
//  2: a quad growing from scale 1 to 2 while translating (not rigid: its size changes).
const char* kYaml = R"(
camera: {position: [0, 0, 0], look_at: [0, 0, 1], sensor_width_mm: 36, sensor_height_mm: 24,
         resolution: [36, 24], focal_length_mm: 50, shutter: {open: 0, close: 0.01}}
materials: {grey: {type: diffuse, reflectance: 0.5}}
shapes:
  - type: mesh
    material: grey
    vertices: [[-0.5, -0.1, 0], [0.5, -0.1, 0], [0.5, 0.1, 0], [-0.5, 0.1, 0]]
    faces: [[0, 1, 2, 3]]
    motion:
      - {time: 0, translate: [0.2, 0, 3], rotate: {axis: [0, 0, 1], angle_deg: 0}}
      - {time: 0.005, translate: [0.1, 0.1, 3], rotate: {axis: [0.1, 0, 1], angle_deg: 60}}
      - {time: 0.01, translate: [0, 0.2, 3.2], rotate: {axis: [0.2, 0, 1], angle_deg: 120}}
  - type: sphere
    material: grey
    centre: [0, 0, 0]
    radius: 0.1
    motion: [{time: 0, translate: [-2, 0, 3]}, {time: 0.01, translate: [-1.8, 0.1, 3.1]}]
  - type: mesh
    material: grey
    vertices: [[-0.1, -0.1, 0], [0.1, -0.1, 0], [0.1, 0.1, 0], [-0.1, 0.1, 0]]
    faces: [[0, 1, 2, 3]]
    motion: [{time: 0, translate: [2, 0, 3], scale: 1}, {time: 0.01, translate: [2.1, 0, 3], scale: 2}]
)";

// The sphere's centre at `time`, interpolated between its steps as Sphere does.
glm::vec3 sphereCentre(const Sphere& sphere, float time) {
  int step;
  float f;
  sphere.timeSteps().locate(time, step, f);
  const auto k = static_cast<size_t>(step);
  return f == 0.0f ? sphere.centres()[k]
                   : glm::mix(sphere.centres()[k], sphere.centres()[k + 1], f);
}

// A point on shape `index` at `time`, by the shape's own interpolation, with its normal.
SurfaceInteraction pointOn(const Scene& scene, int index, std::mt19937& rng, float time) {
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const Shape& shape = scene.shape(index);
  if (const auto* sphere = dynamic_cast<const Sphere*>(&shape)) {
    const float z = 1.0f - 2.0f * u01(rng), phi = 6.2831853f * u01(rng);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const glm::vec3 n(r * std::cos(phi), r * std::sin(phi), z);
    SurfaceInteraction si;
    si.p = sphereCentre(*sphere, time) + sphere->radii()[0] * n;
    si.n = n;
    return si;
  }
  const auto& mesh = dynamic_cast<const TriangleMesh&>(shape);
  Hit hit;
  hit.shape = index;
  hit.prim = static_cast<int>(rng() % mesh.triangleCount());
  hit.u = u01(rng);
  hit.v = u01(rng) * (1.0f - hit.u);
  Ray ray;
  ray.time = time;
  return mesh.interaction(hit, ray);
}

TEST(EmbreeScene, RigidMotionsAreInstancedAndChangingSizesAreNot) {
  const Scene scene(loadSceneFromText(kYaml, "moving.yaml", "."));
  const int steps = scene.shape(0).timeSteps().count;
  ASSERT_GT(steps, 60);  // 120° at ≤ 2° per step
  EXPECT_EQ(scene.shape(0).rigidSteps().size(), static_cast<size_t>(steps));
  EXPECT_EQ(scene.shape(1).rigidSteps().size(),
            static_cast<size_t>(scene.shape(1).timeSteps().count));
  EXPECT_TRUE(scene.shape(2).rigidSteps().empty());
  EXPECT_GT(scene.shape(2).timeSteps().count, 1);
  // Step 0 is the identity; the last step maps the first pose onto the last.
  const auto& mesh = dynamic_cast<const TriangleMesh&>(scene.shape(0));
  const glm::mat4& last = mesh.rigidSteps().back();
  for (size_t v = 0; v < 4; ++v) {
    const glm::vec3 moved(last * glm::vec4(mesh.positions(0)[v], 1.0f));
    EXPECT_LT(glm::length(moved - mesh.positions(steps - 1)[v]), 1e-6f) << v;
  }
}

// Rays from 0.7 m away (within 72° of the normal) at random times towards points that the
// shapes put there at those times. Tolerance 1e-5 m on the hit point: float rounding at
// 3 m is ≈ 1e-6 m, while a pose from the wrong time is off by centimetres and slerped
// instead of linearly interpolated transforms by up to 7.6e-5 m (2° steps of a 0.5 m arm).
TEST(EmbreeScene, MovingShapesAreHitWhereTheirPosesPutThemAtTheRaysTime) {
  const Scene scene(loadSceneFromText(kYaml, "moving.yaml", "."));
  const EmbreeScene& geometry = scene.geometry();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  float worst = 0.0f;
  for (int index = 0; index < 3; ++index)
    for (int i = 0; i < 2000; ++i) {
      const float time = kExposure * u01(rng);
      const SurfaceInteraction target = pointOn(scene, index, rng, time);
      glm::vec3 w;
      do {
        w = glm::vec3(u01(rng), u01(rng), u01(rng)) * 2.0f - 1.0f;
      } while (glm::dot(w, w) > 1.0f || glm::dot(w, w) < 1e-4f);
      w = glm::normalize(w);
      if (glm::dot(w, target.n) < 0.0f) w = -w;
      if (glm::dot(w, target.n) < 0.3f) continue;
      Ray ray;
      ray.o = target.p + 0.7f * w;
      ray.d = -w;
      ray.time = time;
      Hit hit;
      ASSERT_TRUE(geometry.intersect(ray, hit)) << "shape " << index << " sample " << i;
      ASSERT_EQ(hit.shape, index) << "sample " << i;
      const float miss = glm::length(ray.at(hit.t) - target.p);
      worst = std::max(worst, miss);
      ASSERT_LT(miss, 1e-5f) << "shape " << index << " sample " << i << " time " << time;

      // Spawned rays: back towards the origin nothing is in the way; onward through the
      // surface the same surface is not hit again (a sphere's far side is ≥ 6 cm away).
      const SurfaceInteraction si = scene.shape(index).interaction(hit, ray);
      Ray back;
      back.o = si.spawnOrigin(w);
      back.d = w;
      back.tMax = 0.6f;
      back.time = time;
      EXPECT_FALSE(geometry.occluded(back)) << "shape " << index << " sample " << i;
      Ray onward = back;
      onward.o = si.spawnOrigin(-w);
      onward.d = -w;
      onward.tMax = std::numeric_limits<float>::infinity();
      Hit again;
      if (geometry.intersect(onward, again)) {
        EXPECT_TRUE(again.shape != index || again.t > 1e-3f)
            << "shape " << index << " sample " << i << " t " << again.t;
      }
    }
  RecordProperty("worst_hit_distance_m", std::to_string(worst));
}

}  // namespace
}  // namespace camsim
