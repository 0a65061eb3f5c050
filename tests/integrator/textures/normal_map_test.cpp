// Tangent-space normal maps (integrator/textures/normal_map.h) and the tangent frames the
// shapes give them (Shape::tangentFrame), against closed forms:
//  - texel decoding n_t = normalize((2c − 1)·(s, s, 1)), bilinear between texels;
//  - a flat texel returns the shading normal bit for bit;
//  - on a quad z = 0 (∂p/∂u = 2x̂, ∂p/∂v = ŷ) a texel tilted by θ towards +x (+y) tilts the
//    shading normal by θ towards ∂p/∂u (∂p/∂v): N' = (sin θ, 0, cos θ) (resp. (0, sin θ, cos θ));
//    mirrored uvs mirror it; per-vertex tangents (w = ±1) choose the bitangent's side;
//  - a moving mesh turns its frame with it; a sphere's frame follows u (φ) and v (to +y);
//  - the guard: a map bending the normal to 89.9° from the geometric normal is held at
//    cos = kMinCosGeometric; degenerate uvs give no frame.
#include "integrator/textures/normal_map.h"

#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "integrator/geometry/sphere.h"
#include "integrator/geometry/triangle_mesh.h"
#include "integrator/textures/image_texture.h"

namespace camsim {
namespace {

// A 1×1 normal map whose texel encodes the unit normal n (c = (n + 1)/2).
NormalMap constantMap(const glm::vec3& n, float strength = 1.0f) {
  const glm::vec3 c = 0.5f * (n + 1.0f);
  return NormalMap(TextureImage{1, 1, 3, {c.x, c.y, c.z}, {}}, glm::vec2(1.0f), glm::vec2(0.0f),
                   strength);
}

void expectVec(const glm::vec3& got, const glm::vec3& want, float tol, const char* what) {
  EXPECT_NEAR(got.x, want.x, tol) << what;
  EXPECT_NEAR(got.y, want.y, tol) << what;
  EXPECT_NEAR(got.z, want.z, tol) << what;
}

// The quad [0, 2] × [0, 1] at z = 0 facing +z, uv (0, 0) … (1, 1) at its corners (or u
// mirrored), optionally with per-vertex tangents.
TriangleMesh quad(bool mirrorU = false, std::vector<glm::vec4> tangents = {}, TimeSteps steps = {},
                  InstanceMotion motion = {}) {
  std::vector<glm::vec2> uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  if (mirrorU)
    for (glm::vec2& uv : uvs) uv.x = 1.0f - uv.x;
  return TriangleMesh({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}}, {}, {0, 1, 2, 0, 2, 3}, steps,
                      std::move(uvs), false, std::move(motion), std::move(tangents));
}

// The shading normal at the quad's point (b1, b2) of triangle 0 bent by `map`.
glm::vec3 bent(const TriangleMesh& mesh, const NormalMap& map, double time = 0.0f) {
  const Hit hit{0, 0, 0.3f, 0.2f, 1.0f};
  Ray ray;
  ray.time = time;
  const SurfaceInteraction si = mesh.interaction(hit, ray);
  const std::optional<SurfaceTangents> t = mesh.tangentFrame(hit, si);
  EXPECT_TRUE(t.has_value());
  if (!t) return si.ns;
  return perturbShadingNormal(si.ns, si.n, t->tangent, t->bitangent, map.tangentSpaceNormal(si.uv));
}

TEST(NormalMap, DecodesTexelsWithStrength) {
  const TextureImage image{1, 1, 3, {0.75f, 0.5f, 1.0f}, {}};
  const NormalMap one(image, glm::vec2(1.0f), glm::vec2(0.0f), 1.0f);
  expectVec(one.tangentSpaceNormal({0.3f, 0.6f}), glm::normalize(glm::vec3(0.5f, 0.0f, 1.0f)),
            1e-6f, "strength 1");
  const NormalMap two(image, glm::vec2(1.0f), glm::vec2(0.0f), 2.0f);
  expectVec(two.tangentSpaceNormal({0.3f, 0.6f}), glm::normalize(glm::vec3(1.0f, 0.0f, 1.0f)),
            1e-6f, "strength 2");
  // Bilinear: halfway between a flat texel and (1, 0.5, 0.5) (n = (1, 0, 0)) the colour is
  // (0.75, 0.5, 0.75), n_t ∝ (0.5, 0, 0.5).
  const NormalMap pair(TextureImage{2, 1, 3, {0.5f, 0.5f, 1.0f, 1.0f, 0.5f, 0.5f}, {}},
                       glm::vec2(1.0f), glm::vec2(0.0f), 1.0f);
  expectVec(pair.tangentSpaceNormal({0.5f, 0.5f}), glm::normalize(glm::vec3(1.0f, 0.0f, 1.0f)),
            1e-6f, "bilinear");
  // c = 0.5 everywhere: no direction at all; read as unbent.
  const NormalMap grey(TextureImage{1, 1, 3, {0.5f, 0.5f, 0.5f}, {}}, glm::vec2(1.0f),
                       glm::vec2(0.0f), 1.0f);
  EXPECT_EQ(grey.tangentSpaceNormal({0.1f, 0.1f}), glm::vec3(0.0f, 0.0f, 1.0f));
}

TEST(NormalMap, FlatTexelKeepsTheShadingNormalBitForBit) {
  const NormalMap flat(TextureImage{1, 1, 3, {0.5f, 0.5f, 1.0f}, {}}, glm::vec2(1.0f),
                       glm::vec2(0.0f), 1.0f);
  // At any uv: bilinear weights that sum to 1 only to rounding must not tilt it.
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const glm::vec2 uv(0.0137f * static_cast<float>(i) - 0.3f, 0.0291f * static_cast<float>(j));
      ASSERT_EQ(flat.tangentSpaceNormal(uv), glm::vec3(0.0f, 0.0f, 1.0f)) << uv.x << " " << uv.y;
    }
  const glm::vec3 ns = glm::normalize(glm::vec3(0.3f, -0.2f, 0.9f));
  const glm::vec3 got = perturbShadingNormal(ns, ns, {1.0f, 0.0f, -0.3f}, {0.0f, 1.0f, 0.2f},
                                             flat.tangentSpaceNormal({0.7f, 0.2f}));
  EXPECT_EQ(got, ns);  // bit for bit, not just close
}

