// glTF animation (integrator/scene/gltf_motion.cpp): which animations play (all by
// default, or the include's `animation:` choice) and a moving node inside a moving node,
// its pose composed along the node chain. Expected poses are computed here from the keys
// as glTF defines them (LINEAR: lerp of translations, slerp of rotations), independently of
// camsim's keyframes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "tests/integrator/scene/gltf_test_support.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

const glm::dvec3 kRenderOrigin(0.0, 0.0, 5.0);  // the render origin

SceneDescription loadAnimated(const std::filesystem::path& dir, const std::string& entry = "") {
  return loadSceneFromText(
      "camera: {position: [0, 0, 5], look_at: [0, 0, 0]}\n"
      "include:\n  - gltf: anim.gltf\n" +
          entry,
      "test.yaml", dir);
}

std::string sampler(int input, int output) {
  return R"({"input":)" + std::to_string(input) + R"(,"output":)" + std::to_string(output) + "}";
}
std::string channel(int sampler, int node, const char* path) {
  return R"({"sampler":)" + std::to_string(sampler) + R"(,"target":{"node":)" +
         std::to_string(node) + R"(,"path":")" + path + R"("}})";
}

// The glTF LINEAR value at t of keys (times, values) (ends held).
template <typename T, typename Mix>
T linear(const std::vector<double>& times, const std::vector<T>& values, double t, Mix mix) {
  if (t <= times.front()) return values.front();
  if (t >= times.back()) return values.back();
  size_t k = 0;
  while (times[k + 1] < t) ++k;
  return mix(values[k], values[k + 1], (t - times[k]) / (times[k + 1] - times[k]));
}

// A translating parent (keys at 0, 0.6, 1 s) with a rotating child (about z, keys at 0,
// 0.3, 1 s) offset by (1, 0.5, 0) from it, the triangle on the child: every vertex's
// world position is  T_parent(t) + offset + R_child(t) · p.
TEST(GltfAnimation, RotatingChildOfATranslatingParentFollowsBothChains) {
  const std::vector<double> tp = {0.0, 0.6, 1.0}, tc = {0.0, 0.3, 1.0};
  const std::vector<glm::dvec3> parent = {{0, 0, 0}, {2, 1, 0}, {2, 1, -3}};
  const std::vector<glm::dquat> child = {glm::angleAxis(0.0, glm::dvec3(0, 0, 1)),
                                         glm::angleAxis(1.2, glm::dvec3(0, 0, 1)),
                                         glm::angleAxis(2.9, glm::dvec3(0, 0, 1))};
  test::GltfBuilder b;
  const std::vector<float> tri = {0, 0, 0, 0.5f, 0, 0, 0, 0.5f, 0};
  b.floats(tri, "VEC3");
  const int ti = b.floats({0.0f, 0.6f, 1.0f}, "SCALAR");
  const int tv = b.floats({0, 0, 0, 2, 1, 0, 2, 1, -3}, "VEC3");
  const int ri = b.floats({0.0f, 0.3f, 1.0f}, "SCALAR");
  std::vector<float> rv;
  for (const glm::dquat& q : child)
    for (double c : {q.x, q.y, q.z, q.w}) rv.push_back(static_cast<float>(c));
  const int ro = b.floats(rv, "VEC4");
  test::TempDir dir;
  test::writeText(dir.path() / "anim.gltf",
                  b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                         R"("nodes":[{"children":[1]},{"mesh":0,"translation":[1,0.5,0]}],)"
                         R"("scenes":[{"nodes":[0]}],"animations":[{"samplers":[)" +
                         sampler(ti, tv) + "," + sampler(ri, ro) + R"(],"channels":[)" +
                         channel(0, 0, "translation") + "," + channel(1, 1, "rotation") + "]}]"));
  const SceneDescription s = loadAnimated(dir.path());
  ASSERT_EQ(s.shapes.size(), 1u);
  const RigidMotion& m = s.shapes[0].motion;
  ASSERT_FALSE(m.empty());
  const auto lerp = [](const glm::dvec3& a, const glm::dvec3& c, double f) {
    return a + f * (c - a);
  };
  const auto slerp = [](const glm::dquat& a, const glm::dquat& c, double f) {
    return glm::slerp(a, c, f);
  };
  double worst = 0.0;
  for (double t : {0.1, 0.3, 0.45, 0.8, 0.97}) {
    const glm::dvec3 T = linear(tp, parent, t, lerp);
    const glm::dquat R = linear(tc, child, t, slerp);
    for (size_t v = 0; v < 3; ++v) {
      const glm::dvec3 p(tri[3 * v], tri[3 * v + 1], tri[3 * v + 2]);
      const glm::dvec3 world = T + glm::dvec3(1.0, 0.5, 0.0) + R * p;
      const glm::dvec3 placed =
          glm::dvec3(m.at(t) * glm::dvec4(glm::dvec3(s.shapes[0].mesh.positions[v]), 1.0));
      worst = std::max(worst, glm::length(placed - (world - kRenderOrigin)));
      EXPECT_LT(glm::length(placed - (world - kRenderOrigin)), 1e-6)
          << "t " << t << " vertex " << v;
    }
  }
  std::printf("[measured] rotating child of a translating parent: %zu keys, worst error %.2e m\n",
              m.keys().size(), worst);
}

