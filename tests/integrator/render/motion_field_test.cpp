// The motion field (aov motion; integrator/render/aov_film.h) against analytic motion: a
// translating plane, a plane spinning about the optical axis, a camera moving past a static
// plane; and reprojection consistency: on a static scene seen by a moving, turning camera,
// frame k's pixels warped by their depth and the two frames' poses land within 0.05 px of
// where the forward vectors put them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "tests/support/render_frame.h"
#include "tests/support/scene_text.h"

namespace camsim {
namespace {

using test::num;

constexpr int kFieldRes = 32;
constexpr double kRate = 10.0, kDt = 1.0 / kRate;
// fx = f / pitch = 20 mm / (24 mm / 32) px.
constexpr double kFx = 0.020 / (0.024 / kFieldRes), kC = 0.5 * kFieldRes - 0.5;

// Frames at 10 Hz with a 3.6° shutter (1 ms: little blur within a frame); the camera looks
// along −z with +y up, so image right is world +x and image down is world −y.
SceneDescription scene(const std::string& shapes, const std::string& camera = "",
                       const std::string& aovs = "[motion, depth]") {
  const std::string text =
      "camera: {position: [0, 0, 0], look_at: [0, 0, -1], up: [0, 1, 0], resolution: [" +
      std::to_string(kFieldRes) + ", " + std::to_string(kFieldRes) +
      "], sensor_width_mm: 24, sensor_height_mm: 24, focal_length_mm: 20" + camera +
      "}\n"
      "render: {spp: 64, max_depth: 1, aovs: " +
      aovs +
      "}\n"
      "frames: {count: 3, rate_hz: " +
      num(kRate) +
      ", shutter_angle_deg: 3.6}\n"
      "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
      "shapes:\n" +
      shapes + "lights:\n  - {type: point, position: [0, 0, 0], intensity: 1}\n";
  return loadSceneFromText(text, "motion.yaml", ".");
}

double flowAt(const Image& im, int x, int y, const char* channel) {
  return static_cast<double>(im.at(x, y, im.channelIndex(channel)));
}

const char* kPlane =
    "  - {name: plane, type: rectangle, corner: [-20, -20, -2], edge_u: [40, 0, 0], edge_v: [0, "
    "40, 0], material: grey";

// A plane at 2 m moving +x at 0.5 m/s: every point moves 5 cm per frame, imaged
// fx · 0.05 / 2 px to the right; scene flow (0.05, 0, 0) m; backward the opposite.
TEST(MotionField, TranslatingPlane) {
  const double v = 0.5;
  const SceneDescription d = scene(std::string(kPlane) +
                                   ", motion: [{time: 0, translate: [0, 0, 0]}, {time: 1, "
                                   "translate: [" +
                                   num(v) + ", 0, 0]}]}\n");
  const Image a = test::renderSequenceFrame(d, 1).aovs;
  const double shift = kFx * v * kDt / 2.0;
  for (int y = 0; y < kFieldRes; ++y)
    for (int x = 0; x < kFieldRes; ++x) {
      ASSERT_NEAR(flowAt(a, x, y, "motion_fw.X"), shift, 1e-4) << x << "," << y;
      ASSERT_NEAR(flowAt(a, x, y, "motion_fw.Y"), 0.0, 1e-4);
      ASSERT_NEAR(flowAt(a, x, y, "motion_bw.X"), -shift, 1e-4);
      ASSERT_NEAR(flowAt(a, x, y, "flow_fw.X"), v * kDt, 1e-6);
      ASSERT_NEAR(flowAt(a, x, y, "flow_fw.Z"), 0.0, 1e-6);
      ASSERT_NEAR(flowAt(a, x, y, "flow_bw.X"), -v * kDt, 1e-6);
    }
}

// The plane spinning about the optical axis at 0.5 rad/s (0.05 rad per frame): in the
// image (y down) a point at q from the principal point moves to R(−θ) q, so the forward
// vector at the pixel centre q is (R(−θ) − I) q — linear in q, so its footprint mean is
// the centre's value.
TEST(MotionField, SpinningPlane) {
  const double omega = 0.5;
  const SceneDescription d = scene(
      std::string(kPlane) +
      ", motion: [{time: 0, rotate: {axis: [0, 0, 1], angle_deg: 0}}, {time: 0.1, rotate: "
      "{axis: [0, 0, 1], angle_deg: " +
      num(omega * 0.1 * 180.0 / M_PI) +
      "}}, {time: 0.2, rotate: {axis: [0, 0, 1], angle_deg: " + num(omega * 0.2 * 180.0 / M_PI) +
      "}}, {time: 0.3, rotate: {axis: [0, 0, 1], angle_deg: " + num(omega * 0.3 * 180.0 / M_PI) +
      "}}]}\n");
  const Image a = test::renderSequenceFrame(d, 1).aovs;
  const double th = omega * kDt, c = std::cos(th), s = std::sin(th);
  double worst = 0.0;
  for (int y = 0; y < kFieldRes; ++y)
    for (int x = 0; x < kFieldRes; ++x) {
      const double qx = x - kC, qy = y - kC;
      // World rotation by +θ about +z is, in image axes (x right, y down), a rotation by −θ.
      const double ex = (c * qx + s * qy) - qx, ey = (-s * qx + c * qy) - qy;
      const double err = std::max(std::abs(flowAt(a, x, y, "motion_fw.X") - ex),
                                  std::abs(flowAt(a, x, y, "motion_fw.Y") - ey));
      worst = std::max(worst, err);
      ASSERT_LT(err, 0.02) << x << "," << y << ": expected " << ex << ", " << ey;
      const double bx = (c * qx - s * qy) - qx, by = (s * qx + c * qy) - qy;
      ASSERT_NEAR(flowAt(a, x, y, "motion_bw.X"), bx, 0.02);
      ASSERT_NEAR(flowAt(a, x, y, "motion_bw.Y"), by, 0.02);
    }
  std::printf("spinning plane: worst forward-vector error %.4f px\n", worst);
}

// The camera moving +x at 0.5 m/s past a static plane at 2 m: the image moves left by
// fx · 0.05 / 2 px per frame; the scene flow of a static plane is 0; camera-axes normals
// (taken per sample for a moving camera) point back along −z.
TEST(MotionField, MovingCamera) {
  const SceneDescription d =
      scene(std::string(kPlane) + "}\n",
            ", motion: [{time: 0, translate: [0, 0, 0]}, {time: 1, translate: [0.5, 0, 0]}]",
            "[motion, depth, normal]");
  const Image a = test::renderSequenceFrame(d, 1).aovs;
  const double shift = kFx * 0.05 / 2.0;
  for (int y = 0; y < kFieldRes; ++y)
    for (int x = 0; x < kFieldRes; ++x) {
      ASSERT_NEAR(flowAt(a, x, y, "motion_fw.X"), -shift, 1e-4);
      ASSERT_NEAR(flowAt(a, x, y, "motion_bw.X"), shift, 1e-4);
      ASSERT_NEAR(flowAt(a, x, y, "motion_fw.Y"), 0.0, 1e-4);
      ASSERT_EQ(flowAt(a, x, y, "flow_fw.X"), 0.0);
      // The camera moves: its axes per sample. The plane faces it: −z in OpenCV axes.
      ASSERT_NEAR(flowAt(a, x, y, "Ng_cam.Z"), -1.0, 1e-6);
      ASSERT_NEAR(flowAt(a, x, y, "Ng_cam.X"), 0.0, 1e-6);
    }
}

// Reprojection: a static sphere before a tilted plane, the camera moving and turning. Each
// interior pixel of frame 1 is lifted by its depth through frame 1's pose and intrinsics
// and projected with frame 2's; it must land where motion_fw says within 0.05 px.
TEST(MotionField, ReprojectionAgreesWithForwardVectors) {
  const SceneDescription d = scene(
      "  - {name: wall, type: rectangle, corner: [-20, -20, -6], edge_u: [40, 0, 0], edge_v: "
      "[0, 40, -8], material: grey}\n"
      "  - {name: ball, type: sphere, centre: [0.2, -0.1, -3], radius: 0.6, material: grey}\n",
      ", motion: [{time: 0, translate: [0, 0, 0]}, {time: 1, translate: [0.4, 0.1, -0.3], "
      "rotate: {axis: [0, 1, 0.2], angle_deg: 20}}]");
  const Image a = test::renderSequenceFrame(d, 1).aovs;
  const PhysicalCamera camera(d.frameCamera(1));
  const double t1 = d.frameCamera(1).shutter.centre(), t2 = d.frameCamera(2).shutter.centre();
  ASSERT_NEAR(t2 - t1, kDt, 1e-12);
  const glm::dvec4 k = camera.intrinsics();
  const glm::dmat4 pose = camera.worldFromCameraAt(t1);
  double worst = 0.0;
  int checked = 0;
  for (int y = 1; y + 1 < kFieldRes; ++y)
    for (int x = 1; x + 1 < kFieldRes; ++x) {
      // Skip the silhouette: pixels whose depth differs from a neighbour's by over 5 %.
      const double z = flowAt(a, x, y, "depth.Z");
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          edge = edge || std::abs(flowAt(a, x + dx, y + dy, "depth.Z") - z) > 0.05 * z;
      if (edge) continue;
      // OpenCV back-projection: camera axes x right, y down, z forward.
      const glm::dvec3 cv((x - k.z) / k.x * z, (y - k.w) / k.y * z, z);
      const glm::dvec3 world = glm::dvec3(pose[3]) + cv.x * glm::dvec3(pose[0]) -
                               cv.y * glm::dvec3(pose[1]) + cv.z * glm::dvec3(pose[2]);
      const std::optional<glm::dvec2> q = camera.project(world, t2);
      ASSERT_TRUE(q);
      const double err = std::max(std::abs(q->x - x - flowAt(a, x, y, "motion_fw.X")),
                                  std::abs(q->y - y - flowAt(a, x, y, "motion_fw.Y")));
      worst = std::max(worst, err);
      ++checked;
      EXPECT_LT(err, 0.05) << x << "," << y;
    }
  EXPECT_GT(checked, kFieldRes * kFieldRes / 2);
  std::printf("reprojection: %d pixels, worst %.4f px\n", checked, worst);
}

// Every AOV, ids and motion among them, the same bytes on 1 and 2 threads.
TEST(MotionField, AllAovsBitIdenticalAcrossThreadCounts) {
  const SceneDescription d = scene(
      "  - {name: wall, type: rectangle, corner: [-20, -20, -6], edge_u: [40, 0, 0], edge_v: "
      "[0, 40, -8], material: grey, class: 3}\n"
      "  - {name: ball, type: sphere, centre: [0.2, -0.1, -3], radius: 0.6, material: grey, "
      "class: ball, motion: [{time: 0, translate: [0, 0, 0]}, {time: 1, translate: [1, 0, 0]}]}\n",
      ", motion: [{time: 0, translate: [0, 0, 0]}, {time: 1, translate: [0.4, 0.1, -0.3]}]",
      "[depth, distance, position, normal, albedo, roughness, instance_id, class_id, "
      "material_id, motion]");
  const Image one = test::renderSequenceFrame(d, 1, 1).aovs,
              two = test::renderSequenceFrame(d, 1, 2).aovs;
  ASSERT_EQ(one.channels, two.channels);
  EXPECT_EQ(one.pixels, two.pixels);
  for (float v : one.pixels) ASSERT_TRUE(std::isfinite(v));
}

// Without a frames block there is no next frame: a clear error.
TEST(MotionField, NeedsAFramesBlock) {
  const std::string text =
      "camera: {position: [0, 0, 0], look_at: [0, 0, -1]}\n"
      "render: {aovs: [motion]}\n"
      "materials: {m: {type: diffuse, reflectance: 0.5}}\n"
      "shapes:\n  - {type: sphere, centre: [0, 0, -5], radius: 1, material: m}\n";
  try {
    loadSceneFromText(text, "m.yaml", ".");
    FAIL() << "accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("m.yaml:2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("frames"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace camsim