TEST(NormalMap, TiltedMapTiltsTheQuadsNormalByTheAngle) {
  for (float degrees : {10.0f, 30.0f, 60.0f}) {
    const float th = degrees * static_cast<float>(M_PI) / 180.0f, s = std::sin(th),
                c = std::cos(th);
    const glm::vec3 towardsU = bent(quad(), constantMap({s, 0.0f, c}));
    expectVec(towardsU, {s, 0.0f, c}, 2e-6f, "along ∂p/∂u");
    EXPECT_NEAR(std::acos(towardsU.z), th, 1e-5f);
    expectVec(bent(quad(), constantMap({0.0f, s, c})), {0.0f, s, c}, 2e-6f, "along ∂p/∂v");
    // u mirrored: ∂p/∂u = −2x̂; the bitangent still follows v (+y).
    expectVec(bent(quad(true), constantMap({s, 0.0f, c})), {-s, 0.0f, c}, 2e-6f, "mirrored u");
    expectVec(bent(quad(true), constantMap({0.0f, s, c})), {0.0f, s, c}, 2e-6f, "mirrored u, v");
  }
}

TEST(NormalMap, VertexTangentsChooseTheFrame) {
  const float s = 0.5f, c = std::sqrt(0.75f);  // 30°
  // Tangent along +y (not ∂p/∂u): w = +1 → bitangent ns × t = ẑ × ŷ = −x̂.
  const std::vector<glm::vec4> along(4, glm::vec4(0.0f, 1.0f, 0.0f, 1.0f));
  expectVec(bent(quad(false, along), constantMap({s, 0.0f, c})), {0.0f, s, c}, 2e-6f, "t = +y");
  expectVec(bent(quad(false, along), constantMap({0.0f, s, c})), {-s, 0.0f, c}, 2e-6f, "w = +1");
  const std::vector<glm::vec4> flipped(4, glm::vec4(0.0f, 1.0f, 0.0f, -1.0f));
  expectVec(bent(quad(false, flipped), constantMap({0.0f, s, c})), {s, 0.0f, c}, 2e-6f, "w = −1");
}

