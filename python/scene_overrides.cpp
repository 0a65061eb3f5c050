// Overrides of a loaded scene (bindings.h), through the library's override table
// (integrator/scene/overrides.h): the same keys, ranges and messages as the CLI's flags and
// the scene loader. Python values are converted here (a wrong type: InputError naming
// `overrides.<key>`); ranges, text forms and the application to the SceneDescription are
// the library's. Nothing geometric is touched, so no mesh, texture or environment map is read
// again.
#include <initializer_list>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <pybind11/stl.h>

#include "integrator/scene/overrides.h"
#include "python/bindings.h"
#include "sensor/base/input_error.h"

namespace camsim::python {
namespace {

namespace py = pybind11;

const SourceLocation kWhere{"<override>", 0, 0};

[[noreturn]] void fail(const std::string& key, const std::string& message) {
  throw InputError(kWhere, key, message);
}

const OverrideSetting& setting(const char* key) {
  return *findOverrideSetting(key);
}

OverrideSource sourceOf(const OverrideSetting& s) {
  return {kWhere, std::string(s.sceneKey)};
}

template <typename T>
T castOverride(const py::handle& value, const std::string& key, const std::string& expected) {
  // A bool is no number here (found by probing: spp=True rendered 1 spp).
  if constexpr (std::is_arithmetic_v<T>)
    if (PyBool_Check(value.ptr())) fail(key, "expected " + expected + ", got bool");
  try {
    return value.cast<T>();
  } catch (const py::cast_error&) {
    // An int too big for 64 bits fails the cast too ("expected an int, got int" before).
    if constexpr (std::is_integral_v<T>)
      if (py::isinstance<py::int_>(value))
        fail(key, "expected " + expected + " within 64 bits, got " + std::string(py::repr(value)));
    fail(key, "expected " + expected + ", got " +
                  std::string(py::str(py::type::of(value).attr("__name__"))));
  }
}

glm::dvec3 toVec3(const py::handle& v, const std::string& key) {
  const auto xs = castOverride<std::vector<double>>(v, key, "a list of 3 numbers");
  if (xs.size() != 3) fail(key, "expected a list of 3 numbers");
  return {xs[0], xs[1], xs[2]};
}

// A pose value: {"position": …, "look_at": …, "up": …} or a 4×4 world_from_camera.
PoseOverride poseOf(const py::handle& v, const std::string& key) {
  PoseOverride p;
  if (py::isinstance<py::dict>(v)) {
    const py::dict d = py::reinterpret_borrow<py::dict>(v);
    for (const auto& [k, _] : d) {
      const std::string name = py::str(k);
      if (name != "position" && name != "look_at" && name != "up")
        fail(key + "." + name, "unknown key (known: position, look_at, up)");
    }
    if (!d.contains("position") || !d.contains("look_at"))
      fail(key, "give position and look_at (and up), or a 4×4 world_from_camera");
    p.position = toVec3(d["position"], key + ".position");
    p.lookAt = toVec3(d["look_at"], key + ".look_at");
    if (d.contains("up")) p.up = toVec3(d["up"], key + ".up");
    return p;
  }
  const auto rows = castOverride<std::vector<std::vector<double>>>(
      v, key, "a dict {position, look_at, up} or a 4×4 matrix");
  glm::dmat4 w(1.0);
  if (rows.size() != 4) fail(key, "expected a 4×4 matrix");
  for (int r = 0; r < 4; ++r) {
    if (rows[static_cast<std::size_t>(r)].size() != 4) fail(key, "expected a 4×4 matrix");
    for (int c = 0; c < 4; ++c)
      w[c][r] = rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)];
  }
  p.worldFromCamera = w;
  return p;
}

