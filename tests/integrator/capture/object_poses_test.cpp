// Tests for integrator/capture/object_poses.cpp: the model frame of each kind of mesh, and
// poses that put the model where the render sees it — a rendered cube's position AOV against
// the pose projected through cam_K (issue 40: within 0.05 px), a moving and a mirrored
// instance against PhysicalCamera::project.
#include "integrator/capture/object_poses.h"

#include <gtest/gtest.h>

#include <fstream>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include "integrator/capture/capture.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace object_poses_test {

// The unit cube's corners about the origin, and its 12 triangles.
const char* const kCube =
    "    vertices: [[-0.5, -0.5, -0.5], [0.5, -0.5, -0.5], [0.5, 0.5, -0.5], [-0.5, 0.5, -0.5],\n"
    "               [-0.5, -0.5, 0.5], [0.5, -0.5, 0.5], [0.5, 0.5, 0.5], [-0.5, 0.5, 0.5]]\n"
    "    faces: [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],\n"
    "            [3, 6, 2], [3, 7, 6], [0, 4, 7], [0, 7, 3], [1, 2, 6], [1, 6, 5]]\n";

const double kCubeVertices[8][3] = {{-0.5, -0.5, -0.5}, {0.5, -0.5, -0.5}, {0.5, 0.5, -0.5},
                                    {-0.5, 0.5, -0.5},  {-0.5, -0.5, 0.5}, {0.5, -0.5, 0.5},
                                    {0.5, 0.5, 0.5},    {-0.5, 0.5, 0.5}};

// A pinhole 72 × 48 px camera (fx = fy = 100 px) at (0.3, 0.2, −2) looking at the origin
// (away from the world origin: the render origin is the camera's position).
std::string cameraText(const std::string& more = "") {
  return "camera: {position: [0.3, 0.2, -2], look_at: [0, 0, 0], resolution: [72, 48],\n"
         "         focal_length_mm: 50, sensor_width_mm: 36, sensor_height_mm: 24" +
         more + "}\n";
}

glm::dvec2 projectK(const glm::dvec4& k, const glm::dvec3& c) {
  return {k.x * c.x / c.z + k.z, k.y * c.y / c.z + k.w};
}

// The cube, scaled by 0.4 and turned 35° about (1, 2, 0.5), centred at world (0.05, −0.1, 0.2):
// its model is the cube × 0.4 (the scale is not a pose), and every pixel the cube covers
// entirely shows a surface point whose model coordinates — from the position AOV and the
// placement the scene states, inverted here — project through cam_R_m2c, cam_t_m2c and
// cam_K onto the pixel's centre within 0.05 px. (The AOV averages the point over the
// pixel's 64 samples: the mean of a plane's points projects within ~0.01 px of the centre.)
TEST(ObjectPoses, ModelPointsProjectOntoThePositionAovsPixels) {
  const std::string text = cameraText() +
                           "render: {spp: 64, max_depth: 1, aovs: [position]}\n"
                           "materials: {m: {type: diffuse}}\n"
                           "shapes:\n"
                           "  - type: mesh\n"
                           "    class: 3\n"
                           "    material: m\n" +
                           std::string(kCube) +
                           "    instances:\n"
                           "      - {translate: [0.05, -0.1, 0.2], scale: 0.4,\n"
                           "         rotate: {axis: [1, 2, 0.5], angle_deg: 35}}\n"
                           "lights: [{type: point, position: [0, 0, -3], intensity: 10}]\n";
  const SceneDescription d = loadSceneFromText(text, "cube.yaml", ".");
  const ObjectModel model = objectModel(d, 0);
  ASSERT_EQ(model.vertices.size(), 8u);
  for (int i = 0; i < 8; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(model.vertices[i][c], 0.4 * kCubeVertices[i][c], 1e-12);
  EXPECT_NEAR(model.boxMax.x - model.boxMin.x, 0.4, 1e-12);

  const std::vector<ObjectPose> poses = objectPoses(d, d.camera, {});
  ASSERT_EQ(poses.size(), 1u);
  const ObjectPose& p = poses[0];
  EXPECT_EQ(p.classNumber, 3u);
  EXPECT_EQ(p.instance, 1u);
  EXPECT_NEAR(glm::determinant(p.rotation), 1.0, 1e-12);
  const glm::dmat3 rtr = glm::transpose(p.rotation) * p.rotation;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rtr[c][r], r == c ? 1.0 : 0.0, 1e-12);

  const CaptureResult result = capture(d);
  const Image& a = result.aovs;
  const int cov = a.channelIndex("coverage.A"), px = a.channelIndex("P.X");
  ASSERT_GE(cov, 0);
  ASSERT_GE(px, 0);
  const glm::dvec4 k = PhysicalCamera(d.camera).intrinsics();
  // The placement as the scene states it, inverted by hand: world = T + R_axis(35°) · model.
  const glm::dmat3 turn(
      glm::rotate(glm::dmat4(1.0), glm::radians(35.0), glm::normalize(glm::dvec3(1.0, 2.0, 0.5))));
  const glm::dvec3 centre(0.05, -0.1, 0.2);
  int checked = 0;
  double worst = 0.0;
  for (int y = 1; y + 1 < a.height; ++y)
    for (int x = 1; x + 1 < a.width; ++x) {
      bool inside = true;  // the pixel and its neighbours entirely on the cube
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) inside = inside && a.at(x + dx, y + dy, cov) == 1.0f;
      if (!inside) continue;
      const glm::dvec3 world(a.at(x, y, px), a.at(x, y, px + 1), a.at(x, y, px + 2));
      const glm::dvec3 inModel = glm::transpose(turn) * (world - centre);
      const glm::dvec2 u = projectK(k, p.rotation * inModel + p.translation);
      worst = std::max(worst, glm::length(u - glm::dvec2(x, y)));
      ++checked;
    }
  EXPECT_GT(checked, 40);
  EXPECT_LT(worst, 0.05) << checked;
}

