// Tests for integrator/textures/alpha_cutout.h through EmbreeScene's filter functions
// (integrator/geometry/hit_filter.h): rays crossing a checker-cut quad are hit (closest
// hit) and occluded (shadow rays) exactly where the checker is opaque, see the quad behind
// through the holes, and an instanced mesh's instances each follow their own filter.
#include "integrator/textures/alpha_cutout.h"

#include <gtest/gtest.h>

#include <random>

#include "integrator/geometry/embree_scene.h"
#include "integrator/geometry/mesh_instance.h"
#include "integrator/textures/checkerboard_texture.h"

namespace camsim {
namespace {

constexpr float kChecks = 4.0f;  // squares per unit of uv: 4 × 4 over the quad

// A unit quad in the plane z = 0, [0, 1]² with uv = (x, y).
std::shared_ptr<TriangleMesh> unitQuad(float z = 0.0f) {
  std::vector<glm::vec3> p = {{0, 0, z}, {1, 0, z}, {1, 1, z}, {0, 1, z}};
  std::vector<std::uint32_t> idx = {0, 1, 2, 0, 2, 3};
  return std::make_shared<TriangleMesh>(std::move(p), std::vector<glm::vec3>{}, std::move(idx),
                                        TimeSteps{},
                                        std::vector<glm::vec2>{{0, 0}, {1, 0}, {1, 1}, {0, 1}});
}

// The checker's squares "a" are opaque (alpha 1), "b" cut (alpha 0).
AlphaCutout checkerCut(const TriangleMesh& mesh) {
  return AlphaCutout(mesh, std::make_unique<CheckerboardFloatTexture>(1.0f, 0.0f, kChecks), 1.0f,
                     0.5f);
}

// Whether the crossing at (x, y) of the quad lies in an opaque square, and whether it is
// at least 1e-4 from any square's edge (else rounding may decide either way).
bool opaqueAt(float x, float y, bool& clear) {
  const float fx = x * kChecks, fy = y * kChecks;
  clear = std::abs(fx - std::round(fx)) > 4e-4f && std::abs(fy - std::round(fy)) > 4e-4f;
  return checkerboardIsA({x, y}, kChecks, glm::vec2(1.0f), glm::vec2(0.0f));
}

// Rays from z = −1 through random points of the quad: with a wall behind at z = 1, the
// closest hit is the quad exactly where it is opaque, else the wall; shadow rays that stop
// short of the wall are occluded exactly where it is opaque. Half the squares are cut, so
// about half the rays pass. `shapes`: the quad is shape `quad`, the wall the last one.
void expectCheckerVisibility(const EmbreeScene& scene, int quad, int wall, glm::vec2 offset) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  int passed = 0, checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const float x = u01(rng), y = u01(rng);
    bool clear = false;
    const bool opaque = opaqueAt(x, y, clear);
    if (!clear) continue;
    ++checked;
    const glm::vec3 target(x + offset.x, y + offset.y, 0.0f);
    const glm::vec3 from = target + glm::vec3(0.3f * (u01(rng) - 0.5f), 0.2f, -1.0f);
    const Ray ray{from, target - from, 10.0f, 0.0f};
    Hit hit;
    ASSERT_TRUE(scene.intersect(ray, hit)) << i;
    ASSERT_EQ(hit.shape, opaque ? quad : wall) << i << " at " << x << ", " << y;
    const Ray shadow{from, target - from, 1.5f, 0.0f};  // ends between the quad and the wall
    ASSERT_EQ(scene.occluded(shadow), opaque) << i;
    passed += opaque ? 0 : 1;
  }
  EXPECT_GT(checked, 19000);
  EXPECT_NEAR(static_cast<double>(passed) / checked, 0.5, 0.02);
}

TEST(AlphaCutout, RaysPassExactlyThroughTheCutSquares) {
  std::vector<std::unique_ptr<Shape>> shapes;
  const std::shared_ptr<TriangleMesh> quad = unitQuad();
  shapes.push_back(std::make_unique<TriangleMesh>(quad->positions(), quad->normals(),
                                                  quad->indices(), TimeSteps{}, quad->uvs()));
  // The filter reads the texture coordinates of the mesh Embree reports.
  const AlphaCutout cut = checkerCut(dynamic_cast<const TriangleMesh&>(*shapes[0]));
  shapes.push_back(std::make_unique<TriangleMesh>(
      std::vector<glm::vec3>{{-9, -9, 1}, {9, -9, 1}, {9, 9, 1}, {-9, 9, 1}},
      std::vector<glm::vec3>{}, std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}, TimeSteps{}));
  const EmbreeScene scene(shapes, 0.0, 1.0, {&cut, nullptr});
  expectCheckerVisibility(scene, 0, 1, glm::vec2(0.0f));
}

// Three instances of one quad mesh side by side (x offsets 0, 2, 4): the first two cut by
// the checker (one filter on the shared mesh, asked per instance), the third opaque (no
// filter): every ray through it hits it.
TEST(AlphaCutout, EachInstanceOfASharedMeshFollowsItsOwnFilter) {
  const std::shared_ptr<const TriangleMesh> quad = unitQuad();
  const AlphaCutout cut = checkerCut(*quad);
  std::vector<std::unique_ptr<Shape>> shapes;
  for (int i = 0; i < 3; ++i) {
    glm::dmat4 placement(1.0);
    placement[3] = glm::dvec4(2.0 * i, 0.0, 0.0, 1.0);
    shapes.push_back(
        std::make_unique<MeshInstance>(quad, std::vector<glm::dmat4>{placement}, TimeSteps{}));
  }
  shapes.push_back(std::make_unique<TriangleMesh>(
      std::vector<glm::vec3>{{-9, -9, 1}, {19, -9, 1}, {19, 9, 1}, {-9, 9, 1}},
      std::vector<glm::vec3>{}, std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}, TimeSteps{}));
  const EmbreeScene scene(shapes, 0.0, 1.0, {&cut, &cut, nullptr, nullptr});
  expectCheckerVisibility(scene, 0, 3, glm::vec2(0.0f));
  expectCheckerVisibility(scene, 1, 3, glm::vec2(2.0f, 0.0f));
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 target(4.0f + u01(rng), u01(rng), 0.0f);
    const Ray ray{target - glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), 10.0f, 0.0f};
    Hit hit;
    ASSERT_TRUE(scene.intersect(ray, hit));
    ASSERT_EQ(hit.shape, 2) << i;
  }
}

}  // namespace
}  // namespace camsim
