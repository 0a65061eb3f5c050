// Texture coordinates of the shapes (integrator/triangle_mesh, sphere, the loader's
// rectangle): interpolation of per-vertex uvs, the default per-triangle parametrisation,
// the sphere's (φ/2π, θ/π) at its poles and on its equator.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "integrator/geometry/sphere.h"
#include "integrator/geometry/triangle_mesh.h"
#include "integrator/scene/scene_loader.h"

namespace camsim {
namespace {

constexpr float kTol = 1e-6f;

TriangleMesh quad(std::vector<glm::vec2> uvs) {
  std::vector<glm::vec3> positions = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  return TriangleMesh(std::move(positions), {}, {0, 1, 2, 0, 2, 3}, TimeSteps{}, std::move(uvs));
}

SurfaceInteraction hitTriangle(const TriangleMesh& mesh, int prim, float b1, float b2) {
  Hit hit;
  hit.shape = 0;
  hit.prim = prim;
  hit.u = b1;
  hit.v = b2;
  hit.t = 1.0f;
  return mesh.interaction(hit, Ray{});
}

TEST(TriangleMeshUv, InterpolatesVertexUvsBarycentrically) {
  const TriangleMesh mesh = quad({{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}});
  // Triangle 0 = (v0, v1, v2): p = b0 p0 + b1 p1 + b2 p2.
  SurfaceInteraction si = hitTriangle(mesh, 0, 0.5f, 0.25f);
  EXPECT_NEAR(si.uv.x, 0.75f, kTol);
  EXPECT_NEAR(si.uv.y, 0.25f, kTol);
  EXPECT_NEAR(si.p.x, 1.5f, kTol);  // u follows x / 2 on this quad
  // Triangle 1 = (v0, v2, v3).
  si = hitTriangle(mesh, 1, 0.2f, 0.7f);
  EXPECT_NEAR(si.uv.x, 0.2f, kTol);
  EXPECT_NEAR(si.uv.y, 0.9f, kTol);
  EXPECT_NEAR(si.uv.x, si.p.x / 2.0f, kTol);
  EXPECT_NEAR(si.uv.y, si.p.y, kTol);
}

TEST(TriangleMeshUv, WithoutUvsEachTriangleGetsTheDefaultParametrisation) {
  const TriangleMesh mesh = quad({});
  for (int prim : {0, 1}) {
    EXPECT_NEAR(hitTriangle(mesh, prim, 0.0f, 0.0f).uv.x, 0.0f, kTol);  // corner 0 → (0, 0)
    const SurfaceInteraction c1 = hitTriangle(mesh, prim, 1.0f, 0.0f);  // corner 1 → (1, 0)
    EXPECT_NEAR(c1.uv.x, 1.0f, kTol);
    EXPECT_NEAR(c1.uv.y, 0.0f, kTol);
    const SurfaceInteraction c2 = hitTriangle(mesh, prim, 0.0f, 1.0f);  // corner 2 → (1, 1)
    EXPECT_NEAR(c2.uv.x, 1.0f, kTol);
    EXPECT_NEAR(c2.uv.y, 1.0f, kTol);
    const SurfaceInteraction mid = hitTriangle(mesh, prim, 0.3f, 0.2f);
    EXPECT_NEAR(mid.uv.x, 0.5f, kTol);
    EXPECT_NEAR(mid.uv.y, 0.2f, kTol);
  }
}

TEST(TriangleMeshUv, SampledPointsCarryUvs) {
  const TriangleMesh mesh = quad({{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}});
  for (float u1 : {0.1f, 0.7f}) {
    const auto s = mesh.sample({1.0f, 0.5f, 3.0f}, u1, {0.3f, 0.6f}, 0.0f);
    ASSERT_TRUE(s.has_value());
    EXPECT_NEAR(s->point.uv.x, s->point.p.x / 2.0f, 1e-5f);
    EXPECT_NEAR(s->point.uv.y, s->point.p.y, 1e-5f);
  }
}

// A sphere of radius 2 at (1, 2, 3), hit from outside along each axis.
glm::vec2 sphereUv(const glm::vec3& direction) {
  const glm::vec3 centre(1.0f, 2.0f, 3.0f);
  const Sphere sphere({centre}, {2.0f}, TimeSteps{});
  Ray ray;
  ray.o = centre + 10.0f * direction;
  ray.d = -direction;
  Hit hit;
  hit.shape = 0;
  hit.t = 8.0f;
  return sphere.interaction(hit, ray).uv;
}

TEST(SphereUv, PolesAndEquator) {
  const glm::vec2 north = sphereUv({0, 1, 0}), south = sphereUv({0, -1, 0});
  EXPECT_NEAR(north.y, 1.0f, kTol);  // v = 1 − θ/π, θ from +y (world up)
  EXPECT_NEAR(south.y, 0.0f, kTol);
  EXPECT_GE(north.x, 0.0f);
  EXPECT_LT(north.x, 1.0f);
  const struct {
    glm::vec3 direction;
    float u;
  } equator[] = {{{0, 0, 1}, 0.0f}, {{1, 0, 0}, 0.25f}, {{0, 0, -1}, 0.5f}, {{-1, 0, 0}, 0.75f}};
  for (const auto& e : equator) {
    const glm::vec2 uv = sphereUv(e.direction);
    EXPECT_NEAR(uv.x, e.u, kTol) << e.direction.x << " " << e.direction.y;
    EXPECT_NEAR(uv.y, 0.5f, kTol);
  }
  // 45° above the equator between +z and +x: u = 1/8, v = 3/4.
  const glm::vec2 mid = sphereUv(glm::normalize(glm::vec3(0.5f, std::sqrt(0.5f), 0.5f)));
  EXPECT_NEAR(mid.x, 0.125f, 1e-5f);
  EXPECT_NEAR(mid.y, 0.75f, 1e-5f);
  // Just below φ = 2π (u slightly under 1, never 1).
  const glm::vec2 wrap = sphereUv(glm::normalize(glm::vec3(-1e-7f, 0.0f, 1.0f)));
  EXPECT_GE(wrap.x, 0.0f);
  EXPECT_LT(wrap.x, 1.0f);
}

TEST(RectangleUv, LoaderGivesCornerAndEdgeUvs) {
  const SceneDescription d = loadSceneFromText(
      "camera: {position: [0, 0, -1], look_at: [0, 0, 0]}\n"
      "materials: {m: {type: diffuse}}\n"
      "shapes:\n"
      "  - {type: rectangle, corner: [0, 0, 0], edge_u: [1, 0, 0], edge_v: [0, 1, 0], material: "
      "m}\n",
      "test.yaml", ".");
  ASSERT_EQ(d.shapes.size(), 1u);
  const MeshData& m = d.shapes[0].mesh;
  ASSERT_EQ(m.uvs.size(), 4u);
  EXPECT_EQ(m.uvs[0], glm::vec2(0, 0));  // corner
  EXPECT_EQ(m.uvs[1], glm::vec2(1, 0));  // corner + edge_u
  EXPECT_EQ(m.uvs[2], glm::vec2(1, 1));  // corner + edge_u + edge_v
  EXPECT_EQ(m.uvs[3], glm::vec2(0, 1));  // corner + edge_v
}

}  // namespace
}  // namespace camsim
