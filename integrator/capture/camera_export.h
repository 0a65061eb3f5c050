// A camera's model in the terms of the tools that read camsim's exports (issue 36): one
// mapping from PhysicalCamera::projection() (integrator/camera/projection.h), used by every
// writer — cameras.json, transforms.json and colmap/ (dataset_writer.h), the sidecar
// NAME.json and the EXR header (capture_sidecar.cpp, capture_writer.cpp) and the Python
// `meta["pose"]` (python/capture_arrays.cpp).
//
// | camsim model    | cameras.json coefficients (OpenCV order)     | COLMAP 3.8      | nerfstudio      |
// |-----------------|----------------------------------------------|-----------------|-----------------|
// | opencv          | k1 k2 p1 p2 k3 k4 k5 k6 s1 s2 s3 s4 tau_x tau_y | OPENCV (k1 k2 p1 p2 only), FULL_OPENCV (+ k3…k6); none with s or τ | OPENCV (k1 k2 k3 p1 p2 only; its k4 is an r⁸ term, not OpenCV's) |
// | kannala_brandt  | k1 k2 k3 k4 (cv2.fisheye D)                  | OPENCV_FISHEYE  | OPENCV_FISHEYE  |
// | equidistant     | —                                            | OPENCV_FISHEYE (k = 0) | OPENCV_FISHEYE (k = 0) |
// | equisolid, stereographic, orthographic, ftheta | — / ftheta: k1…k4 | none            | none            |
// | unified         | xi k1 k2 p1 p2 (cv2.omnidir xi, D)           | none            | none            |
// | double_sphere   | xi alpha                                     | none            | none            |
// | equirectangular | —                                            | none            | EQUIRECTANGULAR (fl = π·fx: nerfstudio's f spans π rad) |
//
// COLMAP and nerfstudio put the image's corner at 0: their cx, cy are OpenCV's + ½. Where a
// tool has no exact model, `colmapLacks` / `nerfstudioLacks` say what it lacks and the
// writer leaves that export out (the exports are written by default, not requested).
// COLMAP's OPENCV_FISHEYE projects through X/Z: points behind the camera (θ > 90°) cannot
// be observations there, though the model's pixels are the same. A traced lens (camera.lens)
// has no closed-form model: its paraxial stand-in's fx … cy are written with `traced_lens`,
// and COLMAP and nerfstudio lack it.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "integrator/camera/physical_camera.h"
#include "sensor/io/json_writer.h"

namespace camsim {

struct CameraExport {
  std::string model;                                         // EnumNames<ProjectionModel>
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;             // OpenCV: pixel centres at integers
  std::vector<std::pair<std::string, double>> coefficients;  // the model's, OpenCV's order
  // rad; set where the model's valid domain ends inside the image (a corner unimaged)
  std::optional<double> maxFieldAngle;
  std::string colmapModel;           // empty: COLMAP cannot express the model
  std::vector<double> colmapParams;  // fx fy cx cy (corner-based) then the model's extras
  std::string colmapLacks;           // why not, when colmapModel is empty
  std::string nerfstudioModel;       // empty: nerfstudio cannot express the model
  std::vector<std::pair<std::string, double>> nerfstudio;  // fl_x fl_y cx cy and coefficients
  std::string nerfstudioLacks;
  // The horizontal field of view across the image width through the model (rad): the field
  // angles of the left and right edges' midpoints (row cy), or of the last imaged pixel
  // along that row where the image circle ends first; equirectangular W/fx.
  double cameraAngleX = 0.0;
  // A traced lens (camera.lens): fx … cy are its paraxial thin-lens stand-in's and the
  // image's distortion is the prescription's, which no tool's model expresses.
  bool tracedLens = false;
};

CameraExport cameraExport(const PhysicalCamera& camera);

// The model block of cameras.json, the sidecar's `derived` and Python's meta: "model", the
// coefficients by name and "max_field_angle_deg" where it limits the image.
void addCameraModel(JsonObject& json, const CameraExport& e);

// The model's coefficients by their scene keys (camera.projection), in the order of the
// library that reads them: cv2.projectPoints' distCoeffs (opencv), cv2.fisheye's D
// (kannala_brandt), cv2.omnidir's xi then D (unified); empty for the models without any.
std::vector<std::pair<std::string, double>> projectionCoefficients(const Projection& p);

// One line for the EXR header: "k1=… k2=… …" and " max_field_angle_deg=…" where it limits.
std::string cameraModelText(const CameraExport& e);

}  // namespace camsim
