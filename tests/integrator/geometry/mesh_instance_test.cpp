// Tests for integrator/geometry/mesh_instance.cpp: an instance of a shared mesh under a
// stretching, mirroring placement gives the points, normals and texture coordinates of the
// same placement baked into a TriangleMesh (the copy), Embree hits it where it hits the
// copy, rays spawned from its hits do not hit it again, and an emitting instance samples
// points uniformly by its placed area with the pdf its pdf() gives.
#include "integrator/geometry/mesh_instance.h"

#include <gtest/gtest.h>

#include <random>

#include "integrator/geometry/embree_scene.h"
#include "tests/integrator/instance_test_support.h"

namespace camsim {
namespace {

using test::baked;
using test::bumpySphere;
using test::placementOf;
using test::staticMeshOf;

// Stretched (×1.7, ×0.6, ×0.9), mirrored (the y scale is negative), turned 37° and moved.
const glm::dmat4 kStretchMirror =
    placementOf({0.3, -0.2, 2.0}, {1.0, 2.0, 3.0}, 37.0, {1.7, -0.6, 0.9});

// Barycentrics ≥ 1e-3 from the edges (a point on an edge may belong to either triangle).
Hit randomHit(std::mt19937& rng, size_t triangles) {
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  Hit hit;
  hit.shape = 0;
  hit.prim = static_cast<int>(rng() % triangles);
  hit.u = 1e-3f + 0.997f * u01(rng);
  hit.v = 1e-3f + (0.998f - hit.u) * u01(rng);
  return hit;
}

// The instance and the copy agree on every field of the interaction: p within the sum of
// their error bounds (and 2e-6 m: a few float ulps at 2 m), n and ns within 1e-5 (float
// normalisation of differently rounded vectors), uv exactly (the same object-space
// barycentric interpolation). Without vertex normals n alone decides the front, so the
// mirrored instance must flip it exactly as the baked copy's winding does.
void expectSameInteractions(bool withNormals) {
  MeshData mesh = bumpySphere();
  if (!withNormals) mesh.normals.clear();
  const MeshInstance instance(staticMeshOf(mesh), {kStretchMirror}, TimeSteps{}, false);
  const std::shared_ptr<TriangleMesh> copy = staticMeshOf(baked(mesh, kStretchMirror));
  std::mt19937 rng(11);
  int outward = 0;
  for (int i = 0; i < 5000; ++i) {
    const Hit hit = randomHit(rng, copy->triangleCount());
    const Ray ray;
    const SurfaceInteraction a = instance.interaction(hit, ray), b = copy->interaction(hit, ray);
    for (int axis = 0; axis < 3; ++axis) {
      const float d = std::abs(a.p[axis] - b.p[axis]);
      EXPECT_LE(d, a.pError[axis] + b.pError[axis]) << i << " axis " << axis;
      EXPECT_LE(d, 2e-6f) << i << " axis " << axis;
    }
    EXPECT_GT(glm::dot(a.n, b.n), 1.0f - 1e-5f) << i;
    EXPECT_GT(glm::dot(a.ns, b.ns), 1.0f - 1e-5f) << i;
    EXPECT_EQ(a.uv, b.uv) << i;
    EXPECT_EQ(a.prim, hit.prim);
    // The bumpy sphere's front faces out (away from the placed centre) unless mirroring
    // flipped the winding of a mesh without normals.
    outward += glm::dot(a.n, a.p - glm::vec3(kStretchMirror[3])) > 0.0f ? 1 : 0;
  }
  EXPECT_EQ(outward, withNormals ? 5000 : 0);
}

TEST(MeshInstance, StretchedMirroredInstanceHasTheBakedCopysPointsAndNormals) {
  expectSameInteractions(true);
}

TEST(MeshInstance, MirroringFlipsTheFrontOfAMeshWithoutNormalsAsBakingDoes) {
  expectSameInteractions(false);
}

// Embree traces the instance (its shared mesh under an instance transform) and the copy
// (its own baked triangles): rays from 1 m away towards points on the copy hit both at the
// same triangle and point; rays spawned from the instance's hits, back towards the origin
// and on through the surface, never hit the same triangle again. Far from the origin (the
// second placement, ≈ 900 m away and stretched 4:1) Embree's move of the spawned rays into
// object space rounds at ≈ 6e-5 m, far above the object-space error of the point: without
// the instance term of pError (mesh_instance.h) such rays can hit their own triangle.
void expectEmbreeHitsAsOnTheCopy(const glm::dmat4& placement, float scale) {
  const MeshData mesh = bumpySphere();
  std::vector<std::unique_ptr<Shape>> instanced, copied;
  instanced.push_back(std::make_unique<MeshInstance>(
      staticMeshOf(mesh), std::vector<glm::dmat4>{placement}, TimeSteps{}, false));
  const std::shared_ptr<TriangleMesh> copy = staticMeshOf(baked(mesh, placement));
  copied.push_back(std::make_unique<TriangleMesh>(copy->positions(), copy->normals(),
                                                  copy->indices(), TimeSteps{}, copy->uvs()));
  const EmbreeScene a(instanced, 0.0, 1.0), b(copied, 0.0, 1.0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int samePrim = 0, selfHits = 0, spawned = 0, oneMissed = 0;
  const int rays = 20000;
  for (int i = 0; i < rays; ++i) {
    const Hit target = randomHit(rng, copy->triangleCount());
    const glm::vec3 p = copy->interaction(target, Ray{}).p;
    glm::vec3 dir(u(rng), u(rng), u(rng));
    if (glm::length(dir) < 0.1f) dir = {0.0f, 0.0f, 1.0f};
    const Ray ray{p - glm::normalize(dir), glm::normalize(dir), 2.0f, 0.0f};
    Hit ha, hb;
    const bool hitA = a.intersect(ray, ha), hitB = b.intersect(ray, hb);
    if (hitA != hitB) ++oneMissed;  // a graze past a silhouette in one of the two
    if (!hitA || !hitB) continue;
    const SurfaceInteraction sa = instanced[0]->interaction(ha, ray);
    if (ha.prim == hb.prim) {
      ++samePrim;
      const SurfaceInteraction sb = copied[0]->interaction(hb, ray);
      // Along the ray the hit moves by the rounding of the ray (a few ulps of 2 m) over the
      // cosine of incidence: grazing hits are further apart.
      const float cosine = std::abs(glm::dot(sb.n, ray.d));
      ASSERT_LT(glm::length(sa.p - sb.p), scale * (1.5e-7f / cosine + 1e-6f))
          << i << " cos " << cosine;
    }
    for (const glm::vec3 w : {-ray.d, ray.d}) {
      const Ray next{sa.spawnOrigin(w), w, 1.0f, 0.0f};
      Hit again;
      ++spawned;
      if (a.intersect(next, again) && again.prim == ha.prim && again.t < 1e-3f) ++selfHits;
    }
  }
  // The rest: ties on shared edges and grazing rays that pass a silhouette in one scene and
  // hit the next triangle in the other.
  EXPECT_GT(samePrim, rays * 99 / 100);
  EXPECT_LE(oneMissed, rays / 500);
  EXPECT_EQ(selfHits, 0) << "of " << spawned;
}

TEST(MeshInstance, EmbreeHitsTheInstanceWhereItHitsTheCopy) {
  expectEmbreeHitsAsOnTheCopy(kStretchMirror, 2.0f);  // scale: the coordinates' size, m
}

TEST(MeshInstance, FarStretchedInstanceSpawnsRaysThatLeaveIt) {
  expectEmbreeHitsAsOnTheCopy(
      placementOf({300.0, -200.0, 800.0}, {0.3, 1.0, -0.5}, 71.0, {4.0, 1.0, -1.0}), 900.0f);
}

// An emitting instance under the stretching placement: its area is the copy's; each light
// sample carries the density pdf() gives its point, which is the copy's (1 / area, as
// solid angle); and the triangles are chosen in proportion to their placed areas (χ²-like
// bound on the counts: a choice by object-space area is off by up to a factor 2.8 here).
TEST(MeshInstance, EmittingInstanceSamplesByPlacedArea) {
  const MeshData mesh = bumpySphere(8, 6);
  const MeshInstance instance(staticMeshOf(mesh), {kStretchMirror}, TimeSteps{}, true);
  const std::shared_ptr<TriangleMesh> copy = staticMeshOf(baked(mesh, kStretchMirror), true);
  EXPECT_NEAR(instance.area() / copy->area(), 1.0f, 1e-5f);
  const glm::vec3 ref(0.5f, 0.3f, 1.2f);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::vector<double> counts(copy->triangleCount(), 0.0);
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const std::optional<ShapeSample> s = instance.sample(ref, u01(rng), {u01(rng), u01(rng)}, 0);
    ASSERT_TRUE(s);
    EXPECT_NEAR(s->pdf / instance.pdf(ref, s->point), 1.0f, 1e-5f) << i;
    EXPECT_NEAR(s->pdf / copy->pdf(ref, s->point), 1.0f, 1e-4f) << i;
    counts[static_cast<size_t>(s->point.prim)] += 1.0;
  }
  // Each triangle's count against n · area_k / area, in standard deviations (binomial,
  // ≈ √mean): below 5 for all 80 triangles (measured: see the property).
  double worst = 0.0;
  const std::vector<glm::vec3>& p = copy->positions();
  const std::vector<std::uint32_t>& idx = copy->indices();
  for (size_t k = 0; k < counts.size(); ++k) {
    const glm::dvec3 p0(p[idx[3 * k]]), p1(p[idx[3 * k + 1]]), p2(p[idx[3 * k + 2]]);
    const double area = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
    const double mean = n * area / static_cast<double>(copy->area());
    worst = std::max(worst, std::abs(counts[k] - mean) / std::sqrt(mean + 1.0));
  }
  RecordProperty("worst_count_sigma", std::to_string(worst));
  EXPECT_LT(worst, 5.0);
}

// A moving emitting instance: the samples' pdf is pdf()'s at their time (the area of the
// triangle under the interpolated transform).
TEST(MeshInstance, MovingEmittingInstanceSamplesCarryThePdfOfTheirPoint) {
  const MeshData mesh = bumpySphere(8, 6);
  std::vector<glm::dmat4> poses;
  for (int k = 0; k < 5; ++k)
    poses.push_back(placementOf({0.1 * k, 0.0, 2.0}, {0.0, 1.0, 0.2}, 10.0 * k, {1.0, 1.0, 1.0}) *
                    kStretchMirror);
  const MeshInstance instance(staticMeshOf(mesh), poses, TimeSteps{0.0, 0.01, 5}, true);
  ASSERT_FALSE(instance.instanceMotion().empty());
  const glm::vec3 ref(0.5f, 0.3f, 0.2f);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (int i = 0; i < 20000; ++i) {
    const double time = 0.01f * u01(rng);
    const std::optional<ShapeSample> s = instance.sample(ref, u01(rng), {u01(rng), u01(rng)}, time);
    if (!s) continue;
    EXPECT_NEAR(s->pdf / instance.pdf(ref, s->point), 1.0f, 1e-5f) << i;
    EXPECT_EQ(s->point.time, time);
  }
}

}  // namespace
}  // namespace camsim
