// Camera metadata of a capture or a sequence, in the formats SfM and NeRF tools read,
// written beside the frames (one OutputSet: all files at once):
//
//   cameras.json             every frame: intrinsics (OpenCV), the camera model and its
//                            coefficients (camera_export.h), world-from-camera
//                            in the OpenCV (x right, y down, z forward) and OpenGL/Blender
//                            (x right, y up, z backward) conventions, exposure (T, N, ISO,
//                            gain), the frame's reference time and its rows' readout times
//   transforms.json          NeRF (instant-ngp, nerfstudio): camera_model (OPENCV,
//                            OPENCV_FISHEYE, EQUIRECTANGULAR), fl_x, fl_y, cx, cy, its
//                            coefficients, w, h, camera_angle_x; frames[].file_path,
//                            transform_matrix (OpenGL camera-to-world)
//   colmap/cameras.txt, images.txt, points3D.txt (empty)   a COLMAP text model (OPENCV,
//                            FULL_OPENCV or OPENCV_FISHEYE)
// A model nerfstudio or COLMAP cannot express (camera_export.h) leaves its export out:
// cameras.json's `not_written` and the caller's `skipped` say which and why.
//   annotations.json         COCO (with the instance_id AOV): images, categories (the
//                            classes), per visible labelled instance and frame its box, the
//                            box of its projected 3-D bounds and its RLE mask (annotations.h)
//
// The pose is the camera's at the frame's reference time: the centre of its shutter
// window (of row 0 for a rolling shutter; row r is read out r · row_time later). World is
// the scene file's frame (render space plus the render origin). Pixel coordinates: OpenCV's
// cx, cy put pixel centres at integers (cameras.json); COLMAP and NeRF put the image's
// corner at 0, so their cx, cy are OpenCV's + 0.5.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "integrator/camera/physical_camera.h"
#include "integrator/capture/annotations.h"
#include "integrator/capture/capture.h"

namespace camsim {

struct DatasetFrame {
  std::string image;              // the frame's picture, relative to the directory
  PhysicalCameraParams camera;    // the frame's camera (its shutter moved to the frame)
  glm::dvec3 renderOrigin{0.0};   // world = render + origin
  double isoValue = 0.0;          // 0 without a sensor
  double systemGainDnPerE = 0.0;  // 0 without a sensor
  double exposureTimeS = 0.0;     // of the developed frame
  bool annotated = false;         // rendered with the instance_id AOV
  std::vector<InstanceAnnotation> annotations;
};

DatasetFrame datasetFrame(const CaptureResult& result);

// World-from-camera at the frame's reference time, OpenCV axes (columns x right, y down,
// z forward, position), world coordinates; camera is PhysicalCamera(frame.camera).
glm::dmat4 worldFromCameraOpenCv(const DatasetFrame& frame, const PhysicalCamera& camera);

// Writes cameras.json, transforms.json and colmap/*.txt into directory; returns the files.
// skipped (if given) receives a line per export left out.
std::vector<std::filesystem::path> writeDatasetMetadata(
    const std::vector<DatasetFrame>& frames, const std::filesystem::path& directory,
    std::vector<std::string>* skipped = nullptr);

}  // namespace camsim
