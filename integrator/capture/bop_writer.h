// The BOP layout (the 6-DoF pose benchmark's; thodan/bop_toolkit, docs/bop_datasets_format.md)
// of a capture or a sequence, selected by the scene's `exports: [bop]` and written under the
// capture's output directory (docs/output.md, "BOP layout"):
//
//   bop/models/obj_NNNNNN.ply       each obj_id's model (object_poses.h's model frame), ASCII
//                                   PLY in mm: x y z, angle-weighted vertex normals, triangles
//   bop/models/models_info.json     per obj_id: diameter, min_x/y/z, size_x/y/z (mm)
//   bop/train_pbr/SSSSSS/           one BOP scene: a capture is image 0, a sequence one image
//                                   per frame (image id = its sequence frame number)
//     scene_camera.json             per image: cam_K (px, pixel centres at integers), cam_R_w2c,
//                                   cam_t_w2c (mm; world = the scene file's), depth_scale (mm)
//     scene_gt.json                 per image, per labelled shape: obj_id, cam_R_m2c (row-major),
//                                   cam_t_m2c (mm), at the frame's reference time
//     scene_gt_info.json            per image and object: bbox_obj, bbox_visib ([x, y, w, h]
//                                   px, bop_toolkit's: w = x_max − x_min), px_count_all,
//                                   px_count_valid, px_count_visib, visib_fract
//     rgb/IIIIII.png                NAME.png, the capture's developed picture
//     depth/IIIIII.png              16-bit: depth (mm) / depth_scale, rounded; 0 where nothing
//                                   was hit
//     mask/IIIIII_GGGGGG.png        amodal mask of annotation GGGGGG (0/255)
//     mask_visib/IIIIII_GGGGGG.png  its visible mask (0/255)
//
// | quantity     | unit | rule |
// |--------------|------|------|
// | obj_id       | —    | the shape's class number (scene_ids.h: an integer class itself, a named class after the largest integer); every shape of one obj_id must have the same model (within 10⁻⁴ of its size), else InputError |
// | depth_scale  | mm   | the smallest of 0.1, 1, 10, … mm per unit that holds the image's largest depth in 16 bits |
// | mask         | —    | a pixel is in the mask when its coverage (amodal_<n>.A / visible_<n>.A) is ≥ 0.5 |
// | px_count_all | px   | pixels of the amodal mask (inside the image: camsim renders no margin) |
// | px_count_valid | px | pixels of the amodal mask with a depth value (depth PNG > 0) |
// | px_count_visib | px | pixels of the visible mask |
// | visib_fract  | —    | px_count_visib / px_count_all (0 when px_count_all is 0) |
// | bbox_*       | px   | [x_min, y_min, x_max − x_min, y_max − y_min] of the mask's pixels; [−1, −1, −1, −1] when empty |
// Scene id SSSSSS: 0 for `camsim render`, the item's index in a `camsim dataset` run (the
// items' scene folders gather under one train_pbr/ without renumbering). Without the amodal
// AOV's channels in the render, mask/, mask_visib/ and scene_gt_info.json are left out and a
// `skipped` line says so.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "integrator/capture/capture.h"
#include "integrator/capture/object_poses.h"
#include "sensor/io/json_writer.h"

namespace camsim {

inline constexpr double kMmPerM = 1000.0;  // BOP's lengths are in mm

// One model per obj_id of the scene's labelled shapes: the model of its first shape.
struct BopModel {
  std::uint32_t objId = 0;
  std::size_t shape = 0;  // the shape it was taken from
  ObjectModel model;
};

// Per shape of d: its obj_id's model among models (null for an unlabelled shape, or one
// whose obj_id models lacks): the models BOP's poses take (objectPoses), so that every shape
// of an obj_id gets the box of the model written for it.
std::vector<const ObjectModel*> bopShapeModels(const SceneDescription& d,
                                               const std::vector<BopModel>& models);

// The models a run's pose exports pose its frames with, made once, before the run renders
// (CaptureRunWriter's constructor, from the scene: a capture changes its frames' cameras,
// never their shapes), and handed to both writers, so that neither remakes them per frame:
//   bop()         with `exports: [bop]`: one model per obj_id, its first shape's
//   bopOfShape()  per shape: its obj_id's model (bopShapeModels), for BOP's poses
//   ownOfShape()  per shape: its own model's box alone (no vertices), for KITTI's h, w, l
// Making it checks the scene as checkPoseExports does: every labelled shape has a rigid pose
// (objectModel), and with `exports: [bop]` the shapes of one obj_id have one model (within
// 10⁻⁴ of its size) — InputError (naming `exports` and both shapes) otherwise. Empty for a
// scene without either export. Not copyable: the per-shape tables point into it (a move
// keeps them valid).
class PoseModels {
 public:
  PoseModels() = default;
  explicit PoseModels(const SceneDescription& d);
  PoseModels(const PoseModels&) = delete;
  PoseModels& operator=(const PoseModels&) = delete;
  PoseModels(PoseModels&&) = default;
  PoseModels& operator=(PoseModels&&) = default;
  ~PoseModels() = default;

