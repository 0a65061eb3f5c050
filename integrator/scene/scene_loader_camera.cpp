// The scene loader's camera part: pose, sensor, lens, aperture, distortion, shutter and
// motion keyframes (docs/scene-format.md, `camera:`).
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "integrator/scene/scene_loader.h"
#include "integrator/scene/scene_loader_parts.h"
#include "sensor/base/format.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

// A point of render space: within ±SceneLimits::kMaxCoordinate on every axis (Embree's rays
// must stay within ~1.8e18; geometry is stored in single precision).
glm::vec3 toPoint(const YamlValue& where, const glm::dvec3& v) {
  const double m = SceneLimits::kMaxCoordinate;
  if (!(std::abs(v.x) <= m && std::abs(v.y) <= m && std::abs(v.z) <= m))
    where.fail(
        "coordinates must lie within ±1e15 m (of the world origin for the camera, of the "
        "camera's rest position for the rest; limit SceneLimits::kMaxCoordinate)");
  return glm::vec3(v);
}

// A positive length stored in single precision: it must not underflow to 0.
float positiveFloat(const YamlValue& where, double v) {
  const float f = static_cast<float>(v);
  if (!(f > 0.0f)) where.fail("value is too small (it is 0 in single precision)");
  return f;
}

namespace {

// Pixels per side, with the limit named in the message.
int resolutionSide(const YamlValue& v) {
  const std::int64_t n = v.integer(INT64_MIN, INT64_MAX);
  if (n < 1 || n > SceneLimits::kMaxResolution)
    v.fail("value " + std::to_string(n) + " is out of range [1, " +
           std::to_string(SceneLimits::kMaxResolution) + "] (limit SceneLimits::kMaxResolution)");
  return static_cast<int>(n);
}

// `camera.projection`: the camera model (integrator/camera/projection.h), its coefficients
// and, optionally, a calibration's intrinsics in pixels (all four or none). Parsed after the
// lens and the aperture, whose values it needs.
void parseProjection(const YamlValue& value, PhysicalCameraParams& c) {
  YamlMap pm(value);
  Projection& p = c.projection;
  p = Projection{};
  p.model = pm.require("model").choice<ProjectionModel>("projection model");
  struct Field {
    const char* name;
    double* value;
  };
  const Field coefficients[] = {
      {"k1", &p.k1},      {"k2", &p.k2},      {"k3", &p.k3}, {"k4", &p.k4},
      {"k5", &p.k5},      {"k6", &p.k6},      {"p1", &p.p1}, {"p2", &p.p2},
      {"s1", &p.s1},      {"s2", &p.s2},      {"s3", &p.s3}, {"s4", &p.s4},
      {"tau_x", &p.tauX}, {"tau_y", &p.tauY}, {"xi", &p.xi}, {"alpha", &p.alpha}};
  for (const Field& f : coefficients)
    if (auto v = pm.find(f.name)) *f.value = v->number(-1e3, 1e3);
  if (auto v = pm.find("max_field_angle_deg"))
    p.maxFieldAngle = glm::radians(v->number(0.0, 180.0, true));
  const Field intrinsics[] = {{"fx", &p.fx}, {"fy", &p.fy}, {"cx", &p.cx}, {"cy", &p.cy}};
  int given = 0;
  for (const Field& f : intrinsics)
    if (auto v = pm.find(f.name)) {
      *f.value = v->number(-1e7, 1e7);
      ++given;
    }
  if (given != 0 && given != 4)
    value.fail("give all four intrinsics fx, fy, cx, cy (px) or none (then they follow the lens)");
  c.intrinsicsFromLens = given == 0;
  if (c.intrinsicsFromLens) p.fx = p.fy = 1.0;  // placeholders for the checks
  checkProjection(p, value.where(), value.key());
  p = limitedToFold(p);
  if (p.model != ProjectionModel::kOpenCv && c.pupil == LensPupil::kFlat)
    value.fail(
        "camera.aperture.pupil: flat applies to the opencv model only (the pupil of "
        "the fisheye and omnidirectional models turns with the field)");
  pm.finish({"model", "fx",
             "fy",    "cx",
             "cy",    "k1",
             "k2",    "k3",
             "k4",    "k5",
             "k6",    "p1",
             "p2",    "s1",
             "s2",    "s3",
             "s4",    "tau_x",
             "tau_y", "xi",
             "alpha", "max_field_angle_deg"});
}

// upWhere: the `up` key, or null for the default +y (then look_at is named).
glm::dmat4 lookAt(const YamlValue& where, const YamlValue& positionWhere, const YamlValue* upWhere,
                  glm::dvec3 position, glm::dvec3 target, glm::dvec3 up) {
  toPoint(positionWhere, position);  // range check only: the position stays double
  // Scaled by its largest component before normalising (as up, below): a look_at of 1e300
  // overflowed the length, and the zero direction was blamed on up.
  const glm::dvec3 toTarget = target - position;
  const double toMax = std::max({std::abs(toTarget.x), std::abs(toTarget.y), std::abs(toTarget.z)});
  if (!(toMax > 0.0)) where.fail("look_at equals position");
  if (!std::isfinite(toMax)) where.fail("look_at must be a finite point");
  const glm::dvec3 forward = glm::normalize(toTarget / toMax);
  // Right-handed world: right = forward × up (looking along +z with +y up, right is −x).
  // up is scaled by its largest component first, so that no length under- or overflows.
  const double upMax = std::max({std::abs(up.x), std::abs(up.y), std::abs(up.z)});
  const YamlValue& upKey = upWhere ? *upWhere : where;
  if (!(upMax > 0.0) || !std::isfinite(upMax)) upKey.fail("up must be a non-zero direction");
  const glm::dvec3 rightRaw = glm::cross(forward, glm::normalize(up / upMax));
  if (!(glm::length(rightRaw) >= 1e-9)) upKey.fail("up is parallel to the viewing direction");
  const glm::dvec3 right = glm::normalize(rightRaw);
  const glm::dvec3 trueUp = glm::cross(right, forward);
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(right, 0.0);
  m[1] = glm::dvec4(trueUp, 0.0);
  m[2] = glm::dvec4(forward, 0.0);
  m[3] = glm::dvec4(position, 1.0);
  return m;
}

glm::dmat4 parseMatrix(const YamlValue& m) {
  const glm::dmat4 out = parseAffineMatrix(m);
  const glm::dvec3 x(out[0]), y(out[1]), z(out[2]);
  if (std::abs(glm::dot(x, y)) > 1e-4 || std::abs(glm::dot(y, z)) > 1e-4 ||
      std::abs(glm::dot(x, z)) > 1e-4 || std::abs(glm::length(x) - 1.0) > 1e-4 ||
      std::abs(glm::length(y) - 1.0) > 1e-4 || std::abs(glm::length(z) - 1.0) > 1e-4)
    m.fail("the rotation part must be orthonormal (columns right, up, forward)");
  // In camsim's right-handed world the camera's axes right, up, forward satisfy
  // right = forward × up (what look_at builds), so their matrix has determinant −1. A proper
  // rotation (+1) has right = up × forward, pointing left: the image would be mirrored.
  if (glm::dot(glm::cross(x, y), z) > 0.0)
    m.fail(
        "the rotation part has determinant +1: camsim's columns are right, up, forward "
        "with right = forward × up (determinant −1, as look_at builds); this matrix's "
        "first column points left and would mirror the image (negate it; from an OpenCV "
        "pose [x right, y down, z forward] negate the second column instead)");
  return out;
}

Shutter parseShutter(YamlMap map) {
  Shutter::Type type = Shutter::Type::kGlobal;
  if (auto t = map.find("type")) type = t->choice<Shutter::Type>("shutter type");
  double rowTime = 0.0;
  if (auto r = map.find("row_time")) {
    if (type != Shutter::Type::kRolling) r->fail("row_time needs type: rolling");
    rowTime = r->number(0.0, 1.0);
  }
  if (auto curve = map.find("curve")) {
    std::vector<double> times, values;
    for (const YamlValue& point : curve->items()) {
      const std::vector<double> tv = point.numbers();
      if (tv.size() != 2) point.fail("expected [time_s, efficiency]");
      // open's and close's range (found by probing: times of ±1e300 s made every sample NaN
      // and wrote an exposure time of inf).
      if (!(std::abs(tv[0]) <= setting_ranges::kShutterTime))
        point.fail("time " + formatShortest(tv[0]) + " s is outside [-" +
                   formatShortest(setting_ranges::kShutterTime) + ", " +
                   formatShortest(setting_ranges::kShutterTime) + "] s");
      if (!times.empty() && tv[0] <= times.back()) point.fail("times must be strictly increasing");
      if (tv[1] < 0.0 || tv[1] > 1.0) point.fail("efficiency must lie in [0, 1]");
      times.push_back(tv[0]);
      values.push_back(tv[1]);
    }
    if (times.size() < 2) curve->fail("a shutter curve needs at least 2 points");
    double area = 0.0;
    for (size_t i = 1; i < times.size(); ++i)
      area += 0.5 * (values[i] + values[i - 1]) * (times[i] - times[i - 1]);
    if (!(area > 0.0)) curve->fail("the shutter curve lets no light through");
    map.finish({"type", "row_time", "curve"});
    return Shutter(std::move(times), std::move(values), type, rowTime);
  }
  double open = 0.0, close = 1.0 / 60.0, rampOpen = 0.0, rampClose = 0.0;
  if (auto v = map.find("open"))
    open = v->number(-setting_ranges::kShutterTime, setting_ranges::kShutterTime);
  const auto closeValue = map.find("close");
  if (closeValue)
    close = closeValue->number(-setting_ranges::kShutterTime, setting_ranges::kShutterTime);
  if (!(close > open))
    (closeValue ? *closeValue : map.self()).fail("close must be later than open");
  // The exposure as written: close − open rounds (0.3 − 0.1 < 0.2), and a ramp of the whole
  // exposure is allowed.
  const double exposure = (close - open) * (1.0 + 1e-12);
  if (auto v = map.find("ramp_open")) rampOpen = v->number(0.0, exposure);
  const auto rc = map.find("ramp_close");
  if (rc) rampClose = rc->number(0.0, exposure);
  if (rampOpen + rampClose > exposure)
    rc->fail("ramp_open + ramp_close exceed the exposure (close − open)");
  map.finish({"type", "row_time", "open", "close", "ramp_open", "ramp_close"});
  return Shutter::trapezoid(open, close, rampOpen, rampClose, type, rowTime);
}

}  // namespace

