// Tests for integrator/geometry/triangle_mesh.cpp: a moving, emitting mesh's light samples carry
// the density pdf() gives the same point (sample() reuses the area pointOn computed; pdf()
// computes it from the triangle at the point's time); a planar emitter's front plane only
// ever rejects reference points that every sampled point faces away from; a static mesh's
// stored normals are the bits a moving mesh computes at rest; a parallelogram is sampled as
// one.
#include "integrator/geometry/triangle_mesh.h"

#include <gtest/gtest.h>

#include <random>

#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"

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
    const double time = 0.01f * u01(rng);
    const std::optional<ShapeSample> s = mesh.sample(ref, u01(rng), {u01(rng), u01(rng)}, time);
    if (!s) continue;
    const float pdf = mesh.pdf(ref, s->point);
    ASSERT_GT(pdf, 0.0f);
    EXPECT_NEAR(s->pdf / pdf, 1.0f, 1e-5f) << "sample " << i << " time " << time;
    ++checked;
  }
  EXPECT_GT(checked, 1900);
}

TriangleMesh staticMesh(std::vector<glm::vec3> positions, std::vector<std::uint32_t> indices,
                        std::vector<glm::vec3> normals = {}) {
  return TriangleMesh(std::move(positions), std::move(normals), std::move(indices), TimeSteps{});
}

// A static mesh stores its triangles' normals; a moving one computes them at each hit. At
// rest (identity poses) both must give the same bits, and the exact normal within rounding;
// a zero-area triangle gets +z.
TEST(TriangleMesh, StoredNormalsAreTheOnesAMovingMeshComputes) {
  const std::vector<glm::vec3> positions = {{0, 0, 0},     {1, 0, 0},          {0, 1, 0},
                                            {0.3f, -2, 5}, {-1, 0.7f, 2},      {4, 1e-3f, -0.5f},
                                            {2, 2, 2},     {2.5f, 2.5f, 2.5f}, {3, 3, 3}};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 3, 4, 5, 2, 5, 3, 6, 7, 8};
  const TriangleMesh still = staticMesh(positions, indices);
  const TriangleMesh moving(positions, {}, indices, TimeSteps{0.0, 1.0, 2}, {}, true,
                            InstanceMotion::fromPoses({glm::dmat4(1.0), glm::dmat4(1.0)}));
  for (int tri = 0; tri < 4; ++tri) {
    Hit hit;
    hit.prim = tri;
    hit.u = 0.2f;
    hit.v = 0.3f;
    const Ray ray{{0, 0, -1}, {0, 0, 1}, 10.0f, 0.5f};
    const SurfaceInteraction a = still.interaction(hit, ray), b = moving.interaction(hit, ray);
    EXPECT_EQ(a.n, b.n) << "triangle " << tri;
    EXPECT_EQ(a.ns, a.n) << "triangle " << tri;
    const size_t k = 3 * static_cast<size_t>(tri);
    const glm::dvec3 p0(positions[indices[k]]), p1(positions[indices[k + 1]]),
        p2(positions[indices[k + 2]]);
    const glm::dvec3 cross = glm::cross(p1 - p0, p2 - p0);
    const glm::dvec3 exact =
        glm::length(cross) > 0.0 ? glm::normalize(cross) : glm::dvec3(0.0, 0.0, 1.0);
    EXPECT_LT(glm::length(glm::dvec3(a.n) - exact), 1e-6) << "triangle " << tri;
  }
}

