// Tests for integrator/capture/kitti_writer.cpp without a render: a box turned 30° about up
// (a 0.6 × 0.4 × 0.3 m cuboid, bottom centre at world (0.2, 0, 0)) seen by a level camera and
// by one looking 23° down. The label's fields against their closed forms (KITTI's rect frame:
// x right, y down along gravity, z forward level, from the camera), the devkit's 3-D box
// through P2 against the true corners through the true camera, truncation, a box behind the
// camera left out, and `occluded` from the masks' visible fraction.
#include "integrator/capture/kitti_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>

#include <glm/geometric.hpp>

#include "integrator/capture/bop_writer.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace kitti_writer_test {

constexpr int kW = 64, kH = 48;
constexpr double kFx = 50.0 / (36.0 / kW);  // px: 50 mm over a 0.5625 mm pitch
constexpr double kCx = kW / 2 - 0.5, kCy = kH / 2 - 0.5;
constexpr double kTurn = 30.0 * std::numbers::pi / 180.0;
const glm::dvec3 kSize(0.6, 0.4, 0.3);  // m along the model's x (l), y (h), z (w)
const glm::dvec3 kAt(0.2, 0.0, 0.0);    // m: the box's bottom centre

std::string sceneText(const glm::dvec3& position, const glm::dvec3& lookAt,
                      const glm::dvec3& at = kAt) {
  const auto v = [](const glm::dvec3& p) {
    return "[" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
           "]";
  };
  return "camera: {position: " + v(position) + ", look_at: " + v(lookAt) +
         ", resolution: [64, 48],\n"
         "         focal_length_mm: 50, sensor_width_mm: 36, sensor_height_mm: 27}\n"
         "exports: [kitti]\n"
         "materials: {m: {type: diffuse}}\n"
         "shapes:\n"
         "  - type: mesh\n"
         "    class: Car\n"
         "    material: m\n"
         "    vertices: [[-0.5, 0, -0.5], [0.5, 0, -0.5], [0.5, 1, -0.5], [-0.5, 1, -0.5],\n"
         "               [-0.5, 0, 0.5], [0.5, 0, 0.5], [0.5, 1, 0.5], [-0.5, 1, 0.5]]\n"
         "    faces: [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],\n"
         "            [3, 6, 2], [3, 7, 6], [0, 4, 7], [0, 7, 3], [1, 2, 6], [1, 6, 5]]\n"
         "    instances: [{translate: " +
         v(at) +
         ", rotate: {axis: [0, 1, 0], angle_deg: 30},\n"
         "                 scale: [0.6, 0.4, 0.3]}]\n"
         "lights: [{type: point, position: [0, 3, -3], intensity: 50}]\n";
}

CaptureResult described(const std::string& text) {
  CaptureResult r;
  r.description = loadSceneFromText(text, "kitti.yaml", ".");
  return r;
}

// The 2-D bounds (umin, vmin, umax, vmax) of points through a 3×4 row-major P.
glm::dvec4 bounds(const std::vector<double>& p, const std::vector<glm::dvec3>& points) {
  glm::dvec4 b(1e300, 1e300, -1e300, -1e300);
  for (const glm::dvec3& x : points) {
    const double u = p[0] * x.x + p[1] * x.y + p[2] * x.z + p[3];
    const double v = p[4] * x.x + p[5] * x.y + p[6] * x.z + p[7];
    const double w = p[8] * x.x + p[9] * x.y + p[10] * x.z + p[11];
    b = glm::dvec4(std::min(b.x, u / w), std::min(b.y, v / w), std::max(b.z, u / w),
                   std::max(b.w, v / w));
  }
  return b;
}

// The devkit's box corners (rect) from a label: x along l, y up to −h, z along w, turned
// by rotation_y about y.
std::vector<glm::dvec3> devkitCorners(const KittiLabel& l) {
  std::vector<glm::dvec3> c;
  const double cs = std::cos(l.rotationY), sn = std::sin(l.rotationY);
  for (int i = 0; i < 8; ++i) {
    const double x = (i & 1 ? 0.5 : -0.5) * l.l, z = (i & 2 ? 0.5 : -0.5) * l.w;
    c.emplace_back(cs * x + sn * z + l.x, (i & 4 ? -l.h : 0.0) + l.y, -sn * x + cs * z + l.z);
  }
  return c;
}