glm::dmat4 parseAffineMatrix(const YamlValue& m) {
  const std::vector<double> v = m.numbers();
  if (v.size() != 16) m.fail("expected 16 numbers (a 4×4 matrix, row by row)");
  glm::dmat4 out(1.0);
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) out[col][row] = v[static_cast<size_t>(row * 4 + col)];
  if (v[12] != 0.0 || v[13] != 0.0 || v[14] != 0.0 || v[15] != 1.0)
    m.fail("last row must be [0, 0, 0, 1] (an affine map)");
  toPoint(m, glm::dvec3(out[3]));  // the translation must fit in single precision
  return out;
}

namespace {

// A rotation as written: its unit axis and its angle (°, not wrapped).
struct AxisAngle {
  glm::dvec3 axis{0.0, 0.0, 1.0};
  double degrees = 0.0;
  glm::dquat quaternion() const { return glm::angleAxis(glm::radians(degrees), axis); }
};

AxisAngle parseAxisAngle(const YamlValue& value) {
  YamlMap rm(value);
  const YamlValue axisValue = rm.require("axis");
  const glm::dvec3 axis = axisValue.vec3();
  if (!(glm::length(axis) > 0.0)) axisValue.fail("rotation axis must not be zero");
  const double degrees = rm.require("angle_deg").number(-1e6, 1e6);
  rm.finish({"axis", "angle_deg"});
  return {glm::normalize(axis), degrees};
}

// Whether two keyframes' rotations, as written, differ by 180° or more. About one axis
// (or its opposite) by the angles themselves: the quaternions' dot product, cos(Δ/2),
// repeats every 720°, so 0° → 720° passed as no motion and 0° → 600° as −120° (found in
// review); about different axes by the dot product (≤ 0: the relative rotation ≥ 180°).
bool rotateHalfATurnOrMore(const AxisAngle& a, const AxisAngle& b) {
  const double along = glm::dot(a.axis, b.axis);
  if (glm::length(glm::cross(a.axis, b.axis)) < 1e-9 || a.degrees == 0.0 || b.degrees == 0.0)
    return !(std::abs(b.degrees - (along < 0.0 ? -a.degrees : a.degrees)) < 180.0);
  return !(glm::dot(a.quaternion(), b.quaternion()) > 1e-9);
}

}  // namespace

