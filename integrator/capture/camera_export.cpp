#include "integrator/capture/camera_export.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include <glm/trigonometric.hpp>

#include "sensor/base/format.h"

namespace camsim {

using Coefficients = std::vector<std::pair<std::string, double>>;

Coefficients projectionCoefficients(const Projection& p) {
  switch (p.model) {
    case ProjectionModel::kOpenCv:
      return {{"k1", p.k1}, {"k2", p.k2}, {"p1", p.p1},      {"p2", p.p2},     {"k3", p.k3},
              {"k4", p.k4}, {"k5", p.k5}, {"k6", p.k6},      {"s1", p.s1},     {"s2", p.s2},
              {"s3", p.s3}, {"s4", p.s4}, {"tau_x", p.tauX}, {"tau_y", p.tauY}};
    case ProjectionModel::kKannalaBrandt:
    case ProjectionModel::kFTheta:
      return {{"k1", p.k1}, {"k2", p.k2}, {"k3", p.k3}, {"k4", p.k4}};
    case ProjectionModel::kUnified:
      return {{"xi", p.xi}, {"k1", p.k1}, {"k2", p.k2}, {"p1", p.p1}, {"p2", p.p2}};
    case ProjectionModel::kDoubleSphere:
      return {{"xi", p.xi}, {"alpha", p.alpha}};
    default:
      return {};
  }
}

namespace {

// Whether some corner of the image sees no ray: the model's domain (its maxFieldAngle, the
// fold of a distortion, a pinhole's 90°) ends inside the picture.
bool cornerUnimaged(const Projection& p, glm::ivec2 resolution) {
  const double w = resolution.x - 0.5, h = resolution.y - 0.5;
  for (const glm::dvec2 corner :
       {glm::dvec2(-0.5, -0.5), glm::dvec2(w, -0.5), glm::dvec2(-0.5, h), glm::dvec2(w, h)})
    if (!unproject(p, corner)) return true;
  return false;
}

// The field angle (rad) of the last imaged point from (cx, cy) towards (edgeX, cy), signed:
// negative left of cx. The field across the width is then right's − left's, also when cx
// lies outside the image (found by probing: unsigned angles added, cx = −20 px gave 87.9°
// for a 45.3° field).
double edgeFieldAngle(const Projection& p, double edgeX) {
  const double sign = edgeX < p.cx ? -1.0 : 1.0;
  const auto angle = [sign](const glm::dvec3& d) {
    return sign * std::acos(std::clamp(d.z, -1.0, 1.0));
  };
  if (auto d = unproject(p, {edgeX, p.cy})) return angle(*d);
  double in = p.cx, out = edgeX;  // unproject(in) exists, unproject(out) does not
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (in + out);
    (unproject(p, {mid, p.cy}) ? in : out) = mid;
  }
  const std::optional<glm::dvec3> d = unproject(p, {in, p.cy});
  return d ? angle(*d) : 0.0;
}

bool allZero(std::initializer_list<double> values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return v == 0.0; });
}

}  // namespace