// The box's true corners in the camera's OpenCV frame (x right = forward × up, y down-ish,
// z forward), built from the scene's placement and the look_at camera.
std::vector<glm::dvec3> trueCorners(const glm::dvec3& position, const glm::dvec3& lookAt,
                                    const glm::dvec3& at = kAt) {
  const glm::dvec3 z = glm::normalize(lookAt - position);
  const glm::dvec3 x = glm::normalize(glm::cross(z, glm::dvec3(0, 1, 0)));
  const glm::dvec3 y = glm::cross(z, x);
  std::vector<glm::dvec3> c;
  const double cs = std::cos(kTurn), sn = std::sin(kTurn);
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 m((i & 1 ? 0.5 : -0.5) * kSize.x, (i & 2 ? 1.0 : 0.0) * kSize.y,
                       (i & 4 ? 0.5 : -0.5) * kSize.z);
    const glm::dvec3 world = glm::dvec3(cs * m.x + sn * m.z, m.y, -sn * m.x + cs * m.z) + at;
    const glm::dvec3 d = world - position;
    c.emplace_back(glm::dot(x, d), glm::dot(y, d), glm::dot(z, d));
  }
  return c;
}

const std::vector<double> kKZero = {kFx, 0, kCx, 0, 0, kFx, kCy, 0, 0, 0, 1, 0};  // K [I | 0]

TEST(KittiWriter, ALevelCamerasLabelHasTheClosedFormFields) {
  const glm::dvec3 position(0, 0.3, -3);
  const KittiFrame f = kittiFrame(described(sceneText(position, {0, 0.3, 0})));
  ASSERT_EQ(f.p2.size(), 12U);
  // K as the camera computes it, in float: fx and fy agree with 50 mm / 0.5625 mm to 1e-7.
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(f.p2[i], kKZero[i], 1e-5) << "P2[" << i << "]";
  ASSERT_EQ(f.labels.size(), 1U);
  const KittiLabel& l = f.labels[0];
  EXPECT_EQ(l.type, "Car");
  EXPECT_NEAR(l.h, 0.4, 1e-9);
  EXPECT_NEAR(l.w, 0.3, 1e-9);
  EXPECT_NEAR(l.l, 0.6, 1e-9);
  // The camera's right is world −x (forward +z × up +y); its down world −y.
  EXPECT_NEAR(l.x, -0.2, 1e-9);
  EXPECT_NEAR(l.y, 0.3, 1e-9);
  EXPECT_NEAR(l.z, 3.0, 1e-9);
  // The model's +x, turned 30° about up, is world (cos 30°, 0, −sin 30°), rect (−cos, 0, −sin):
  // rotation_y = atan2(sin 30°, −cos 30°) = 150°.
  EXPECT_NEAR(l.rotationY, 150.0 * std::numbers::pi / 180.0, 1e-9);
  EXPECT_NEAR(l.alpha, l.rotationY - std::atan2(-0.2, 3.0), 1e-9);
  EXPECT_EQ(l.truncated, 0.0);
  EXPECT_EQ(l.occluded, 3);  // no amodal channels: unknown
  EXPECT_TRUE(f.skipped.empty());
}

// A label line's fields are whitespace-separated: every whitespace character of the class
// name becomes '_' (found by probing: a tab and a newline in the name split the line).
TEST(KittiWriter, WhitespaceInTheClassNameBecomesUnderscores) {
  std::string text = sceneText({0, 0.3, -3}, {0, 0.3, 0});
  const std::string from = "class: Car";
  text.replace(text.find(from), from.size(), "class: \"traffic\\tcone\\nsmall big\"");
  const KittiFrame f = kittiFrame(described(text));
  ASSERT_EQ(f.labels.size(), 1U);
  EXPECT_EQ(f.labels[0].type, "traffic_cone_small_big");
}

// Looking 23° down: rect stays level (y along gravity), so the location is the height
// difference and the level distance; P2 = K [R_cam←rect | 0] projects the devkit's box as
// the true camera projects the true box.
TEST(KittiWriter, ATiltedCamerasP2ProjectsTheDevkitBoxAsTheCameraSeesTheBox) {
  const glm::dvec3 position(0, 1.5, -3), lookAt(0, 0.2, 0);
  const KittiFrame f = kittiFrame(described(sceneText(position, lookAt)));
  ASSERT_EQ(f.labels.size(), 1U);
  const KittiLabel& l = f.labels[0];
  EXPECT_NEAR(l.x, -0.2, 1e-9);
  EXPECT_NEAR(l.y, 1.5, 1e-9);
  EXPECT_NEAR(l.z, 3.0, 1e-9);
  EXPECT_NEAR(l.rotationY, 150.0 * std::numbers::pi / 180.0, 1e-9);
  const glm::dvec4 label = bounds(f.p2, devkitCorners(l));
  const glm::dvec4 truth = bounds(kKZero, trueCorners(position, lookAt));
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(label[i], truth[i], 1e-4) << "bound " << i;
  EXPECT_NEAR(l.left, truth.x, 1e-4);  // px: K in float (above)
  EXPECT_NEAR(l.top, truth.y, 1e-4);
  EXPECT_NEAR(l.right, truth.z, 1e-4);
  EXPECT_NEAR(l.bottom, truth.w, 1e-4);
  EXPECT_EQ(l.truncated, 0.0);
  // Not K [I | 0]: the rotation is the 23° tilt (P2's last row is rect's z in camera axes).
  EXPECT_NEAR(std::acos(f.p2[10]), std::atan2(1.3, 3.0), 1e-9);
}