glm::dquat parseRotation(const YamlValue& value) {
  return parseAxisAngle(value).quaternion();
}

RigidMotion parseMotion(const YamlValue& value, bool forCamera, const glm::dvec3& origin) {
  std::vector<Keyframe> keys;
  AxisAngle previous;  // the last keyframe's rotation as written (none: 0°)
  for (const YamlValue& item : value.items()) {
    YamlMap map(item);
    Keyframe k;
    const YamlValue time = map.require("time");
    k.time = time.number(-1e6, 1e6);
    if (!keys.empty() && k.time <= keys.back().time)
      time.fail("keyframe times must be strictly increasing");
    if (auto t = map.find("translate")) {
      // Shifted in double and kept double: a float of a world coordinate near 10⁶ m is
      // only good to 6 cm. toPoint only checks that render space holds it.
      k.translate = t->vec3() - origin;
      toPoint(*t, k.translate);
    }
    AxisAngle rotation;
    if (auto r = map.find("rotate")) {
      rotation = parseAxisAngle(*r);
      k.rotate = rotation.quaternion();
    }
    if (auto sc = map.find("scale")) {
      if (forCamera) sc->fail("a camera cannot be scaled");
      k.scale = sc->number(0.0, 1e12, true);
    }
    map.finish(forCamera ? std::vector<std::string>{"time", "translate", "rotate"}
                         : std::vector<std::string>{"time", "translate", "rotate", "scale"});
    // The absolute value of the quaternions' dot product let 0° → 270° through, played as
    // −90°, and 0° → 360° as no motion (found by probing).
    if (!keys.empty() && rotateHalfATurnOrMore(previous, rotation))
      item.fail(
          "consecutive keyframes rotate by 180° or more: add keyframes in between (or "
          "continue the angle: 190 after 170, not -170)");
    previous = rotation;
    keys.push_back(k);
  }
  if (keys.empty()) value.fail("motion needs at least one keyframe");
  return RigidMotion(std::move(keys));
}

