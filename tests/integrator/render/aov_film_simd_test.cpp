// AovFilm's per-sample code is compiled twice (aov_film_add.cpp): for the build's target and
// for AVX2. Both must give the same bytes: the same first hits (on moving and static
// shapes, misses, a turning camera for the camera-axes normals, the motion field, albedo
// at terminated wavelengths, occlusion and boundaries) added to two films, one held to the
// target's copy, end in identical images. Where the CPU has no AVX2 (or the portable
// build), both films run the same copy and the test says so.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "integrator/render/aov_film.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"

namespace camsim {
namespace {

constexpr const char* kSimdScene = R"(
camera:
  position: [0, 0.5, -2]
  look_at: [0, 0.4, 2]
  up: [0, 1, 0]
  resolution: [8, 6]
  sensor_width_mm: 36
  sensor_height_mm: 24
  focal_length_mm: 35
  motion:
    - {time: 0, translate: [-0.2, 0, 0], rotate: {axis: [0, 1, 0], angle_deg: -2}}
    - {time: 0.25, translate: [0.2, 0, 0], rotate: {axis: [0, 1, 0], angle_deg: 2}}
render:
  spp: 16
  aovs: [depth, distance, position, normal, albedo, roughness, instance_id, class_id, material_id, motion, occlusion, boundary]
frames: {count: 3, rate_hz: 24, shutter_angle_deg: 180}
materials:
  grey: {type: diffuse, reflectance: 0.5}
shapes:
  - {name: wall, type: rectangle, corner: [-4, 0, 3], edge_u: [8, 0, 0], edge_v: [0, 3, 0], material: grey}
  - name: ball
    class: ball
    type: sphere
    centre: [0, 0.2, 1]
    radius: 0.2
    material: grey
    motion:
      - {time: 0, translate: [-0.5, 0, 0]}
      - {time: 0.25, translate: [0.5, 0, 0]}
lights:
  - {type: point, position: [0, 2, 0], intensity: 10}
)";

TEST(AovFilmSimd, TargetAndAvx2CopiesGiveTheSameBytes) {
  const SceneDescription d = loadSceneFromText(kSimdScene, "simd.yaml", ".");
  Scene scene(d, glm::dvec2(0.0, 0.25));
  scene.setCamera(d.frameCamera(1));
  AovFilm avx2(scene), target(scene, false);
  EXPECT_FALSE(target.usesAvx2());
  if (!avx2.usesAvx2())
    std::printf(
        "note: no AVX2 on this CPU (or the portable build): one copy compared with itself\n");
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  AovPixel a, b;
  const glm::ivec2 res = scene.camera().resolution();
  for (int y = 0; y < res.y; ++y)
    for (int x = 0; x < res.x; ++x) {
      avx2.startPixel(a, {x, y});
      target.startPixel(b, {x, y});
      for (int s = 0; s < 40; ++s) {  // more than a batch (AovPixel::kBatch)
        VisibleSurface v;
        v.hit = u(rng) < 0.9f;  // some misses
        v.shape = u(rng) < 0.5f ? 0 : 1;
        v.p = glm::vec3(2.0f * u(rng) - 1.0f, u(rng), 1.0f + 2.0f * u(rng));
        v.n = glm::normalize(glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, -1.0f));
        v.ns = glm::normalize(v.n + 0.1f * glm::vec3(u(rng), u(rng), u(rng)));
        v.distance = 1.0f + 3.0f * u(rng);
        v.roughness = u(rng);
        for (int i = 0; i < kWavelengthSamples; ++i) v.albedo[i] = u(rng);
        SampledWavelengths lambda = SampledWavelengths::sampleVisible(u(rng));
        if (s % 5 == 0) lambda.terminateSecondary();  // pdf 0 at three wavelengths
        const double t = 1.0 / 24.0 + static_cast<double>(u(rng)) / 48.0;
        const glm::dmat4 pose = scene.camera().worldFromCameraAt(t);
        avx2.nextSurface(a) = v;
        target.nextSurface(b) = v;
        avx2.addSample(a, {t, lambda, &pose});
        target.addSample(b, {t, lambda, &pose});
      }
      avx2.endPixel(a);
      target.endPixel(b);
      // The pixel's double sums, bit for bit (the images below are floats, which would hide
      // a difference in the last bits of a sum).
      const auto same = [](const auto& p, const auto& q) {
        return std::memcmp(&p, &q, sizeof p) == 0;
      };
      EXPECT_TRUE(same(a.scalars, b.scalars) && same(a.position, b.position) &&
                  same(a.normal, b.normal) && same(a.geometricNormal, b.geometricNormal) &&
                  same(a.normalCam, b.normalCam) &&
                  same(a.geometricNormalCam, b.geometricNormalCam) && same(a.albedo, b.albedo) &&
                  same(a.white, b.white) && same(a.motionLanes, b.motionLanes) &&
                  same(a.flow, b.flow) && same(a.ids, b.ids))
          << "pixel " << x << ", " << y;
    }
  const Image ia = avx2.takeImage(), ib = target.takeImage();
  ASSERT_EQ(ia.channels, ib.channels);
  ASSERT_EQ(ia.pixels.size(), ib.pixels.size());
  EXPECT_EQ(std::memcmp(ia.pixels.data(), ib.pixels.data(), ia.pixels.size() * sizeof(float)), 0);
  // The images are not empty: the motion, albedo and camera-axes normals were exercised.
  for (const char* c :
       {"motion_fw.X", "flow_fw.X", "albedo.G", "N_cam.X", "depth.Z", "boundary.A"}) {
    const int i = ia.channelIndex(c);
    ASSERT_GE(i, 0) << c;
    bool nonZero = false;
    for (int y = 0; y < res.y; ++y)
      for (int x = 0; x < res.x; ++x) nonZero = nonZero || ia.at(x, y, i) != 0.0f;
    EXPECT_TRUE(nonZero) << c;
  }
}

}  // namespace
}  // namespace camsim