TEST(KittiWriter, ABoxPartlyOutOfTheImageIsTruncatedAndClipped) {
  // 1.2 m to the camera's left at 3 m: the box's 2-D bounds cross the left edge.
  const glm::dvec3 position(0, 0.3, -3);
  const KittiFrame f = kittiFrame(described(sceneText(position, {0, 0.3, 0}, {1.2, 0, 0})));
  ASSERT_EQ(f.labels.size(), 1U);
  const KittiLabel& l = f.labels[0];
  const glm::dvec4 truth = bounds(kKZero, trueCorners(position, {0, 0.3, 0}, {1.2, 0, 0}));
  ASSERT_LT(truth.x, -0.5);
  ASSERT_GT(truth.z, -0.5);
  EXPECT_EQ(l.left, 0.0);
  EXPECT_NEAR(l.right, truth.z, 1e-4);
  const double inside = (truth.z + 0.5) / (truth.z - truth.x);  // the rows are all inside
  EXPECT_NEAR(l.truncated, 1.0 - inside, 1e-5);
}

TEST(KittiWriter, ABoxBehindTheCameraIsLeftOutSaying) {
  const KittiFrame f = kittiFrame(described(sceneText({0, 0.3, 2}, {0, 0.3, 5})));
  EXPECT_TRUE(f.labels.empty());
  ASSERT_EQ(f.skipped.size(), 1U);
  EXPECT_NE(f.skipped[0].find("behind the camera"), std::string::npos) << f.skipped[0];
}

// occluded from the masks: of 20 amodal pixels 20 or 19 visible (≥ 0.95) → 0; 18 … 10
// (≥ 0.5) → 1; 9 → 2.
TEST(KittiWriter, OccludedIsTheVisibleFractionsClass) {
  for (const auto& [visible, want] :
       {std::pair{20, 0}, {19, 0}, {18, 1}, {12, 1}, {10, 1}, {9, 2}}) {
    CaptureResult r = described(sceneText({0, 0.3, -3}, {0, 0.3, 0}));
    r.aovs = Image(kW, kH, {"amodal_1.A", "visible_1.A"});
    for (int x = 0; x < 20; ++x) {
      r.aovs.at(x, 0, 0) = 1.0f;
      r.aovs.at(x, 0, 1) = x < visible ? 0.75f : 0.25f;  // coverage ≥ ½ counts
    }
    const KittiFrame f = kittiFrame(r);
    ASSERT_EQ(f.labels.size(), 1U);
    EXPECT_EQ(f.labels[0].occluded, want) << visible << " of 20 visible";
  }
}

// Two objects' `occluded` from one pass over the masks (20 amodal pixels each, 19 and 9 of
// them visible), and the run's models (PoseModels: each shape's box alone) give the labels
// that the models made here give.
TEST(KittiWriter, EveryObjectsOccludedFromOnePassWithTheRunsModels) {
  std::string text = sceneText({0, 0.3, -3}, {0, 0.3, 0});
  text.replace(text.find("}]\nlights"), 2,
               "}, {translate: [-0.4, 0, 0.5], scale: [0.6, 0.4, 0.3]}]");
  CaptureResult r = described(text);
  r.aovs = Image(kW, kH, {"amodal_1.A", "visible_1.A", "amodal_2.A", "visible_2.A"});
  for (int x = 0; x < 20; ++x) {
    r.aovs.at(x, 0, 0) = 1.0f;
    r.aovs.at(x, 0, 1) = x < 19 ? 1.0f : 0.0f;
    r.aovs.at(x, 1, 2) = 1.0f;
    r.aovs.at(x, 1, 3) = x < 9 ? 1.0f : 0.0f;
  }
  const PoseModels models(r.description);
  const KittiFrame made = kittiFrame(r), given = kittiFrame(r, models.ownOfShape());
  ASSERT_EQ(made.labels.size(), 2U);
  ASSERT_EQ(given.labels.size(), 2U);
  EXPECT_EQ(given.labels[0].occluded, 0);
  EXPECT_EQ(given.labels[1].occluded, 2);
  for (std::size_t i = 0; i < 2; ++i) {
    const KittiLabel &a = made.labels[i], &b = given.labels[i];
    EXPECT_EQ(a.occluded, b.occluded) << i;
    for (const auto& [u, v] : {std::pair{a.h, b.h},
                               {a.w, b.w},
                               {a.l, b.l},
                               {a.x, b.x},
                               {a.y, b.y},
                               {a.z, b.z},
                               {a.left, b.left},
                               {a.right, b.right}})
      EXPECT_EQ(u, v) << i;
  }
}

