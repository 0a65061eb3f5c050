// The glTF file's structure beyond its byte layout, each found by probing a frozen build
// (gltf_validate.cpp, gltf_document.cpp, gltf_accessors.cpp, gltf_read_materials.cpp,
// scene_loader_gltf.cpp, gltf_materials.cpp): values of the wrong type named by their JSON
// path instead of read as defaults, a node matrix that is no affine map, scenes whose nodes
// repeat, hierarchies deeper than the loader's recursion, view-less accessors of billions of
// elements; and what the loader makes of what it accepts: a triangle list's leftover
// vertices are noted, a shared mesh under a mirroring node keeps its front, a light under a
// huge scale keeps its direction, a yfov too narrow for focal_length_mm's range is refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "integrator/scene/gltf_document.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "tests/integrator/scene/gltf_test_support.h"

namespace camsim {
namespace gltf_structure_test {

namespace fs = std::filesystem;

fs::path scratchFile(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("camsim_gltf_structure_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path f = dir / (name + ".gltf");
  test::writeText(f, text);
  return f;
}

// A triangle (accessor 0) and then `rest`: the meshes, nodes, scenes … of the case.
std::string triangleWith(const std::string& rest) {
  test::GltfBuilder b;
  b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  return b.json(rest);
}

const std::string kMesh = R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)";

// The key and message of readGltf's refusal ("accepted" if none).
std::pair<std::string, std::string> refusal(const std::string& name, const std::string& text) {
  try {
    readGltf(scratchFile(name, text));
  } catch (const InputError& e) {
    return {e.key(), e.message()};
  }
  return {"accepted", ""};
}

SceneDescription sceneWith(
    const fs::path& gltf, const std::string& camera = "{position: [0, 0, 5], look_at: [0, 0, 0]}") {
  return loadSceneFromText("camera: " + camera + "\ninclude:\n  - gltf: " + gltf.string() + "\n",
                           "test.yaml", ".");
}

TEST(GltfStructure, MalformedValuesAreRefusedWithTheirPath) {
  const std::string lights =
      R"("extensionsUsed":["KHR_lights_punctual"],"extensions":{"KHR_lights_punctual":{"lights":[)";
  const struct {
    const char* name;
    std::string text, key, says;
  } cases[] = {
      {"projective",
       triangleWith(kMesh + R"("nodes":[{"mesh":0,"matrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,2]}],)"
                            R"("scenes":[{"nodes":[0]}])"),
       "nodes[0].matrix", "must be affine"},
      {"both",
       triangleWith(kMesh + R"("nodes":[{"mesh":0,"matrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1],)"
                            R"("translation":[0.5,0,0]}],"scenes":[{"nodes":[0]}])"),
       "nodes[0].matrix", "not both"},
      {"text",
       triangleWith(kMesh +
                    R"("nodes":[{"mesh":0,"translation":"1,2,3"}],"scenes":[{"nodes":[0]}])"),
       "nodes[0].translation", "an array of 3 numbers"},
      {"twice", triangleWith(kMesh + R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0,0]}])"),
       "scenes[0].nodes[1]", "node 0 is listed twice"},
      {"child",
       triangleWith(kMesh + R"("nodes":[{"children":[1]},{"mesh":0}],"scenes":[{"nodes":[0,1]}])"),
       "scenes[0].nodes[1]", "node 1 is a child of nodes[0]"},
      {"intensity",
       triangleWith(kMesh + lights +
                    R"({"type":"point","intensity":"500"}]}},"nodes":[{"mesh":0}],)"
                    R"("scenes":[{"nodes":[0]}])"),
       "extensions.KHR_lights_punctual.lights[0].intensity", "must be a number"},
      {"colour",
       triangleWith(kMesh + lights +
                    R"({"type":"point","color":[1,0]}]}},"nodes":[{"mesh":0}],)"
                    R"("scenes":[{"nodes":[0]}])"),
       "extensions.KHR_lights_punctual.lights[0].color", "an array of 3 numbers"},
      {"untyped",
       triangleWith(kMesh + lights +
                    R"({"intensity":5}]}},"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])"),
       "extensions.KHR_lights_punctual.lights[0].type", "\"directional\""},
      {"yfov",
       triangleWith(
           kMesh + R"("cameras":[{"type":"perspective","perspective":{"yfov":"0.5","znear":0.1}}],)"
                   R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])"),
       "cameras[0].perspective.yfov", "must be a number"},
      {"alpha",
       triangleWith(
           R"("materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.5,0.5,-1]}}],)"
           R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],)"
           R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])"),
       "materials[0].pbrMetallicRoughness.baseColorFactor[3]", "must lie in [0, 1]"},
      {"zeros",
       R"({"asset":{"version":"2.0"},"accessors":[{"componentType":5126,"count":4294967296,)"
       R"("type":"VEC3"}],)" +
           kMesh + R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})",
       "accessors[0].count", "without a bufferView"},
  };
  for (const auto& c : cases) {
    const auto [key, message] = refusal(c.name, c.text);
    EXPECT_EQ(key, c.key) << c.name << ": " << message;
    EXPECT_NE(message.find(c.says), std::string::npos) << c.name << ": " << message;
  }
  // Five vertices of a triangle list: one triangle, the last two dropped and noted (the
  // Khronos validator warns; they were dropped silently).
  {
    test::GltfBuilder b;
    b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 2, 0}, "VEC3");
    const GltfDocument doc = readGltf(
        scratchFile("five", b.json(kMesh + R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])")));
    ASSERT_EQ(doc.meshes.size(), 1U);
    EXPECT_EQ(doc.meshes[0].primitives[0].mesh.indices.size(), 3U);
    ASSERT_EQ(doc.notes.size(), 1U);
    EXPECT_NE(doc.notes[0].find("accessors[0].count: 5 vertices"), std::string::npos)
        << doc.notes[0];
  }
  // Animation keys before 0 s, or rotations of length 0.
  for (const bool negative : {true, false}) {
    test::GltfBuilder b;
    b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int t = b.floats({negative ? -1.0f : 0.0f, 1.0f}, "SCALAR");
    const int r = b.floats({0, 0, 0, 1, 0, 0, 0, negative ? 1.0f : 0.0f}, "VEC4");
    const auto [key, message] = refusal(
        "keys", b.json(kMesh +
                       R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],)"
                       R"("animations":[{"samplers":[{"input":)" +
                       std::to_string(t) + R"(,"output":)" + std::to_string(r) +
                       R"(}],"channels":[{"sampler":0,"target":{"node":0,"path":"rotation"}}]}])"));
    EXPECT_EQ(key, negative ? "accessors[1]" : "accessors[2]") << message;
    EXPECT_NE(message.find(negative ? "must be >= 0 s" : "key 1 is no unit quaternion"),
              std::string::npos)
        << message;
  }
}

