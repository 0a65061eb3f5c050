// The glTF importer (integrator/scene/scene_loader_gltf.cpp and gltf_*.cpp): node
// hierarchy, cameras, animation, materials and lights as camsim's scene parts, checked
// against the files' own numbers (Khronos sample assets in tests/data/gltf).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "integrator/camera/physical_camera.h"
#include "integrator/scene/scene_loader.h"
#include "integrator/textures/image_texture.h"
#include "sensor/base/input_error.h"
#include "sensor/spectra/cie.h"
#include "tests/integrator/scene/gltf_test_support.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

std::string sceneWith(const std::string& include,
                      const std::string& camera = "  position: [0, 0, 5]\n  look_at: [0, 0, 0]\n") {
  return "camera:\n" + camera + "  resolution: [64, 48]\ninclude:\n" + include;
}

SceneDescription load(const std::string& yaml, const std::filesystem::path& dir = test::kGltfData) {
  return loadSceneFromText(yaml, "test.yaml", dir);
}

TEST(GltfLoader, CamerasGltfPerspectiveCameraGivesItsFieldOfView) {
  const SceneDescription s = load(sceneWith("  - gltf: khronos/Cameras.gltf\n",
                                            "  gltf: {camera: 0}\n  sensor_height_mm: 24\n"
                                            "  sensor_width_mm: 32\n"));
  // yfov 0.7 rad on the sensor's height: f = (h/2)/tan(yfov/2).
  EXPECT_NEAR(s.camera.focalLength, 0.5 * s.camera.sensorSize.y / std::tan(0.35), 1e-15);
  EXPECT_NEAR(s.camera.sensorSize.y, 0.024, 1e-9);  // the stated sensor (stored as float)
  // The camera node at (0.5, 0.5, 3) looks down −z: render origin there, forward −z.
  EXPECT_NEAR(s.renderOrigin.x, 0.5, 1e-12);
  EXPECT_NEAR(s.renderOrigin.z, 3.0, 1e-12);
  EXPECT_NEAR(s.camera.worldFromCamera[2].z, -1.0, 1e-12);
  // A point at half the field of view above the axis images on the top edge (y = −½ px).
  const PhysicalCamera cam(s.camera);
  const double h = 2.0;  // m in front of the camera
  const auto top = cam.project(glm::dvec3(0.0, h * std::tan(0.35), -h), 0.0);
  ASSERT_TRUE(top);
  EXPECT_NEAR(top->y, -0.5, 1e-9);
  EXPECT_NEAR(top->x, 31.5, 1e-9);
  // The quad: one shape, rotated by the node's quaternion about x.
  ASSERT_EQ(s.shapes.size(), 1u);
  EXPECT_EQ(s.shapes[0].mesh.indices.size(), 6u);
  EXPECT_FALSE(s.notes.empty());  // aspectRatio and znear/zfar are reported as unused
}

TEST(GltfLoader, OrthographicCameraIsRefusedWithItsPath) {
  try {
    load(sceneWith("  - gltf: khronos/Cameras.gltf\n", "  gltf: {camera: 1}\n"));
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cameras[1] is orthographic"), std::string::npos)
        << e.what();
  }
}

