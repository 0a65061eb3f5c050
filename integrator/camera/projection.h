// Projection: the camera models of real rigs as plain data and three functions — a
// camera-space direction to a pixel (project), a pixel to a unit direction (unproject) and
// the solid angle a pixel's area maps to (solidAngleDensity) — so rays, ground truth,
// radiometry and exports can share one exact mapping (issue 36).
//
// Conventions (as PhysicalCamera's): camera OpenCV axes x right, y down, z forward; pixels
// in OpenCV's convention, centres at integers (cx = W/2 − ½ for a centred axis). Every model
// first maps the direction d = (X, Y, Z) to normalised film coordinates m = (mx, my) and then
// to the pixel u = fx·mx + cx, v = fy·my + cy. θ = atan2(√(X²+Y²), Z) is the field angle.
//
// | parameter       | unit | default | used by |
// |-----------------|------|---------|---------|
// | model           | —    | opencv  | see ProjectionModel |
// | fx, fy          | px   | 500     | all (equirectangular: px per radian of longitude / latitude) |
// | cx, cy          | px   | 319.5, 239.5 | all |
// | k1 … k6         | —    | 0       | opencv: radial, rational (k4…k6 the denominator); kannala_brandt: k1…k4; ftheta: k1…k4 (θ², θ³, θ⁴, θ⁵ terms); unified: k1 k2 |
// | p1, p2          | —    | 0       | opencv, unified: tangential |
// | s1 … s4         | —    | 0       | opencv: thin prism |
// | tauX, tauY      | rad  | 0       | opencv: sensor tilt τx τy |
// | xi              | —    | 0       | unified (ξ ≥ 0), double_sphere (ξ ∈ [−1, 1]) |
// | alpha           | —    | 0.5     | double_sphere (α ∈ [0, 1]) |
// | maxFieldAngle   | rad  | π       | largest θ imaged (all but equirectangular), within the model's own limit |
//
// Models (equations in the model files: projection.cpp, projection_fisheye.cpp,
// projection_omni.cpp):
//   opencv          OpenCV calib3d pinhole, x' = X/Z, with radial k1…k6 (rational),
//                   tangential p1 p2, thin prism s1…s4 and sensor tilt τx τy; Z > 0.
//   kannala_brandt  OpenCV fisheye: ρ = θ(1 + k1θ² + k2θ⁴ + k3θ⁶ + k4θ⁸).
//   equidistant     ρ = θ;  equisolid ρ = 2 sin(θ/2);  stereographic ρ = 2 tan(θ/2) (θ < π);
//   orthographic    ρ = sin θ (θ ≤ π/2).
//   ftheta          ρ = θ + k1θ² + k2θ³ + k3θ⁴ + k4θ⁵ (NVIDIA's f-theta polynomial, in units
//                   of fx: its pixel coefficients a1…a5 are fx = a1, k_i = a_{i+1}/a1).
//   unified         Mei's unified model as OpenCV omnidir: ξ, then k1 k2 p1 p2.
//   double_sphere   Usenko, Demmel, Cremers 2018: ξ, α.
//   equirectangular u = cx + fx·longitude, v = cy + fy·latitude (latitude positive down).
// The radial models put m = ρ(θ)·(X, Y)/√(X²+Y²).
#pragma once

#include <numbers>
#include <optional>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sensor/base/enum_names.h"
#include "sensor/base/input_error.h"