// A chain of nodes as deep as the loader reads, and one deeper (2,000 levels overflowed the
// stack of its recursive walk).
TEST(GltfStructure, NodeHierarchiesDeeperThanTheLimitAreRefused) {
  const auto chain = [](int depth) {
    std::string nodes;
    for (int i = 0; i < depth; ++i)
      nodes += (i ? "," : "") + (i + 1 < depth ? R"({"children":[)" + std::to_string(i + 1) + "]}"
                                               : std::string(R"({"mesh":0})"));
    return triangleWith(kMesh + R"("nodes":[)" + nodes + R"(],"scenes":[{"nodes":[0]}])");
  };
  const SceneDescription d = sceneWith(scratchFile("deepest", chain(kMaxGltfNodeDepth)));
  EXPECT_EQ(d.shapes.size(), 1U);
  const auto [key, message] = refusal("deeper", chain(kMaxGltfNodeDepth + 1));
  EXPECT_EQ(key, "nodes[" + std::to_string(kMaxGltfNodeDepth) + "]") << message;
  EXPECT_NE(message.find("camsim reads at most 256"), std::string::npos) << message;
}

// glTF keeps a triangle's front under a mirroring node (its winding turns clockwise): the
// placed triangle's counter-clockwise normal must face +z, as the asset's does, whether the
// mesh is baked (one node) or shared (two nodes place it).
TEST(GltfStructure, AMirroredNodeKeepsItsFrontAlsoWhenItsMeshIsShared) {
  for (const bool shared : {false, true}) {
    const std::string nodes =
        shared ? R"([{"mesh":0,"scale":[-1,1,1]},{"mesh":0,"translation":[3,0,0]}])"
               : R"([{"mesh":0,"scale":[-1,1,1]}])";
    const SceneDescription d = sceneWith(
        scratchFile(shared ? "mirror_shared" : "mirror_baked",
                    triangleWith(kMesh + R"("nodes":)" + nodes + R"(,"scenes":[{"nodes":[)" +
                                 (shared ? "0,1" : "0") + "]}]")));
    ASSERT_EQ(d.shapes.size(), shared ? 2U : 1U);
    for (const ShapeDescription& s : d.shapes) {
      const MeshData& mesh = s.sharedMesh ? *s.sharedMesh : s.mesh;
      const glm::dmat4 m = s.sharedMesh ? s.placement : glm::dmat4(1.0);
      glm::dvec3 p[3];
      for (int k = 0; k < 3; ++k)
        p[k] = glm::dvec3(m * glm::dvec4(glm::dvec3(mesh.positions[mesh.indices[k]]), 1.0));
      EXPECT_GT(glm::cross(p[1] - p[0], p[2] - p[0]).z, 0.0) << s.label << " shared " << shared;
    }
  }
}