PhysicalCameraParams parseCamera(YamlMap map, const TableSearch& search) {
  PhysicalCameraParams c;
  if (auto g = map.find("gltf")) {
    // The pose and focal length come from a glTF camera (the loader applies it).
    for (const char* key : {"world_from_camera", "position", "look_at", "up", "focal_length_mm"})
      if (map.has(key))
        map.find(key)->fail(std::string("the camera's pose and focal length come from its glTF "
                                        "camera: remove '") +
                            key + "'");
  } else if (auto m = map.find("world_from_camera")) {
    c.worldFromCamera = parseMatrix(*m);
  } else {
    const YamlValue position = map.require("position");
    const YamlValue target = map.require("look_at");
    glm::dvec3 up(0.0, 1.0, 0.0);
    const std::optional<YamlValue> upValue = map.find("up");
    if (upValue) up = upValue->vec3();
    c.worldFromCamera =
        lookAt(target, position, upValue ? &*upValue : nullptr, position.vec3(), target.vec3(), up);
  }
  if (auto v = map.find("sensor_width_mm"))
    c.sensorSize.x = static_cast<double>(positiveFloat(*v, v->number(0.0, 1000.0, true) * 1e-3));
  if (auto v = map.find("sensor_height_mm"))
    c.sensorSize.y = static_cast<double>(positiveFloat(*v, v->number(0.0, 1000.0, true) * 1e-3));
  if (auto v = map.find("resolution")) {
    const std::vector<YamlValue> items = v->items();
    if (items.size() != 2) v->fail("expected [width, height] in pixels");
    c.resolution.x = resolutionSide(items[0]);
    c.resolution.y = resolutionSide(items[1]);
    if (std::int64_t(c.resolution.x) * c.resolution.y > SceneLimits::kMaxPixels)
      v->fail("more than " + std::to_string(SceneLimits::kMaxPixels) +
              " pixels (limit SceneLimits::kMaxPixels)");
  }
  if (auto v = map.find("fill_factor")) c.fillFactor = v->number(0.0, 1.0, true);
  if (auto v = map.find("focal_length_mm"))
    c.focalLength = static_cast<double>(positiveFloat(*v, v->number(0.0, 1e5, true) * 1e-3));
  if (auto v = map.find("f_number"))
    c.fNumber = v->number(setting_ranges::kFNumber.lo, setting_ranges::kFNumber.hi);
  if (auto v = map.find("focus_distance_m")) {
    c.focusDistance = v->number(0.0, 1e12, true);
    if (!(c.focusDistance > c.focalLength * 1.0001))
      v->fail("focus distance must exceed 1.0001 × the focal length (" +
              std::to_string(c.focalLength * 1.0001) + " m): closer, the image distance " +
              "f·z/(z − f) is unbounded");
  }
  if (auto a = map.find("aperture")) {
    YamlMap am(*a);
    int blades = 0;
    double rotation = 0.0;
    if (auto b = am.find("blades")) {
      blades = static_cast<int>(b->integer(0, 64));
      if (blades > 0 && blades < 3) b->fail("blades must be 0 (circular) or at least 3");
    }
    if (auto r = am.find("rotation_deg")) rotation = glm::radians(r->number(-360.0, 360.0));
    if (auto pu = am.find("pupil")) c.pupil = pu->choice<LensPupil>("pupil");
    ApertureShape shape{blades, rotation};
    if (auto d = am.find("diffraction")) shape.diffraction = d->boolean();
    am.finish({"blades", "rotation_deg", "pupil", "diffraction"});
    c.aperture = shape;
  }
  if (auto t = map.find("lens_transmittance"))
    c.lensTransmittance = parseSpectrum(*t, SpectrumUse::kReflectance, search);
  if (auto d = map.find("distortion")) {
    // Brown–Conrady k1 k2 k3 p1 p2: the opencv model's first five coefficients.
    YamlMap dm(*d);
    double* fields[] = {&c.projection.k1, &c.projection.k2, &c.projection.k3, &c.projection.p1,
                        &c.projection.p2};
    const char* names[] = {"k1", "k2", "k3", "p1", "p2"};
    for (int i = 0; i < 5; ++i)
      if (auto v = dm.find(names[i])) *fields[i] = v->number(-1e3, 1e3);
    dm.finish({"k1", "k2", "k3", "p1", "p2"});
    if (map.has("projection"))
      d->fail("give the distortion inside camera.projection (model: opencv), not both");
    c.projection = limitedToFold(c.projection);
  }
  if (auto pr = map.find("projection")) {
    parseProjection(*pr, c);
    // With the image's own size (the --projection override's probe scene has none: its
    // check is applyOverrides', with the scene's size).
    if (map.has("resolution") && !c.intrinsicsFromLens) {
      const std::string problem = imagedNothing(c.projection, c.resolution);
      if (!problem.empty()) pr->fail(problem);
    }
  }
  if (auto s = map.find("shutter")) c.shutter = parseShutter(YamlMap(*s));
  if (auto m = map.find("motion")) c.motion = parseMotion(*m, true, glm::dvec3(0.0));
  if (auto l = map.find("lens")) parseCameraLens(*l, map, search, c);
  map.finish({"position", "look_at", "up", "world_from_camera", "sensor_width_mm",
              "sensor_height_mm", "resolution", "fill_factor", "focal_length_mm", "f_number",
              "focus_distance_m", "aperture", "lens_transmittance", "distortion", "projection",
              "shutter", "motion", "gltf", "lens"});
  return c;
}

}  // namespace camsim
