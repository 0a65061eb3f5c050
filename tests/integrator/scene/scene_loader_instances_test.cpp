// Tests for a mesh shape's `instances:` (integrator/scene/scene_loader_instances.cpp) and a
// material's `alpha_cutout:` (scene_loader_materials.cpp): placements from translate /
// rotate / scale or a matrix, shifted into render space; names, classes and materials per
// instance; one shared mesh; the errors, each at its line; and the Scene's own checks of
// descriptions built in code.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "integrator/geometry/mesh_instance.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_ids.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace {

// Lines 1–4; the camera sits at (1, 2, 3): render space is the world minus that.
const std::string kHead =
    "camera: {position: [1, 2, 3], look_at: [0, 0, 0]}\n"
    "materials:\n"
    "  m: {type: diffuse}\n"
    "  n: {type: diffuse, alpha_cutout: {alpha: {checkerboard: {a: 1, b: 0}}, cutoff: 0.3}}\n"
    "shapes:\n";
// Lines 6–9: a mesh (one triangle) whose `instances:` follow on line 10.
const std::string kMesh =
    "  - type: mesh\n"
    "    material: m\n"
    "    vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n"
    "    faces: [[0, 1, 2]]\n";

SceneDescription loadInstances(const std::string& text) {
  return loadSceneFromText(text, "test.yaml", ".");
}

void expectNear(const glm::dmat4& a, const glm::dmat4& b) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], 1e-12) << c << "," << r;
}

TEST(SceneLoaderInstances, PlacementsNamesClassesAndMaterials) {
  const SceneDescription d = loadInstances(
      kHead +
      "  - type: mesh\n    name: tri\n    class: rock\n    material: m\n"
      "    vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n    faces: [[0, 1, 2]]\n"
      "    instances:\n"
      "      - {translate: [4, 5, 6], rotate: {axis: [0, 0, 2], angle_deg: 90}, scale: 2}\n"
      "      - {scale: [1, -2, 3], name: flipped, class: 7, material: n}\n"
      "      - {matrix: [1, 0, 0, 10,  0, 2, 0, 20,  0, 0, 3, 30,  0, 0, 0, 1]}\n"
      "      - {translate: [1, 1, 1], motion: [{time: 0, translate: [2, 2, 3]}]}\n");
  ASSERT_EQ(d.shapes.size(), 4u);
  for (const ShapeDescription& s : d.shapes) {
    EXPECT_EQ(s.sharedMesh, d.shapes[0].sharedMesh);
    EXPECT_TRUE(s.mesh.positions.empty());
  }
  ASSERT_TRUE(d.shapes[0].sharedMesh);
  EXPECT_EQ(d.shapes[0].sharedMesh->positions[1], glm::vec3(1, 0, 0));  // object space
  const glm::dvec3 origin(1, 2, 3);
  glm::dmat4 trs = glm::rotate(glm::dmat4(1.0), M_PI / 2, glm::dvec3(0, 0, 1));
  trs = trs * glm::scale(glm::dmat4(1.0), glm::dvec3(2.0));
  trs[3] = glm::dvec4(glm::dvec3(4, 5, 6) - origin, 1.0);
  expectNear(d.shapes[0].placement, trs);
  glm::dmat4 mirrored = glm::scale(glm::dmat4(1.0), glm::dvec3(1, -2, 3));
  mirrored[3] = glm::dvec4(-origin, 1.0);
  expectNear(d.shapes[1].placement, mirrored);
  glm::dmat4 matrix = glm::scale(glm::dmat4(1.0), glm::dvec3(1, 2, 3));
  matrix[3] = glm::dvec4(glm::dvec3(10, 20, 30) - origin, 1.0);
  expectNear(d.shapes[2].placement, matrix);
  // A moving instance: the keyframes carry the shift, the placement does not.
  glm::dmat4 moved(1.0);
  moved[3] = glm::dvec4(1, 1, 1, 1);
  expectNear(d.shapes[3].placement, moved);
  expectNear(d.shapes[3].motion.at(0.0), glm::translate(glm::dmat4(1.0), glm::dvec3(1, 0, 0)));
  EXPECT_EQ(d.shapes[0].label, "tri[0]");
  EXPECT_EQ(d.shapes[1].label, "flipped");
  EXPECT_EQ(d.shapes[0].className, "rock");
  EXPECT_EQ(d.shapes[1].className, "7");
  EXPECT_EQ(d.shapes[1].classNumber, 7u);
  EXPECT_EQ(d.shapes[0].material, 0);
  EXPECT_EQ(d.shapes[1].material, 1);
  ASSERT_TRUE(d.materials[1].alphaCutout);
  EXPECT_EQ(d.materials[1].alphaCutout->cutoff, 0.3f);
  EXPECT_EQ(d.materials[1].alphaCutout->factor, 1.0f);
  EXPECT_EQ(d.materials[1].alphaCutout->texture->kind, TextureDescription::Kind::kCheckerboard);
  // One instance id per instance; the Scene instances the shared mesh.
  const SceneIds ids = sceneIds(d);
  EXPECT_EQ(ids[IdKind::kInstance].names.size(), 5u);
  const Scene scene(d);
  for (int i = 0; i < 4; ++i)
    EXPECT_NE(dynamic_cast<const MeshInstance*>(&scene.shape(i)), nullptr) << i;
}