// A light's direction is its node's −z whatever the node's scale (1e200 overflowed its
// length to inf: a NaN direction aborted the render).
TEST(GltfStructure, ALightUnderAHugeScaleKeepsItsDirection) {
  const SceneDescription d = sceneWith(scratchFile(
      "huge_light",
      triangleWith(
          kMesh + R"("extensionsUsed":["KHR_lights_punctual"],"extensions":{"KHR_lights_punctual":)"
                  R"({"lights":[{"type":"directional","intensity":3}]}},)"
                  R"("nodes":[{"mesh":0},{"scale":[1e200,1e200,1e200],"extensions":)"
                  R"({"KHR_lights_punctual":{"light":0}}}],"scenes":[{"nodes":[0,1]}])")));
  ASSERT_EQ(d.lights.size(), 1U);
  EXPECT_NEAR(d.lights[0].direction.z, -1.0f, 1e-6f);
}

// A yfov narrower than focal_length_mm's 1e5 mm on the sensor (1e-20 rad rendered every
// sample NaN, a black image, exit 0); a file without scenes places nothing (it was silent).
TEST(GltfStructure, ATinyYfovAndAFileWithoutScenesAreRefused) {
  const fs::path narrow = scratchFile(
      "narrow",
      triangleWith(kMesh +
                   R"("cameras":[{"type":"perspective","perspective":{"yfov":1e-20,"znear":0.1}}],)"
                   R"("nodes":[{"mesh":0},{"camera":0,"translation":[0,0,5]}],)"
                   R"("scenes":[{"nodes":[0,1]}])"));
  try {
    sceneWith(narrow, "{gltf: {include: 0, camera: 0}}");
    ADD_FAILURE() << "a yfov of 1e-20 rad was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "camera.gltf");
    EXPECT_NE(e.message().find("beyond focal_length_mm's 1e5"), std::string::npos) << e.what();
  }
  try {
    sceneWith(scratchFile("sceneless", triangleWith(kMesh + R"("nodes":[{"mesh":0}])")));
    ADD_FAILURE() << "a file without scenes was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "include[0].gltf");
    EXPECT_NE(e.message().find("the file has no scenes"), std::string::npos) << e.what();
  }
}

}  // namespace gltf_structure_test
}  // namespace camsim