// The camera node's scale is dropped, but a zero scale, a shear or a mirror is refused,
// naming the node (found by probing: a zero scale gave a NaN pose and a black image with
// exit 0; a mirroring scale was accepted and mirrored the image).
TEST(GltfLoader, ASingularShearedOrMirroringCameraNodeIsRefused) {
  const test::TempDir dir;
  const auto gltf = [](const std::string& node) {
    return "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": [{\"nodes\": [0]}], "
           "\"nodes\": [{\"camera\": 0, " +
           node +
           "}], \"cameras\": [{\"type\": \"perspective\", \"perspective\": {\"yfov\": 0.7, "
           "\"znear\": 0.01}}]}";
  };
  const std::string scene = sceneWith(
      "  - gltf: cam.gltf\nmaterials: {m: {type: diffuse}}\n"
      "shapes: [{type: sphere, centre: [0, 0, -3], radius: 1, material: m}]\n",
      "  gltf: {camera: 0}\n");
  test::writeFile(dir.path() / "cam.gltf",
                  gltf("\"translation\": [0, 0.1, 1.5], \"scale\": [2, 3, 0.5]"));
  const SceneDescription scaled = load(scene, dir.path());
  EXPECT_NEAR(scaled.camera.worldFromCamera[0].x, 1.0, 1e-12);  // axes unit, forward −z
  EXPECT_NEAR(scaled.camera.worldFromCamera[1].y, 1.0, 1e-12);
  EXPECT_NEAR(scaled.camera.worldFromCamera[2].z, -1.0, 1e-12);
  const std::pair<std::string, std::string> refused[] = {
      {"\"scale\": [0, 0, 0]", "nodes[0]: the camera's transform is singular (a zero scale)"},
      {"\"scale\": [1, 0, 1]", "nodes[0]: the camera's transform is singular"},
      {"\"scale\": [-1, 1, 1]", "nodes[0]: the camera's transform mirrors"},
      {"\"matrix\": [1, 0, 0, 0, 0.5, 1, 0, 0, 0, 0, 1, 0, 0, 0.1, 1.5, 1]",
       "nodes[0]: the camera's transform shears"},
  };
  // A mirroring include names the include, not the node.
  test::writeFile(dir.path() / "cam.gltf", gltf("\"translation\": [0, 0.1, 1.5]"));
  try {
    load(sceneWith("  - {gltf: cam.gltf, scale: [-1, 1, 1]}\nmaterials: {m: {type: diffuse}}\n"
                   "shapes: [{type: sphere, centre: [0, 0, -3], radius: 1, material: m}]\n",
                   "  gltf: {camera: 0}\n"),
         dir.path());
    ADD_FAILURE() << "a mirroring include loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("include[0]'s placement (its scale): the camera's "
                                         "transform mirrors"),
              std::string::npos)
        << e.what();
  }
  for (const auto& [node, message] : refused) {
    test::writeFile(dir.path() / "cam.gltf", gltf(node));
    try {
      load(scene, dir.path());
      ADD_FAILURE() << node << ": loaded";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("test.yaml:2:9: key 'camera.gltf': " + message),
                std::string::npos)
          << node << ": " << e.what();
    }
  }
}

TEST(GltfLoader, AnimatedTriangleRotationMatchesItsKeys) {
  const SceneDescription s = load(sceneWith("  - gltf: khronos/AnimatedTriangle.gltf\n"));
  ASSERT_EQ(s.shapes.size(), 1u);
  const RigidMotion& m = s.shapes[0].motion;
  ASSERT_FALSE(m.empty());
  // Keys: about +z by 0°, 90°, 180°, 270°, 360° at t = 0, ¼, ½, ¾, 1 s (LINEAR): slerp.
  for (double t : {0.25, 0.5, 0.75, 0.125, 0.6}) {
    const double angle = t * 2.0 * std::numbers::pi;
    const glm::dmat4 at = m.at(t);
    EXPECT_NEAR(at[0].x, std::cos(angle), 1e-6) << t;
    EXPECT_NEAR(at[0].y, std::sin(angle), 1e-6) << t;
    EXPECT_NEAR(at[1].x, -std::sin(angle), 1e-6) << t;
    EXPECT_NEAR(at[2].z, 1.0, 1e-6) << t;
    // The render origin is the camera at (0, 0, 5): translation −origin.
    EXPECT_NEAR(at[3].z, -5.0, 1e-12) << t;
  }
}

