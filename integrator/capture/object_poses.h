// 6-DoF object poses of a frame (issue 40), for the pose-dataset exports (BOP:
// bop_writer.h): for each labelled shape (a shape with a `class:`), the rigid transform
// from its model frame to the camera at the frame's reference time, and its model.
//
// | field        | unit | convention |
// |--------------|------|------------|
// | rotation R   | —    | model → camera, OpenCV camera axes (x right, y down, z forward); a proper rotation |
// | translation t| m    | the model origin in camera coordinates: p_cam = R · p_model + t |
// | boxMin/Max   | m    | the model's axis-aligned 3-D bounding box in model coordinates |
// | time         | s    | the frame's reference time: the shutter window's centre (of row 0 for a rolling shutter), as cameras.json's poses |
//
// The model frame — the same for every instance of a mesh, so that one model serves them
// all (ShapeDescription::objectFromModel):
//   mesh file        its vertices × the shape's `scale` (m); the shape's `translate` is pose
//   inline vertices, rectangle   the coordinates as written (m)
//   instances:       the shared mesh's: the file's vertices × `scale` (the shape's
//                    `translate` and each instance's placement are pose)
//   glTF primitive   its POSITION accessor's coordinates
//   sphere           centred on the sphere's centre, axes parallel to the scene's
//                    (a 32 × 16 latitude–longitude tessellation of the sphere as the model)
// A pose is a rotation and a translation: whatever else maps the model to the scene — an
// instance's or a glTF node's scale, shear or mirroring (the polar decomposition L = R·S
// of the placement's 3×3 part L, R proper), a motion's keyframe scale (the same at every
// key) — is baked into the model's vertices (S·v). A shape whose keyframes scale it
// differently over time has no rigid pose: objectModel throws InputError.
// A moving shape is posed at the frame's reference time (its keyframed motion there).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "integrator/camera/physical_camera.h"
#include "integrator/scene/scene_description.h"
#include "sensor/base/input_error.h"

namespace camsim {

// A shape's model: triangles in its model frame (m).
struct ObjectModel {
  std::vector<glm::dvec3> vertices;     // m
  std::vector<std::uint32_t> indices;   // three per triangle, the rendered winding
  glm::dvec3 boxMin{0.0}, boxMax{0.0};  // m, the vertices' bounds
  // m: how far the vertices may be off from the float positions they were made from (a
  // float's rounding at the largest stored coordinate, through the model's scale): two
  // copies of one mesh placed far apart differ by about this much.
  double rounding = 0.0;
};

// The coverage at which a pixel is in an object's mask (the amodal aov's amodal_<n>.A and
// visible_<n>.A): BOP's mask PNGs and pixel counts, KITTI's `occluded`.
inline constexpr double kMaskCoverage = 0.5;

struct ObjectPose {
  std::size_t shape = 0;                // index into SceneDescription::shapes
  std::uint32_t instance = 0;           // shape + 1: the instance number (scene_ids.h, AOV names)
  std::uint32_t classNumber = 0;        // the class's number (scene_ids.h: the class_id value)
  glm::dmat3 rotation{1.0};             // model → camera (OpenCV axes)
  glm::dvec3 translation{0.0};          // m
  glm::dvec3 boxMin{0.0}, boxMax{0.0};  // m, model coordinates
};

// Where the pose exports' input errors point: the scene's `exports` key (the scene file
// alone when it has none).
SourceLocation exportsPlace(const SceneDescription& d);

// The model of d.shapes[shape] (labelled or not). Throws InputError naming the shape when
// its motion's keyframes scale it differently (no rigid pose).
ObjectModel objectModel(const SceneDescription& d, std::size_t shape);

// The rigid model → render-space transform of s at time t (render space: world minus
// SceneDescription::renderOrigin).
glm::dmat4 renderFromModel(const ShapeDescription& s, double t);

// Render space from camera at time t in OpenCV axes (columns: x right, y down, z forward,
// the position; m): the camera's pose (columns right, up, forward, position) with its y
// axis turned down. The one definition of the camera's OpenCV pose: object poses, BOP's
// cam_R_w2c, KITTI's rect frame and the datasets' world_from_camera_opencv
// (dataset_writer.h) all derive from it.
glm::dmat4 renderFromCameraCv(const PhysicalCamera& camera, double t);

// Camera (OpenCV axes) from render space at time t: renderFromCameraCv's inverse.
glm::dmat4 cameraCvFromRender(const PhysicalCamera& camera, double t);

// The poses of every labelled shape of d, in shape order, with `camera` (a frame's camera:
// description.camera of a capture or of a sequence's frame) at its reference time. models:
// the models already made, so that none is rebuilt (a run's writers pose every frame from
// one table, PoseModels: bop_writer.h): models[i] is d.shapes[i]'s model or one standing for
// it (BOP: its obj_id's; KITTI: its box alone), null for an unlabelled shape (size:
// d.shapes.size()), or empty. A pose's box is its model's. A labelled shape given null, or
// no models at all, has its model made here.
std::vector<ObjectPose> objectPoses(const SceneDescription& d, const PhysicalCameraParams& camera,
                                    std::span<const ObjectModel* const> models);

}  // namespace camsim