namespace camsim {

enum class ProjectionModel {
  kOpenCv,
  kKannalaBrandt,
  kEquidistant,
  kEquisolid,
  kStereographic,
  kOrthographic,
  kFTheta,
  kUnified,
  kDoubleSphere,
  kEquirectangular,
};
// The scene's `camera.projection.model` names (sensor/base/enum_names.h).
template <>
struct EnumNames<ProjectionModel> {
  static constexpr EnumName<ProjectionModel> kTable[] = {
      {ProjectionModel::kOpenCv, "opencv"},
      {ProjectionModel::kKannalaBrandt, "kannala_brandt"},
      {ProjectionModel::kEquidistant, "equidistant"},
      {ProjectionModel::kEquisolid, "equisolid"},
      {ProjectionModel::kStereographic, "stereographic"},
      {ProjectionModel::kOrthographic, "orthographic"},
      {ProjectionModel::kFTheta, "ftheta"},
      {ProjectionModel::kUnified, "unified"},
      {ProjectionModel::kDoubleSphere, "double_sphere"},
      {ProjectionModel::kEquirectangular, "equirectangular"},
      {ProjectionModel::kKannalaBrandt, "opencv_fisheye"},
      {ProjectionModel::kUnified, "mei"},
  };
};

// One camera's projection; the coefficients a model does not use are ignored.
struct Projection {
  ProjectionModel model = ProjectionModel::kOpenCv;
  double fx = 500.0, fy = 500.0;  // px
  double cx = 319.5, cy = 239.5;  // px
  double k1 = 0.0, k2 = 0.0, k3 = 0.0, k4 = 0.0, k5 = 0.0, k6 = 0.0;
  double p1 = 0.0, p2 = 0.0;
  double s1 = 0.0, s2 = 0.0, s3 = 0.0, s4 = 0.0;
  double tauX = 0.0, tauY = 0.0;  // rad
  double xi = 0.0;
  double alpha = 0.5;
  double maxFieldAngle = std::numbers::pi;  // rad, half-angle from the optical axis
};

// The pixel (OpenCV convention) a camera-space direction (CV axes, any length > 0) images
// at; none outside the model's valid domain (behind a pinhole, past maxFieldAngle, where a
// distortion folds over).
std::optional<glm::dvec2> project(const Projection& p, glm::dvec3 dirCv);

// The unit direction (CV axes) pixel sees; none outside the image circle or the model's
// valid domain. Closed form where the model has one, else Newton's method to ~1e-15.
std::optional<glm::dvec3> unproject(const Projection& p, glm::dvec2 pixel);

// dΩ/dA at pixel: the solid angle (sr) per unit image area (px²) the mapping gives there,
// |det ∂ω/∂(u, v)| for the unit direction ω(u, v); 0 outside the valid domain. A uniform
// radiance field gives each pixel energy in proportion to its integral over the pixel.
double solidAngleDensity(const Projection& p, glm::dvec2 pixel);

// The field angle up to which the model is one-to-one: where dρ/dθ of its radial part (the
// radial distortion of opencv and unified, the polynomial of kannala_brandt and ftheta) first
// reaches 0, found every 0.01° and refined by bisection; the model's own limit when it never
// does. (project and unproject also reject points where det J ≤ 0 or the radial factor is
// ≤ 0, but a distortion that turns up again beyond a fold would pass those local tests.)
double foldFieldAngle(const Projection& p);
// p with maxFieldAngle lowered to foldFieldAngle(p): what a loader applies, so that project
// and unproject are one-to-one for any calibrated distortion.
Projection limitedToFold(Projection p);

// unproject and solidAngleDensity at once (the distortion inverted once): what a camera ray
// needs. None where unproject has none or the density is not positive.
struct ModelRay {
  glm::dvec3 direction;  // unit, OpenCV camera axes
  double density;        // dΩ/dA, sr per px²
};
std::optional<ModelRay> unprojectWithDensity(const Projection& p, glm::dvec2 pixel);

// Range checks for a projection a scene file or front end set, throwing InputError with the
// key `keyPrefix.name` of the offending coefficient and its allowed range.
void checkProjection(const Projection& p, const SourceLocation& where = {},
                     const std::string& keyPrefix = "camera.projection");

// "" when p images at least one of a 9 × 9 grid of pixel centres of a `resolution` image;
// else why not (calibrated intrinsics in the wrong unit — cx in µm, fx in m — image nothing:
// found by probing, a black frame with complete exports, exit 0).
std::string imagedNothing(const Projection& p, glm::ivec2 resolution);

// The opencv model with every distortion coefficient 0 and no field limit inside 90°: the
// ideal pinhole's mapping.
inline bool isUndistortedOpenCv(const Projection& p) {
  return p.model == ProjectionModel::kOpenCv && p.k1 == 0.0 && p.k2 == 0.0 && p.k3 == 0.0 &&
         p.k4 == 0.0 && p.k5 == 0.0 && p.k6 == 0.0 && p.p1 == 0.0 && p.p2 == 0.0 && p.s1 == 0.0 &&
         p.s2 == 0.0 && p.s3 == 0.0 && p.s4 == 0.0 && p.tauX == 0.0 && p.tauY == 0.0 &&
         p.maxFieldAngle >= 0.5 * std::numbers::pi;
}

}  // namespace camsim
