// The KITTI object layout (the KITTI Vision Benchmark's 3-D object detection devkit,
// readme.txt) of a capture or a sequence, selected by the scene's `exports: [kitti]` and
// written under the capture's output directory, one image per frame (image id IIIIII = the
// sequence frame number; for a capture the dataset item's index, 0 for a render, so the
// kitti/ folders of a dataset's single-capture items merge by copying):
//
//   kitti/image_2/IIIIII.png   NAME.png, the developed picture
//   kitti/calib/IIIIII.txt     P0, P1, P2, P3 (3×4, row-major), R0_rect (3×3), Tr_velo_to_cam,
//                              Tr_imu_to_velo (3×4): one camera, so P0 = P1 = P2 = P3; no
//                              lidar or IMU, so both Tr are [I | 0]
//   kitti/label_2/IIIIII.txt   one line per labelled shape in front of the camera and in
//                              the image:
//                              type truncated occluded alpha left top right bottom h w l x y z
//                              rotation_y
//
// Coordinates: KITTI's rectified camera frame ("rect"): y down along gravity, z forward
// level, x right (camsim's world has +y up); for a level camera it is the camera's OpenCV
// frame and P2 = K [I | 0]. For a camera that looks up or down, rect is the camera frame
// turned level about its x axis and back, R0_rect = I, and P2 = K [R_cam←rect | 0], so that
// a KITTI reader's x_img = P2 · X_rect holds.
//
// | field        | unit | rule |
// |--------------|------|------|
// | type         | —    | the shape's class name (spaces as '_'); an integer class as `Class<n>` |
// | h, w, l      | m    | the model's box (object_poses.h's model frame) along its y (up), z, x |
// | x, y, z      | m    | the box's bottom centre (model y at its minimum) in rect coordinates |
// | rotation_y   | rad  | about rect's y: the model's +x axis in rect is (cos r, ·, −sin r); [−π, π] |
// | alpha        | rad  | rotation_y − atan2(x, z), wrapped to [−π, π] |
// | left … bottom| px   | the KITTI box's 8 corners (as a devkit reader builds them from h, w, l, x, y, z, rotation_y) through P2, their bounds clipped to the image [0, W − 1] × [0, H − 1] (pixel centres at integers) |
// | truncated    | —    | 1 − area(box ∩ image) / area(box) of those bounds before the clip |
// | occluded     | —    | from the masks' visible fraction v (amodal aov, bop_writer.h's rule): 0 if v ≥ 0.95, 1 if v ≥ 0.5, 2 below; 3 (unknown) without the amodal channels |
// A shape whose model is not upright (its y not within 10° of world up) is labelled with its
// box turned into rect regardless (a note says which); one with a corner of its box nearer
// than 0.1 m along the camera's or rect's z is left out with a note; one whose clipped box
// would be empty, silently. A camera more than 1° off level gets a note: P2 = K R, so
// readers that take K from P2's entries need a level camera.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "integrator/capture/capture.h"
#include "integrator/capture/object_poses.h"

namespace camsim {

// One KITTI label line's values (the table above).
struct KittiLabel {
  std::string type;
  double truncated = 0.0;
  int occluded = 3;
  double alpha = 0.0;
  double left = 0.0, top = 0.0, right = 0.0, bottom = 0.0;  // px
  double h = 0.0, w = 0.0, l = 0.0;                         // m
  double x = 0.0, y = 0.0, z = 0.0;                         // m, rect
  double rotationY = 0.0;                                   // rad
};

// The labels of a frame (capture result) and its P2 (3×4, row-major: P[r][c] = p[4r + c]).
struct KittiFrame {
  std::vector<KittiLabel> labels;
  std::vector<double> p2;  // 12
  std::vector<std::string> skipped;
};
// models: what objectPoses takes, each labelled shape's own model (a run's
// PoseModels::ownOfShape, bop_writer.h: its box alone); empty: each made here.
KittiFrame kittiFrame(const CaptureResult& result, std::span<const ObjectModel* const> models = {});

// Writes kitti/image_2, calib and label_2 files of the frame into directory (NAME.png must
// be there already); skipped lines appended. models: as kittiFrame's.
std::vector<std::filesystem::path> writeKittiFrame(const CaptureResult& result,
                                                   std::span<const ObjectModel* const> models,
                                                   const std::filesystem::path& directory,
                                                   int imageId,
                                                   std::vector<std::string>* skipped = nullptr);

}  // namespace camsim