// A parallelogram of two triangles (a rectangle light) is sampled as one: the sample's
// point is the affine image of u (so a stratified 2D set stays one over the emitter), with
// the density 1/area that pdf() gives its point. A quad whose triangles differ in area is
// not: its triangles get samples in proportion to their areas.
TEST(TriangleMesh, AParallelogramIsSampledAsOne) {
  const glm::vec3 p0(0.3f, -0.2f, 1.0f), e1(0.5f, 0.1f, 0.0f), e2(0.2f, 0.3f, 0.4f);
  const TriangleMesh quad = staticMesh({p0, p0 + e1, p0 + e1 + e2, p0 + e2}, {0, 1, 2, 0, 2, 3});
  const glm::vec3 ref(0.4f, 0.1f, -1.0f);
  const float area = glm::length(glm::cross(e1, e2));
  constexpr int kGrid = 16;
  int inFirst = 0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const glm::vec2 u((i + 0.5f) / kGrid, (j + 0.37f) / kGrid);
      const std::optional<ShapeSample> s = quad.sample(ref, 0.5f, u, 0.0);
      ASSERT_TRUE(s) << i << ", " << j;
      const glm::vec3 expected = p0 + u.x * e1 + u.y * e2;
      EXPECT_LT(glm::length(s->point.p - expected), 1e-6f) << i << ", " << j;
      EXPECT_NEAR(s->pdf / quad.pdf(ref, s->point), 1.0f, 1e-6f);
      EXPECT_EQ(s->point.prim, u.y <= u.x ? 0 : 1);
      // Solid angle to area: p_A = p_ω·|cos θ|/d².
      EXPECT_NEAR(s->pdf * std::abs(glm::dot(s->point.n, s->wi)) /
                      glm::dot(s->point.p - ref, s->point.p - ref),
                  1.0f / area, 1e-5f / area);
      inFirst += s->point.prim == 0;
    }
  EXPECT_EQ(inFirst, kGrid * (kGrid + 1) / 2);
  // Nearly a parallelogram (triangle 1 is 0.06 % larger): still sampled so, and its density is
  // each triangle's own ½ / area_k, not 1/area (which is 0.03 % off on either triangle).
  const glm::vec3 p3 = p0 + 1.0012f * e2;
  const TriangleMesh nearly = staticMesh({p0, p0 + e1, p0 + e1 + e2, p3}, {0, 1, 2, 0, 2, 3});
  const float areas[2] = {0.5f * glm::length(glm::cross(e1, e2)),
                          0.5f * glm::length(glm::cross(e1 + e2, p3 - p0))};
  for (const glm::vec2 u : {glm::vec2(0.7f, 0.2f), glm::vec2(0.2f, 0.7f)}) {
    const std::optional<ShapeSample> s = nearly.sample(ref, 0.5f, u, 0.0);
    ASSERT_TRUE(s);
    const int tri = s->point.prim;
    EXPECT_EQ(tri, u.y <= u.x ? 0 : 1);
    EXPECT_NEAR(s->pdf * std::abs(glm::dot(s->point.n, s->wi)) /
                    glm::dot(s->point.p - ref, s->point.p - ref),
                0.5f / areas[tri], 2e-6f / areas[tri]);
    EXPECT_NEAR(s->pdf / nearly.pdf(ref, s->point), 1.0f, 1e-6f);
  }
  // A trapezoid: triangle 0 holds 3/4 of the area, and so of the samples.
  const TriangleMesh trapezoid =
      staticMesh({{0, 0, 0}, {3, 0, 0}, {2, 1, 0}, {1, 1, 0}}, {0, 1, 2, 0, 2, 3});
  int first = 0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const std::optional<ShapeSample> s =
          trapezoid.sample({1.5f, 0.5f, 1.0f}, 0.5f, {(i + 0.5f) / kGrid, (j + 0.5f) / kGrid}, 0.0);
      ASSERT_TRUE(s);
      first += s->point.prim == 0;
    }
  EXPECT_EQ(first, kGrid * kGrid * 3 / 4);
}

TEST(TriangleMesh, UnitQuadHasAFrontPlaneThatRejectsOnlyPointsBehindIt) {
  const TriangleMesh quad =
      staticMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {0, 1, 2, 0, 2, 3});
  const std::optional<FrontPlane> plane = quad.frontPlane();
  ASSERT_TRUE(plane);
  EXPECT_NEAR(plane->n.z, 1.0f, 1e-7f);
  EXPECT_NEAR(plane->offset, 0.0f, 1e-7f);
  EXPECT_TRUE(plane->entirelyBehind({0.5f, 0.5f, -1.0f}));
  EXPECT_TRUE(plane->entirelyBehind({50.0f, -20.0f, -0.01f}));  // behind, beside the quad
  EXPECT_FALSE(plane->entirelyBehind({0.5f, 0.5f, 1.0f}));
  EXPECT_FALSE(plane->entirelyBehind({2.0f, 2.0f, 0.0f}));    // in the plane
  EXPECT_FALSE(plane->entirelyBehind({0.5f, 0.5f, -1e-7f}));  // within the tolerance
}

TEST(TriangleMesh, VertexNormalsOnTheFrontKeepThePlane) {
  const std::vector<glm::vec3> tilted{glm::normalize(glm::vec3(0.3f, 0.0f, 1.0f)),
                                      glm::normalize(glm::vec3(0.0f, -0.5f, 1.0f)),
                                      glm::vec3(0, 0, 1), glm::normalize(glm::vec3(1, 1, 1))};
  const std::optional<FrontPlane> plane =
      staticMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {0, 1, 2, 0, 2, 3}, tilted)
          .frontPlane();
  ASSERT_TRUE(plane);
  EXPECT_GT(plane->n.z, 0.999f);
  EXPECT_TRUE(plane->entirelyBehind({0.5f, 0.5f, -1.0f}));
}