// A projection value: a dict (written as JSON, which the scene loader reads as YAML; NumPy
// scalars become floats) or the YAML/JSON text itself.
std::string projectionTextOf(const py::handle& v, const std::string& key) {
  if (py::isinstance<py::str>(v)) return textArg(v, kWhere.file, key);
  if (!py::isinstance<py::dict>(v))
    fail(key, "expected a dict (camera.projection's keys) or a str, got " +
                  std::string(py::str(py::type::of(v).attr("__name__"))));
  try {
    py::object json = py::module_::import("json");
    return json.attr("dumps")(v, py::arg("default") = py::module_::import("builtins").attr("float"))
        .cast<std::string>();
  } catch (const py::error_already_set& e) {
    // The exception's own text, not e.what(), which carries the Python traceback (found by
    // probing: an array value printed json/encoder.py's frames).
    fail(key, "a value is neither a str nor a number (" +
                  std::string(py::str(e.type().attr("__name__"))) + ": " +
                  std::string(py::str(e.value())) + ")");
  }
}

void apply(SceneDescription& d, const Overrides& o) {
  applyOverrides(d, o, kWhere);
}

}  // namespace

void setOverrideFromPython(Overrides& o, const OverrideSetting& s, const py::handle& value,
                           const std::string& typeKey) {
  switch (s.type) {
    case OverrideType::kInteger:
      // An on/off setting ([0, 1]: guiding) also takes a bool.
      if (PyBool_Check(value.ptr()) && s.integers.lo == 0 && s.integers.hi == 1) {
        setOverrideInteger(o, s, value.ptr() == Py_True ? 1 : 0, sourceOf(s));
        return;
      }
      setOverrideInteger(o, s, castOverride<long long>(value, typeKey, "an int"), sourceOf(s));
      return;
    case OverrideType::kNumber:
      setOverrideNumber(o, s, castOverride<double>(value, typeKey, "a number"), sourceOf(s));
      return;
    case OverrideType::kNoise:
      if (!py::isinstance<py::str>(value))  // bytes too (castOverride's caster takes them)
        fail(typeKey,
             "expected a str, got " + std::string(py::str(py::type::of(value).attr("__name__"))));
      setOverrideText(o, s, textArg(value, kWhere.file, typeKey), sourceOf(s));
      return;
    case OverrideType::kSensor:  // a preset name or a file (str or os.PathLike)
      setOverrideText(o, s, sensorNameOrPath(value, kWhere.file, typeKey), sourceOf(s));
      return;
    case OverrideType::kPose:
      o.pose = poseOf(value, typeKey);
      return;
    case OverrideType::kProjection:
      setOverrideText(o, s, projectionTextOf(value, typeKey), sourceOf(s));
      return;
  }
}

void overridePoseLookAt(SceneDescription& d, const glm::dvec3& position, const glm::dvec3& lookAt,
                        const glm::dvec3& up) {
  Overrides o;
  o.pose = PoseOverride{std::nullopt, position, lookAt, up};
  apply(d, o);
}

void overridePoseMatrix(SceneDescription& d, const glm::dmat4& worldFromCamera) {
  Overrides o;
  o.pose = PoseOverride{worldFromCamera};
  apply(d, o);
}

Overrides overridesFromDict(const py::dict& overrides, const std::string& prefix) {
  Overrides o;
  for (const auto& [k, v] : overrides) {
    const std::string key = py::str(k);
    const OverrideSetting* s = findOverrideSetting(key);
    if (s == nullptr) {
      std::string known;
      for (const OverrideSetting& each : overrideSettings())
        known += (known.empty() ? "" : ", ") + std::string(each.key);
      fail(prefix + key, "unknown override (known: " + known + ")");
    }
    if (!v.is_none()) setOverrideFromPython(o, *s, v, prefix + key);
  }
  return o;
}

void applyPythonOverrides(SceneDescription& d,
                          std::initializer_list<std::pair<const char*, py::object>> values) {
  Overrides o;
  for (const auto& [key, value] : values)
    if (!value.is_none()) {
      const OverrideSetting& s = setting(key);
      setOverrideFromPython(o, s, value, std::string(s.sceneKey));
    }
  apply(d, o);
}

void applyOverrides(SceneDescription& d, const py::dict& overrides) {
  apply(d, overridesFromDict(overrides, "overrides."));
}

}  // namespace camsim::python