// One instance only: baked into a mesh of its own (nothing to share), its vertices placed.
TEST(SceneLoaderInstances, AMeshPlacedOnceIsBaked) {
  const Scene scene(
      loadInstances(kHead + kMesh + "    instances: [{translate: [1, 2, 4], scale: [2, 1, 1]}]\n"));
  const auto* mesh = dynamic_cast<const TriangleMesh*>(&scene.shape(0));
  ASSERT_NE(mesh, nullptr);
  EXPECT_EQ(mesh->positions()[1], glm::vec3(2, 0, 1));
}

struct InstanceError {
  const char* name;
  std::string text;
  int line;
  std::string message;
};

const InstanceError kInstanceErrors[] = {
    {"MatrixAndTranslate",
     kHead + kMesh +
         "    instances: [{matrix: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], "
         "translate: [0, 0, 0]}]\n",
     10, "not both"},
    {"SingularMatrix",
     kHead + kMesh +
         "    instances:\n      - matrix: [1, 0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 1]\n",
     11, "singular"},
    {"MatrixLastRow",
     kHead + kMesh +
         "    instances: [{matrix: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1]}]\n",
     10, "last row"},
    {"MatrixSize", kHead + kMesh + "    instances: [{matrix: [1, 0, 0]}]\n", 10, "16 numbers"},
    {"ZeroScale", kHead + kMesh + "    instances: [{scale: [1, 0, 1]}]\n", 10, "non-zero"},
    {"UnknownKey", kHead + kMesh + "    instances: [{translat: [1, 0, 1]}]\n", 10, "unknown key"},
    {"UnknownMaterial", kHead + kMesh + "    instances: [{material: q}]\n", 10, "no material"},
    {"Empty", kHead + kMesh + "    instances: []\n", 10, "at least one"},
    {"NotAMesh",
     kHead + "  - {type: sphere, centre: [0, 0, 0], radius: 1, material: m, instances: [{}]}\n", 6,
     "only a mesh"},
    {"ShapeMotion",
     kHead + kMesh + "    motion: [{time: 0}]\n    instances: [{translate: [0, 0, 0]}]\n", 10,
     "cannot move"},
    {"CutoutOnSphere", kHead + "  - {type: sphere, centre: [0, 0, 0], radius: 1, material: n}\n", 6,
     "needs a mesh"},
    {"CutoutOnEmitter",
     kHead + "  - {type: rectangle, corner: [0, 0, 0], edge_u: [1, 0, 0], edge_v: [0, 1, 0],\n"
             "     material: n, emission: {luminance: 1}}\n",
     7, "cut-out emitters"},
    {"CutoutKey",
     "camera: {position: [1, 2, 3], look_at: [0, 0, 0]}\n"
     "materials: {m: {type: diffuse, alpha_cutout: {cutof: 1}}}\n"
     "shapes: [{type: sphere, centre: [0, 0, 0], radius: 1, material: m}]\n",
     2, "unknown key"},
};

class SceneLoaderInstanceError : public ::testing::TestWithParam<InstanceError> {};

TEST_P(SceneLoaderInstanceError, ThrowsAtTheLine) {
  const InstanceError& c = GetParam();
  try {
    loadInstances(c.text);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, c.line) << e.what();
    EXPECT_NE(e.message().find(c.message), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(SceneLoaderInstances, SceneLoaderInstanceError,
                         ::testing::ValuesIn(kInstanceErrors),
                         [](const ::testing::TestParamInfo<InstanceError>& p) {
                           return std::string(p.param.name);
                         });

// Descriptions built in code (the glTF importer's) are checked by the Scene: a singular
// placement, or a cut-out on an emitter, is an InputError naming the shape.
TEST(SceneLoaderInstances, SceneRejectsWhatTheLoaderWouldHave) {
  SceneDescription d =
      loadInstances(kHead + kMesh + "    instances: [{}, {translate: [0, 0, 1]}]\n");
  SceneDescription singular = d;
  singular.shapes[1].placement[1] = glm::dvec4(0.0);
  EXPECT_THROW(
      {
        try {
          const Scene scene(singular);
        } catch (const InputError& e) {
          // The entry's key path and line; the label first in the message.
          EXPECT_EQ(e.key(), "shapes[0].instances[1]");
          EXPECT_GT(e.where().line, 0);
          EXPECT_EQ(e.message().rfind("'shapes[0][1]': ", 0), 0u) << e.what();
          throw;
        }
      },
      InputError);
  SceneDescription emitting = d;
  emitting.shapes[0].material = 1;  // the cut-out material
  emitting.shapes[0].emission = EmissionDescription{Spectrum::constant(1.0), false};
  EXPECT_THROW(const Scene scene(emitting), InputError);
}

}  // namespace
}  // namespace camsim