// A moving mesh (keyframed translation and turn) is posed at the frame's reference time,
// the shutter's centre: its model vertices through the pose and cam_K land where
// PhysicalCamera::project images the vertices its motion places at that time (the camera
// pans too); within 1e-6 px.
TEST(ObjectPoses, AMovingMeshIsPosedAtTheShuttersCentre) {
  const std::string text = cameraText(
                               ",\n shutter: {open: 0.1, close: 0.3},\n"
                               " motion: [{time: 0, rotate: {axis: [0, 1, 0], angle_deg: 0}},\n"
                               "          {time: 1, rotate: {axis: [0, 1, 0], angle_deg: 10}}]") +
                           "materials: {m: {type: diffuse}}\n"
                           "shapes:\n"
                           "  - type: mesh\n"
                           "    class: box\n"
                           "    material: m\n" +
                           std::string(kCube) +
                           "    motion: [{time: 0, translate: [0, 0, 0], scale: 0.3},\n"
                           "             {time: 1, translate: [0.4, 0.1, 0.5], scale: 0.3,\n"
                           "              rotate: {axis: [0, 0, 1], angle_deg: 60}}]\n";
  const SceneDescription d = loadSceneFromText(text, "moving.yaml", ".");
  const ShapeDescription& s = d.shapes[0];
  const double t = d.camera.shutter.centre();
  EXPECT_NEAR(t, 0.2, 1e-12);
  const PhysicalCamera camera(d.camera);
  const ObjectModel model = objectModel(d, 0);
  const ObjectPose p = objectPoses(d, d.camera, {}).at(0);
  for (std::size_t i = 0; i < model.vertices.size(); ++i) {
    EXPECT_NEAR(glm::length(model.vertices[i]), 0.3 * std::sqrt(0.75), 1e-9);  // scale baked
    const glm::dvec3 placed(s.motion.at(t) * glm::dvec4(glm::dvec3(s.mesh.positions[i]), 1.0));
    const std::optional<glm::dvec2> truth = camera.project(placed, t);
    ASSERT_TRUE(truth);
    const glm::dvec2 u =
        projectK(camera.intrinsics(), p.rotation * model.vertices[i] + p.translation);
    EXPECT_LT(glm::length(u - *truth), 1e-6) << i;
  }
}

// A mirroring, shearing instance matrix: the pose keeps a proper rotation and the model
// carries the rest (S = Rᵀ L), still landing on the projected placed vertices.
TEST(ObjectPoses, AMirroredInstanceKeepsAProperRotation) {
  const std::string text = cameraText() +
                           "materials: {m: {type: diffuse}}\n"
                           "shapes:\n"
                           "  - type: mesh\n"
                           "    class: 1\n"
                           "    material: m\n" +
                           std::string(kCube) +
                           "    instances:\n"
                           "      - {matrix: [-0.3, 0.1, 0, 0.1,  0, 0.2, 0.05, 0,  0.1, 0, 0.25, "
                           "0.3,  0, 0, 0, 1]}\n";
  const SceneDescription d = loadSceneFromText(text, "mirror.yaml", ".");
  const ShapeDescription& s = d.shapes[0];
  const PhysicalCamera camera(d.camera);
  const double t = d.camera.shutter.centre();
  const ObjectModel model = objectModel(d, 0);
  const ObjectPose p = objectPoses(d, d.camera, {}).at(0);
  EXPECT_NEAR(glm::determinant(p.rotation), 1.0, 1e-9);
  for (std::size_t i = 0; i < model.vertices.size(); ++i) {
    const glm::dvec3 placed(s.placement * glm::dvec4(glm::dvec3(s.sharedMesh->positions[i]), 1.0));
    const glm::dvec2 u =
        projectK(camera.intrinsics(), p.rotation * model.vertices[i] + p.translation);
    EXPECT_LT(glm::length(u - *camera.project(placed, t)), 1e-6) << i;
  }
}