// A rotating parent (a quarter turn about z over 1 s, keys at 0 and 1 s) carrying a child
// 1 m out that translates along z: the child's origin swings on an arc, which keys at the
// union of the key times (0, 1 s) alone would cut short. Checked midway between samples.
TEST(GltfAnimation, ChildOfARotatingParentSwingsOnTheArc) {
  test::GltfBuilder b;
  b.floats({0, 0, 0, 0.1f, 0, 0, 0, 0.1f, 0}, "VEC3");
  const int times = b.floats({0.0f, 1.0f}, "SCALAR");
  const glm::dquat q1 = glm::angleAxis(0.5 * std::numbers::pi, glm::dvec3(0, 0, 1));
  const int rot =
      b.floats({0, 0, 0, 1, 0, 0, static_cast<float>(q1.z), static_cast<float>(q1.w)}, "VEC4");
  const int z = b.floats({1, 0, 0, 1, 0, 2}, "VEC3");
  test::TempDir dir;
  test::writeText(dir.path() / "anim.gltf",
                  b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                         R"("nodes":[{"children":[1]},{"mesh":0}],"scenes":[{"nodes":[0]}],)"
                         R"("animations":[{"samplers":[)" +
                         sampler(times, rot) + "," + sampler(times, z) + R"(],"channels":[)" +
                         channel(0, 0, "rotation") + "," + channel(1, 1, "translation") + "]}]"));
  const SceneDescription s = loadAnimated(dir.path());
  const RigidMotion& m = s.shapes[0].motion;
  EXPECT_GT(m.keys().size(), 2u);  // samples were added between the keys
  double worst = 0.0;
  for (double t : {0.13, 0.37, 0.5, 0.71, 0.9}) {
    const double angle = 0.5 * std::numbers::pi * t;
    const glm::dvec3 origin(std::cos(angle), std::sin(angle), 2.0 * t);  // the child's
    const glm::dvec3 placed = glm::dvec3(m.at(t)[3]);
    worst = std::max(worst, glm::length(placed - (origin - kRenderOrigin)));
    EXPECT_LT(glm::length(placed - (origin - kRenderOrigin)), 1e-5) << t;
  }
  std::printf("[measured] child of a rotating parent: %zu keys, worst error %.2e m\n",
              m.keys().size(), worst);
}

// Two animations, each moving its own node: both play by default; `animation:` picks one
// by name or index, a list, or none.
TEST(GltfAnimation, AllAnimationsPlayByDefaultAndTheSceneCanChoose) {
  test::GltfBuilder b;
  b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const int times = b.floats({0.0f, 1.0f}, "SCALAR");
  const int move = b.floats({0, 0, 0, 0, 3, 0}, "VEC3");
  test::TempDir dir;
  test::writeText(
      dir.path() / "anim.gltf",
      b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
             R"("nodes":[{"mesh":0,"name":"a"},{"mesh":0,"name":"b"}],"scenes":[{"nodes":[0,1]}],)"
             R"("animations":[{"name":"first","samplers":[)" +
             sampler(times, move) + R"(],"channels":[)" + channel(0, 0, "translation") +
             R"(]},{"name":"second","samplers":[)" + sampler(times, move) + R"(],"channels":[)" +
             channel(0, 1, "translation") + "]}]"));
  auto moving = [&](const std::string& entry) {
    const SceneDescription s = loadAnimated(dir.path(), entry);
    std::string out;
    for (const ShapeDescription& shape : s.shapes)
      out += shape.motion.empty() ? "-"
                                  : (std::abs(shape.motion.at(1.0)[3].y - 3.0) < 1e-12 ? "M" : "?");
    return out;
  };
  EXPECT_EQ(moving(""), "MM");
  EXPECT_EQ(moving("    animation: all\n"), "MM");
  EXPECT_EQ(moving("    animation: second\n"), "-M");
  EXPECT_EQ(moving("    animation: 0\n"), "M-");
  EXPECT_EQ(moving("    animation: [second, 0]\n"), "MM");
  EXPECT_EQ(moving("    animation: none\n"), "--");
  try {
    loadAnimated(dir.path(), "    animation: third\n");
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no animation 'third'"), std::string::npos) << e.what();
  }
}

// Two animations moving the same node's translation: the first in the file plays, noted.
TEST(GltfAnimation, TheFirstOfTwoAnimationsOfOneNodeWins) {
  test::GltfBuilder b;
  b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const int times = b.floats({0.0f, 1.0f}, "SCALAR");
  const int up = b.floats({0, 0, 0, 0, 3, 0}, "VEC3");
  const int down = b.floats({0, 0, 0, 0, -3, 0}, "VEC3");
  test::TempDir dir;
  test::writeText(dir.path() / "anim.gltf",
                  b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                         R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"animations":[)"
                         R"({"samplers":[)" +
                         sampler(times, up) + R"(],"channels":[)" + channel(0, 0, "translation") +
                         R"(]},{"samplers":[)" + sampler(times, down) + R"(],"channels":[)" +
                         channel(0, 0, "translation") + "]}]"));
  const SceneDescription s = loadAnimated(dir.path());
  EXPECT_NEAR(s.shapes[0].motion.at(1.0)[3].y, 3.0, 1e-12);
  bool noted = false;
  for (const std::string& n : s.notes)
    noted = noted || n.find("animations[1].channels[0]: not played") != std::string::npos;
  EXPECT_TRUE(noted);
}

}  // namespace
}  // namespace camsim