TEST(NormalMap, MovingMeshTurnsItsFrame) {
  // Rotated 90° about +z at both steps: ∂p/∂u = 2x̂ turns to 2ŷ.
  const glm::mat4 turn(glm::vec4(0, 1, 0, 0), glm::vec4(-1, 0, 0, 0), glm::vec4(0, 0, 1, 0),
                       glm::vec4(0, 0, 0, 1));
  InstanceMotion motion;
  motion.steps = {turn, turn};
  const TriangleMesh mesh = quad(false, {}, TimeSteps{0.0, 1.0, 2}, motion);
  const float s = 0.5f, c = std::sqrt(0.75f);
  expectVec(bent(mesh, constantMap({s, 0.0f, c}), 0.5f), {0.0f, s, c}, 2e-6f, "turned");
}

TEST(NormalMap, SphereFrameFollowsUAndV) {
  const Sphere sphere({{0.0f, 0.0f, 0.0f}}, {1.0f}, TimeSteps{});
  SurfaceInteraction si;
  si.n = si.ns = {0.0f, 0.0f, 1.0f};  // u = 0 on the equator: φ grows towards +x, v towards +y
  const std::optional<SurfaceTangents> t = sphere.tangentFrame(Hit{}, si);
  ASSERT_TRUE(t.has_value());
  expectVec(glm::normalize(t->tangent), {1.0f, 0.0f, 0.0f}, 1e-7f, "∂p/∂u");
  expectVec(glm::normalize(t->bitangent), {0.0f, 1.0f, 0.0f}, 1e-7f, "∂p/∂v");
  // At the pole the frame vanishes and a map leaves the normal alone.
  si.n = si.ns = {0.0f, 1.0f, 0.0f};
  const std::optional<SurfaceTangents> pole = sphere.tangentFrame(Hit{}, si);
  ASSERT_TRUE(pole.has_value());
  EXPECT_EQ(perturbShadingNormal(si.ns, si.n, pole->tangent, pole->bitangent,
                                 glm::normalize(glm::vec3(0.5f, 0.0f, 1.0f))),
            si.ns);
}

TEST(NormalMap, GuardKeepsTheNormalAboveTheSurface) {
  const float th = 89.9f * static_cast<float>(M_PI) / 180.0f;
  const glm::vec3 got = bent(quad(), constantMap({std::sin(th), 0.0f, std::cos(th)}));
  EXPECT_NEAR(glm::length(got), 1.0f, 1e-6f);
  EXPECT_NEAR(got.z, kMinCosGeometric, 1e-6f);  // held at the smallest cosine
  EXPECT_EQ(got.y, 0.0f);                       // the direction of the bend is kept
  EXPECT_GT(got.x, 0.0f);
  // Pointing straight into the surface: nothing to keep, the shading normal stays.
  const glm::vec3 ns(0.0f, 0.0f, 1.0f);
  EXPECT_EQ(perturbShadingNormal(ns, ns, {1, 0, 0}, {0, 1, 0}, {0.0f, 0.0f, -1.0f}), ns);
  // Degenerate uvs: no frame.
  const TriangleMesh line({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {0, 1, 2}, TimeSteps{},
                          {{0, 0}, {1, 1}, {2, 2}}, false);
  const Hit hit{0, 0, 0.3f, 0.3f, 1.0f};
  EXPECT_FALSE(line.tangentFrame(hit, line.interaction(hit, Ray{})).has_value());
}

}  // namespace
}  // namespace camsim