TEST(GltfLoader, CubeKeepsItsTexturesAndUvs) {
  const SceneDescription s = load(sceneWith("  - gltf: Cube/Cube.gltf\n"));
  ASSERT_EQ(s.shapes.size(), 1u);
  const ShapeDescription& cube = s.shapes[0];
  EXPECT_EQ(cube.mesh.indices.size(), 36u);
  EXPECT_EQ(cube.mesh.uvs.size(), cube.mesh.positions.size());
  EXPECT_EQ(cube.mesh.tangents.size(), cube.mesh.positions.size());
  const MaterialDescription& m = s.materials[static_cast<size_t>(cube.material)];
  EXPECT_EQ(m.type, MaterialDescription::Type::kMetallicRoughness);
  ASSERT_EQ(m.reflectance.kind, TextureDescription::Kind::kImage);
  ASSERT_TRUE(m.reflectance.image);
  EXPECT_EQ(m.reflectance.image->width, 512);
  EXPECT_EQ(m.reflectance.image->channels, 3);
  ASSERT_TRUE(m.roughness.image);
  EXPECT_EQ(m.roughness.image->channels, 1);
  // The files it read: the .gltf, its .bin and both PNGs.
  int pngs = 0;
  for (const auto& f : s.inputFiles) pngs += f.extension() == ".png";
  EXPECT_EQ(pngs, 2);
}

TEST(GltfLoader, GlbBoxLoads) {
  const SceneDescription s = load(sceneWith("  - gltf: box01.glb\n    translate: [1, 2, 3]\n"));
  ASSERT_FALSE(s.shapes.empty());
  EXPECT_GT(s.shapes[0].mesh.indices.size(), 0u);
}

// A two-node file whose nodes share one mesh: instanced, and each placement as given.
TEST(GltfLoader, MeshUsedByTwoNodesIsStoredOnceAndPlacedTwice) {
  test::GltfBuilder b;
  b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const std::string text =
      b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
             R"("nodes":[{"mesh":0,"translation":[1,0,0]},{"mesh":0,"scale":[2,1,1]}],)"
             R"("scenes":[{"nodes":[0,1]}])");
  const auto dir = std::filesystem::temp_directory_path() / "camsim_gltf_instances";
  std::filesystem::create_directories(dir);
  test::writeText(dir / "two.gltf", text);
  const SceneDescription s = load(sceneWith("  - gltf: two.gltf\n"), dir);
  ASSERT_EQ(s.shapes.size(), 2u);
  ASSERT_TRUE(s.shapes[0].sharedMesh);
  EXPECT_EQ(s.shapes[0].sharedMesh, s.shapes[1].sharedMesh);
  EXPECT_TRUE(s.shapes[0].mesh.positions.empty());
  EXPECT_NEAR(s.shapes[0].placement[3].x, 1.0, 1e-12);
  EXPECT_NEAR(s.shapes[1].placement[0].x, 2.0, 1e-12);
  EXPECT_NEAR(s.shapes[1].placement[3].z, -5.0, 1e-12);  // render space
}

// A mirroring placement keeps the front side in front: the winding is reversed.
TEST(GltfLoader, MirroringPlacementReversesTheWinding) {
  test::GltfBuilder b;
  b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const auto dir = std::filesystem::temp_directory_path() / "camsim_gltf_mirror";
  std::filesystem::create_directories(dir);
  test::writeText(dir / "tri.gltf",
                  b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                         R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])"));
  const SceneDescription plain = load(sceneWith("  - gltf: tri.gltf\n"), dir);
  const SceneDescription mirrored =
      load(sceneWith("  - gltf: tri.gltf\n    scale: [-1, 1, 1]\n"), dir);
  ASSERT_EQ(mirrored.shapes.size(), 1u);
  const MeshData& a = plain.shapes[0].mesh;
  const MeshData& m = mirrored.shapes[0].mesh;
  auto normal = [](const MeshData& d) {
    return glm::cross(d.positions[d.indices[1]] - d.positions[d.indices[0]],
                      d.positions[d.indices[2]] - d.positions[d.indices[0]]);
  };
  EXPECT_GT(normal(a).z, 0.0f);
  EXPECT_GT(normal(m).z, 0.0f);  // mirrored in x, still facing +z
  EXPECT_FLOAT_EQ(m.positions[1].x, -1.0f);
}