CameraExport cameraExport(const PhysicalCamera& camera) {
  const Projection& p = camera.projection();
  const glm::ivec2 res = camera.params().resolution;
  CameraExport e;
  e.model = enumName(p.model);
  e.fx = p.fx, e.fy = p.fy, e.cx = p.cx, e.cy = p.cy;
  e.coefficients = projectionCoefficients(p);
  if (p.model != ProjectionModel::kEquirectangular && cornerUnimaged(p, res))
    e.maxFieldAngle = p.maxFieldAngle;
  e.cameraAngleX = p.model == ProjectionModel::kEquirectangular
                       ? res.x / p.fx
                       : edgeFieldAngle(p, res.x - 0.5) - edgeFieldAngle(p, -0.5);

  const std::vector<double> k = {p.fx, p.fy, p.cx + 0.5, p.cy + 0.5};
  const std::string name = "the " + e.model + " model";
  switch (p.model) {
    case ProjectionModel::kOpenCv:
      if (!allZero({p.s1, p.s2, p.s3, p.s4, p.tauX, p.tauY})) {
        e.colmapLacks =
            "COLMAP has no pinhole model with thin prism (s1..s4) or tilt (tau_x, "
            "tau_y) terms (THIN_PRISM_FISHEYE is a fisheye)";
        e.nerfstudioLacks = "nerfstudio's OPENCV has no thin prism or tilt terms";
        break;
      }
      e.colmapParams = k;
      if (allZero({p.k3, p.k4, p.k5, p.k6})) {
        e.colmapModel = "OPENCV";
        e.colmapParams.insert(e.colmapParams.end(), {p.k1, p.k2, p.p1, p.p2});
      } else {
        e.colmapModel = "FULL_OPENCV";
        e.colmapParams.insert(e.colmapParams.end(),
                              {p.k1, p.k2, p.p1, p.p2, p.k3, p.k4, p.k5, p.k6});
      }
      if (allZero({p.k4, p.k5, p.k6})) {
        e.nerfstudioModel = "OPENCV";
        e.nerfstudio = {{"k1", p.k1}, {"k2", p.k2}, {"k3", p.k3}, {"p1", p.p1}, {"p2", p.p2}};
      } else {
        e.nerfstudioLacks =
            "nerfstudio's OPENCV has no rational terms k4..k6 (its k4 is a "
            "polynomial r^8 term)";
      }
      break;
    case ProjectionModel::kKannalaBrandt:
    case ProjectionModel::kEquidistant: {
      const bool kb = p.model == ProjectionModel::kKannalaBrandt;
      const std::vector<double> d = kb ? std::vector<double>{p.k1, p.k2, p.k3, p.k4}
                                       : std::vector<double>{0.0, 0.0, 0.0, 0.0};
      e.colmapModel = e.nerfstudioModel = "OPENCV_FISHEYE";
      e.colmapParams = k;
      e.colmapParams.insert(e.colmapParams.end(), d.begin(), d.end());
      e.nerfstudio = {{"k1", d[0]}, {"k2", d[1]}, {"k3", d[2]}, {"k4", d[3]}};
      break;
    }
    case ProjectionModel::kEquirectangular:
      e.colmapLacks = "COLMAP has no equirectangular (spherical) camera model";
      e.nerfstudioModel = "EQUIRECTANGULAR";
      break;
    default:
      e.colmapLacks = "COLMAP has no camera model for " + name +
                      " (its fisheyes are OPENCV_FISHEYE, RADIAL_FISHEYE, FOV and "
                      "THIN_PRISM_FISHEYE)";
      e.nerfstudioLacks = "nerfstudio has no camera model for " + name +
                          " (its are OPENCV, OPENCV_FISHEYE and EQUIRECTANGULAR)";
  }
  // A traced lens images through its prescription (found by probing: the 10 mm fisheye
  // was exported as an undistorted pinhole, its points 14 px off on average, 90 px at the
  // edge of a 96-px image).
  if (camera.lensCamera()) {
    e.tracedLens = true;
    e.colmapModel.clear();
    e.colmapParams.clear();
    e.nerfstudioModel.clear();
    e.nerfstudio.clear();
    const std::string why =
        " has no model for a traced lens (camera.lens): its distortion is the prescription's "
        "(fx, fy, cx, cy are the lens's paraxial stand-in's)";
    e.colmapLacks = "COLMAP" + why;
    e.nerfstudioLacks = "nerfstudio" + why;
  }
  if (!e.nerfstudioModel.empty()) {
    // nerfstudio's equirectangular spans π rad per focal length (cameras.py: θ = −π·x/fx).
    const double scale = p.model == ProjectionModel::kEquirectangular ? std::numbers::pi : 1.0;
    Coefficients n = {
        {"fl_x", scale * p.fx}, {"fl_y", scale * p.fy}, {"cx", p.cx + 0.5}, {"cy", p.cy + 0.5}};
    n.insert(n.end(), e.nerfstudio.begin(), e.nerfstudio.end());
    e.nerfstudio = std::move(n);
  }
  return e;
}

std::string cameraModelText(const CameraExport& e) {
  std::string s;
  for (const auto& [name, value] : e.coefficients)
    s += (s.empty() ? "" : " ") + name + "=" + formatShortest(value);
  if (e.maxFieldAngle)
    s += (s.empty() ? "" : " ") + std::string("max_field_angle_deg=") +
         formatShortest(glm::degrees(*e.maxFieldAngle));
  if (e.tracedLens) s += (s.empty() ? "" : " ") + std::string("traced_lens");
  return s;
}

void addCameraModel(JsonObject& json, const CameraExport& e) {
  json.set("model", e.model);
  for (const auto& [name, value] : e.coefficients) json.setJson(name, formatShortest(value));
  if (e.maxFieldAngle)
    json.setJson("max_field_angle_deg", formatShortest(glm::degrees(*e.maxFieldAngle)));
  if (e.tracedLens) json.setJson("traced_lens", "true");
}

}  // namespace camsim