TEST(TriangleMesh, NoFrontPlaneUnlessPlanarStaticAndOneSided) {
  // A tetrahedron: not planar.
  EXPECT_FALSE(
      staticMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3})
          .frontPlane());
  // A folded quad (one corner lifted 1 cm).
  EXPECT_FALSE(staticMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0.01f}, {0, 1, 0}}, {0, 1, 2, 0, 2, 3})
                   .frontPlane());
  // Coplanar but one triangle wound the other way: two fronts.
  EXPECT_FALSE(
      staticMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {0, 1, 2, 0, 3, 2}).frontPlane());
  // Vertex normals on the back side: pointOn flips n towards them; the plane is not claimed.
  EXPECT_FALSE(staticMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {0, 1, 2, 0, 2, 3},
                          std::vector<glm::vec3>(4, glm::vec3(0, 0, -1)))
                   .frontPlane());
  // Vertex normals almost in the plane (cos 1e-4 with the face normal): interpolated in
  // float they may flip pointOn's n; not claimed.
  const glm::vec3 grazing = glm::normalize(glm::vec3(1.0f, 0.0f, 1e-4f));
  EXPECT_FALSE(staticMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {0, 1, 2, 0, 2, 3},
                          std::vector<glm::vec3>(4, grazing))
                   .frontPlane());
  // Not sampled by any light: nothing computed.
  EXPECT_FALSE(TriangleMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {0, 1, 2}, TimeSteps{}, {},
                            /*samplable=*/false)
                   .frontPlane());
  // Degenerate triangles are never sampled and do not count.
  EXPECT_TRUE(
      staticMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 3}}, {0, 1, 2, 3, 3, 3}).frontPlane());
}

TEST(TriangleMesh, FrontPlaneNeverRejectsAPointASampleWouldLight) {
  // A tilted fan of triangles 800 m from the origin (large coordinates, float rounding):
  // wherever the plane says "behind", every sampled point's normal faces away from ref,
  // as AreaLight::L would find; and it does say so for points clearly behind.
  const glm::vec3 centre(800.0f, -300.0f, 450.0f);
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, -0.8f, 0.52f));
  const glm::vec3 s = glm::normalize(glm::cross(n, glm::vec3(0, 0, 1))), t = glm::cross(n, s);
  std::vector<glm::vec3> positions{centre};
  std::vector<std::uint32_t> indices;
  for (int k = 0; k < 12; ++k) {
    const float a = 0.5236f * static_cast<float>(k);
    positions.push_back(centre + 2.0f * (std::cos(a) * s + std::sin(a) * t));
    indices.insert(indices.end(), {0, static_cast<std::uint32_t>(1 + k),
                                   static_cast<std::uint32_t>(1 + (k + 1) % 12)});
  }
  const TriangleMesh fan = staticMesh(positions, indices);
  const std::optional<FrontPlane> plane = fan.frontPlane();
  ASSERT_TRUE(plane);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f), side(-20.0f, 20.0f);
  int behind = 0;
  for (int i = 0; i < 4000; ++i) {
    // Reference points up to 20 m along the plane and within ±(10 µm…10 m) of it.
    const float depth = std::pow(10.0f, -5.0f + 6.0f * u01(rng)) * (u01(rng) < 0.5f ? -1 : 1);
    const glm::vec3 ref = centre + side(rng) * s + side(rng) * t + depth * n;
    if (!plane->entirelyBehind(ref)) {
      EXPECT_GT(depth, -0.1f) << "a point 0.1 m or more behind was not rejected";
      continue;
    }
    ++behind;
    EXPECT_LT(depth, 0.0f);
    // Exactly (double): ref is behind every triangle's plane at all three corners, so
    // behind every point of the fan.
    for (size_t k = 0; k < indices.size(); k += 3) {
      const glm::dvec3 p0(positions[indices[k]]), p1(positions[indices[k + 1]]),
          p2(positions[indices[k + 2]]);
      const glm::dvec3 nk = glm::normalize(glm::cross(p1 - p0, p2 - p0));
      for (const glm::dvec3& v : {p0, p1, p2}) ASSERT_LT(glm::dot(nk, glm::dvec3(ref) - v), 0.0);
    }
    for (int j = 0; j < 20; ++j) {
      const std::optional<ShapeSample> smp = fan.sample(ref, u01(rng), {u01(rng), u01(rng)}, 0);
      if (smp) {
        EXPECT_LE(glm::dot(smp->point.n, ref - smp->point.p), 0.0f);
      }
    }
  }
  EXPECT_GT(behind, 800);
}

}  // namespace
}  // namespace camsim