  const std::vector<BopModel>& bop() const { return bop_; }
  std::span<const ObjectModel* const> bopOfShape() const { return bopOfShape_; }
  std::span<const ObjectModel* const> ownOfShape() const { return ownOfShape_; }

 private:
  std::vector<BopModel> bop_;
  std::vector<ObjectModel> boxes_;  // per shape: its model's box and rounding alone
  std::vector<const ObjectModel*> bopOfShape_, ownOfShape_;
};

// The models of reference and other that share an obj_id and differ (within 10⁻⁴ of the
// model's size, as the shapes of one scene must agree): the first such pair in obj_id
// order, or nulls. obj_ids only one side has are not compared. A dataset's items are one
// BOP dataset (their train_pbr/ scenes gather under one models/), so it compares items.
struct DifferentBopModels {
  const BopModel* reference = nullptr;
  const BopModel* other = nullptr;
};
DifferentBopModels firstDifferentBopModels(const std::vector<BopModel>& reference,
                                           const std::vector<BopModel>& other);

// What the models_info.json entry of a model holds (mm): the largest distance between two
// of its vertices, and its box.
struct BopModelInfo {
  double diameter = 0.0;
  glm::dvec3 min{0.0}, size{0.0};
};
BopModelInfo bopModelInfo(const ObjectModel& model);

// bop/models/: obj_NNNNNN.ply per model and models_info.json, into directory.
std::vector<std::filesystem::path> writeBopModels(const std::vector<BopModel>& models,
                                                  const std::filesystem::path& directory);

// The 16-bit depth step (mm) for a largest depth of maxDepthMm.
double bopDepthScale(double maxDepthMm);

// The BOP scene of one capture or sequence, written as its frames arrive.
class BopWriter {
 public:
  // directory: the capture's output directory (bop/ is made in it); sceneId: SSSSSS;
  // models: the run's (PoseModels of the frames' scene), kept by address: it must outlive
  // the writer.
  BopWriter(std::filesystem::path directory, int sceneId, const PoseModels& models);
  // Writes the frame's rgb, depth and masks (its picture NAME.png must be in the directory
  // already) and keeps its JSON entries. imageId: 0 for a capture, a sequence's frame number.
  std::vector<std::filesystem::path> addFrame(const CaptureResult& result, int imageId);
  // Writes the models and the scene's JSON files.
  std::vector<std::filesystem::path> finish();
  // What was left out, a line each (no amodal AOV: no masks).
  const std::vector<std::string>& skipped() const { return skipped_; }

 private:
  std::filesystem::path directory_, scene_;
  const PoseModels* models_;
  bool masks_ = true;  // every frame so far had the amodal channels
  JsonObject camera_, gt_, gtInfo_;
  std::vector<std::string> skipped_;
};

// A capture's whole BOP scene (image 0): addFrame and finish; skipped lines appended.
// models: PoseModels(result.description), made by the caller.
std::vector<std::filesystem::path> writeBop(const CaptureResult& result, const PoseModels& models,
                                            const std::filesystem::path& directory, int sceneId,
                                            std::vector<std::string>* skipped = nullptr);

// The scene's BOP and KITTI exports checked before anything renders — every labelled shape
// has a rigid pose (objectModel), and BOP's models of one obj_id agree: InputError
// otherwise (PoseModels(d), made and dropped). Nothing for a scene without either export.
// For what writes no pose exports (a tile part, a Python capture, a dataset's check of all
// its items): a run that writes them makes the models it keeps (CaptureRunWriter), the same
// check.
void checkPoseExports(const SceneDescription& d);

}  // namespace camsim