// A mesh file's model is the file × scale wherever `translate` puts it: two shapes of the
// file at different places have the same model (one BOP model serves both), and a sphere's is
// centred on its centre.
TEST(ObjectPoses, AMeshFilesModelIsTheFileTimesItsScale) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "camsim_poses_obj";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "tri.obj") << "v 1 0 0\nv 0 2 0\nv 0 0 3\nf 1 2 3\n";
  const std::string text = cameraText() +
                           "materials: {m: {type: diffuse}}\n"
                           "shapes:\n"
                           "  - {type: mesh, file: tri.obj, scale: 0.1, translate: [1, 2, 3], "
                           "class: 2, material: m}\n"
                           "  - {type: mesh, file: tri.obj, scale: 0.1, translate: [-1, 0, 4], "
                           "class: 2, material: m}\n"
                           "  - {type: sphere, centre: [0.5, 0, 1], radius: 0.2, class: 4, "
                           "material: m}\n";
  const SceneDescription d = loadSceneFromText(text, "files.yaml", dir);
  for (std::size_t shape : {std::size_t{0}, std::size_t{1}}) {
    const ObjectModel m = objectModel(d, shape);
    ASSERT_EQ(m.vertices.size(), 3u);
    EXPECT_NEAR(m.vertices[0].x, 0.1, 1e-6);
    EXPECT_NEAR(m.vertices[1].y, 0.2, 1e-6);
    EXPECT_NEAR(m.vertices[2].z, 0.3, 1e-6);
    EXPECT_NEAR(m.vertices[2].x, 0.0, 1e-6);
  }
  const ObjectModel ball = objectModel(d, 2);
  EXPECT_NEAR(ball.boxMax.y, 0.2, 1e-8);  // the radius as stored, in float
  EXPECT_NEAR(ball.boxMin.y, -0.2, 1e-8);
  // Its pose's translation is the centre in camera coordinates.
  const std::vector<ObjectPose> poses = objectPoses(d, d.camera, {});
  ASSERT_EQ(poses.size(), 3u);
  const PhysicalCamera camera(d.camera);
  const glm::dvec3 centre = glm::dvec3(cameraCvFromRender(camera, 0.0) *
                                       glm::dvec4(glm::dvec3(0.5, 0.0, 1.0) - d.renderOrigin, 1.0));
  EXPECT_LT(glm::length(poses[2].translation - centre), 1e-7);  // the centre is stored in float
  std::filesystem::remove_all(dir);
}

// Keyframes that scale differently leave no rigid pose: an InputError naming the shape.
TEST(ObjectPoses, AShapeWhoseScaleChangesHasNoRigidPose) {
  const std::string text = cameraText() +
                           "materials: {m: {type: diffuse}}\n"
                           "shapes:\n"
                           "  - type: mesh\n"
                           "    name: grower\n"
                           "    class: 1\n"
                           "    material: m\n" +
                           std::string(kCube) +
                           "    motion: [{time: 0, scale: 0.3}, {time: 1, scale: 0.6}]\n";
  const SceneDescription d = loadSceneFromText(text, "grow.yaml", ".");
  try {
    (void)objectModel(d, 0);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("grower"), std::string::npos) << e.what();
  }
}

// Models given (as a sequence's BOP writer keeps them): the same poses bit for bit, each
// box the given model's; a labelled shape given none has its own model made; an unlabelled
// one has no pose.
TEST(ObjectPoses, GivenModelsGiveTheSamePosesWithTheirBoxes) {
  const std::string text = cameraText() +
                           "materials: {m: {type: diffuse}}\n"
                           "shapes:\n"
                           "  - {type: sphere, centre: [0.5, 0, 1], radius: 0.2, class: 4, "
                           "material: m}\n"
                           "  - {type: sphere, centre: [0, 0, 0], radius: 1, material: m}\n"
                           "  - {type: sphere, centre: [-0.5, 0.1, 2], radius: 0.2, class: 4, "
                           "material: m}\n"
                           "  - {type: sphere, centre: [0, -0.3, 2], radius: 0.3, class: 5, "
                           "material: m}\n";
  const SceneDescription d = loadSceneFromText(text, "given.yaml", ".");
  const std::vector<ObjectPose> made = objectPoses(d, d.camera, {});
  const ObjectModel own = objectModel(d, 0);
  ObjectModel other;  // a stand-in with a box of its own
  other.boxMin = glm::dvec3(-1.0, -2.0, -3.0);
  other.boxMax = glm::dvec3(1.0, 2.0, 3.0);
  const std::vector<const ObjectModel*> models{&own, nullptr, &other, nullptr};
  const std::vector<ObjectPose> given = objectPoses(d, d.camera, models);
  ASSERT_EQ(made.size(), 3u);
  ASSERT_EQ(given.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(given[i].shape, made[i].shape);
    EXPECT_EQ(given[i].classNumber, made[i].classNumber);
    EXPECT_TRUE(given[i].rotation == made[i].rotation) << i;
    EXPECT_TRUE(given[i].translation == made[i].translation) << i;
  }
  EXPECT_TRUE(given[0].boxMin == own.boxMin && given[0].boxMax == own.boxMax);
  EXPECT_TRUE(given[1].boxMin == other.boxMin && given[1].boxMax == other.boxMax);
  EXPECT_TRUE(given[2].boxMin == made[2].boxMin && given[2].boxMax == made[2].boxMax);
}

}  // namespace object_poses_test
}  // namespace camsim