// STEP keeps each value until the next key; CUBICSPLINE follows the Hermite spline.
TEST(GltfLoader, StepAndCubicSplineTranslation) {
  test::GltfBuilder b;
  b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const int times = b.floats({0.0f, 1.0f}, "SCALAR");
  const int step = b.floats({0, 0, 0, 2, 0, 0}, "VEC3");
  // cubic: (in, value, out) per key; value 0 → 1 with out-tangent 0, in-tangent 0: smoothstep.
  const int cubic = b.floats({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0}, "VEC3");
  const std::string anim =
      R"("animations":[{"samplers":[{"input":)" + std::to_string(times) + R"(,"output":)" +
      std::to_string(step) + R"(,"interpolation":"STEP"},)" + R"({"input":)" +
      std::to_string(times) + R"(,"output":)" + std::to_string(cubic) +
      R"(,"interpolation":"CUBICSPLINE"}],)" +
      R"("channels":[{"sampler":0,"target":{"node":0,"path":"translation"}},)" +
      R"({"sampler":1,"target":{"node":1,"path":"translation"}}]}])";
  const auto dir = std::filesystem::temp_directory_path() / "camsim_gltf_interp";
  std::filesystem::create_directories(dir);
  test::writeText(dir / "anim.gltf",
                  b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                         R"("nodes":[{"mesh":0},{"mesh":0}],"scenes":[{"nodes":[0,1]}],)" +
                         anim));
  const SceneDescription s = load(sceneWith("  - gltf: anim.gltf\n"), dir);
  ASSERT_EQ(s.shapes.size(), 2u);
  EXPECT_NEAR(s.shapes[0].motion.at(0.5)[3].x, 0.0, 1e-12);
  EXPECT_NEAR(s.shapes[0].motion.at(0.999)[3].x, 0.0, 1e-12);
  EXPECT_NEAR(s.shapes[0].motion.at(1.0)[3].x, 2.0, 1e-12);
  for (double t : {0.25, 0.5, 0.75}) {
    const double smooth = t * t * (3.0 - 2.0 * t);
    EXPECT_NEAR(s.shapes[1].motion.at(t)[3].y, smooth, 1e-12) << t;  // on the samples
  }
  EXPECT_NEAR(s.shapes[1].motion.at(0.3)[3].y, 0.3 * 0.3 * 2.4, 2e-3);  // between: linear
}

TEST(GltfLoader, PointLightInCandela) {
  const std::string text = test::GltfBuilder().json(
      R"("extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","intensity":100}]}},)"
      R"("extensionsUsed":["KHR_lights_punctual"],)"
      R"("nodes":[{"translation":[0,2,0],"extensions":{"KHR_lights_punctual":{"light":0}}}],)"
      R"("scenes":[{"nodes":[0]}])");
  const auto dir = std::filesystem::temp_directory_path() / "camsim_gltf_light";
  std::filesystem::create_directories(dir);
  test::writeText(dir / "light.gltf", text);
  const SceneDescription s =
      load(sceneWith("  - gltf: light.gltf\nshapes:\n  - type: sphere\n"
                     "    centre: [0, 0, -10]\n    radius: 1\n    material: m\n"
                     "materials:\n  m: {type: diffuse}\n"),
           dir);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].kind, LightDescription::Kind::kPoint);
  EXPECT_NEAR(luminance(s.lights[0].spectrum), 100.0, 1e-5);  // cd: 683 Σ I ȳ Δλ (float samples)
  EXPECT_NEAR(s.lights[0].position.y, 2.0f, 1e-6f);
}

}  // namespace
}  // namespace camsim