// Looking straight down from 3 m up with the image's top towards world +z (`up`): rect's
// forward is where the image's top faces — the limit of a camera tilted ever further down —
// so a box 0.6 m that way is 0.6 m ahead (the wrong limit puts it behind and leaves it out),
// and the 90° tilt gets its note.
TEST(KittiWriter, AStraightDownCamerasRectLooksWhereTheImagesTopFaces) {
  std::string text = sceneText({0.2, 3, -0.6}, {0.2, 0, -0.6});
  text.replace(text.find("resolution:"), 0, "up: [0, 0, 1], ");
  const KittiFrame f = kittiFrame(described(text));
  ASSERT_EQ(f.labels.size(), 1U);
  const KittiLabel& l = f.labels[0];
  EXPECT_NEAR(l.x, 0.0, 1e-9);
  EXPECT_NEAR(l.y, 3.0, 1e-9);
  EXPECT_NEAR(l.z, 0.6, 1e-9);
  EXPECT_NEAR(l.rotationY, 150.0 * std::numbers::pi / 180.0, 1e-9);
  ASSERT_EQ(f.skipped.size(), 1U);
  EXPECT_NE(f.skipped[0].find("90° off level"), std::string::npos) << f.skipped[0];
}

// A rolled camera is off level too (found by probing: only the forward axis's pitch was
// measured, so an 11.3° roll, P2 no longer K, got no note); a level one gets none.
TEST(KittiWriter, ARolledCameraIsOffLevel) {
  std::string text = sceneText({0, 0.3, -2}, {0, 0.3, 2});
  EXPECT_TRUE(kittiFrame(described(text)).skipped.empty());
  text.replace(text.find("resolution:"), 0, "up: [0.2, 1, 0], ");
  const KittiFrame f = kittiFrame(described(text));
  ASSERT_EQ(f.skipped.size(), 1U);
  EXPECT_NE(f.skipped[0].find("11.3° off level"), std::string::npos) << f.skipped[0];
}

// A frame whose one box is left out still writes its three files, the label file empty.
TEST(KittiWriter, AFrameWithoutLabelsWritesAnEmptyLabelFile) {
  CaptureResult r = described(sceneText({0, 0.3, 2}, {0, 0.3, 5}));
  const camsim::test::TempDir dir;
  camsim::test::writeFile(dir.path() / (r.description.name + ".png"), "png");
  std::vector<std::string> notes;
  const auto files = writeKittiFrame(r, {}, dir.path(), 7, &notes);
  EXPECT_EQ(files.size(), 3U);
  EXPECT_EQ(camsim::test::readFile(dir.path() / "kitti/image_2/000007.png"), "png");
  EXPECT_EQ(camsim::test::readFile(dir.path() / "kitti/label_2/000007.txt"), "");
  EXPECT_EQ(camsim::test::readFile(dir.path() / "kitti/calib/000007.txt").substr(0, 4), "P0: ");
  ASSERT_EQ(notes.size(), 1U);
  EXPECT_NE(notes[0].find("behind the camera"), std::string::npos);
}

// A labelled shape whose keyframes scale it has no rigid pose: refused before rendering.
TEST(KittiWriter, AShapeWithoutARigidPoseIsRefusedBeforeRendering) {
  std::string text = sceneText({0, 0.3, -3}, {0, 0.3, 0});
  text.replace(text.find("    instances:"), std::string::npos,
               "    name: grower\n"
               "    motion: [{time: 0, scale: 0.3}, {time: 1, scale: 0.6}]\n");
  const SceneDescription d = loadSceneFromText(text, "grow.yaml", ".");
  try {
    checkPoseExports(d);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("grower"), std::string::npos) << e.what();
  }
}

}  // namespace kitti_writer_test
}  // namespace camsim
