// Overrides of a loaded scene (bindings.h): the CLI's render flags and the camera pose,
// applied to the SceneDescription in place. Nothing geometric is touched, so no mesh,
// texture or environment map is read again; the pose goes through the scene loader itself
// (a camera-only scene text), so its checks and messages are the loader's.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <optional>
#include <vector>

#include "integrator/scene/scene_loader.h"
#include "python/bindings.h"
#include "sensor/base/input_error.h"
#include "sensor/model/sensor_spec.h"

namespace camsim::python {
namespace {

namespace py = pybind11;

[[noreturn]] void fail(const std::string& key, const std::string& message) {
  throw InputError(SourceLocation{"<override>", 0, 0}, key, message);
}

// Shortest round-trip decimal: the loader reads back exactly this double.
std::string shortest(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

std::string vec(const glm::dvec3& v) {
  return "[" + shortest(v.x) + ", " + shortest(v.y) + ", " + shortest(v.z) + "]";
}

void checkRange(const std::string& key, double v, double lo, double hi) {
  if (!std::isfinite(v)) fail(key, "'" + shortest(v) + "' is not a finite number");
  if (!(v > lo && v <= hi))
    fail(key,
         "value " + shortest(v) + " is out of range (" + shortest(lo) + ", " + shortest(hi) + "]");
}

// The pose the loader builds from `camera: <cameraYaml>`, moved into d's render space
// (d's render origin is kept: shapes and lights stay where they are, bit for bit).
void setPose(SceneDescription& d, const std::string& cameraYaml) {
  SceneDescription probe;
  try {
    probe = loadSceneFromText("camera: " + cameraYaml +
                                  "\nmaterials: {m: {type: diffuse}}\nshapes: [{type: sphere, "
                                  "centre: [0, 0, 0], radius: 1, material: m}]\n",
                              "<override>", ".");
  } catch (const InputError& e) {
    fail(e.key(), e.message());  // its line and column are those of the probe text
  }
  glm::dmat4 m = probe.camera.worldFromCamera;
  m[3] = glm::dvec4(probe.renderOrigin - d.renderOrigin, 1.0);
  d.camera.worldFromCamera = m;
}

template <typename T>
T castOverride(const py::handle& value, const std::string& key, const char* expected) {
  try {
    return value.cast<T>();
  } catch (const py::cast_error&) {
    fail(key, std::string("expected ") + expected + ", got " +
                  std::string(py::str(py::type::of(value).attr("__name__"))));
  }
}

}  // namespace

void overrideSeed(SceneDescription& d, std::uint64_t seed) {
  if (seed > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
    fail("render.seed", "out of range [0, 2^63 - 1]");
  d.render.seed = seed;
}

void overrideSpp(SceneDescription& d, long long spp) {
  if (spp < 1 || spp > SceneLimits::kMaxSpp)
    fail("render.spp", "value " + std::to_string(spp) + " is out of range [1, " +
                           std::to_string(SceneLimits::kMaxSpp) + "]");
  d.render.spp = static_cast<int>(spp);
}

// As --exposure-time: the scene's shutter curve stretched to this effective time.
void overrideExposureTime(SceneDescription& d, double seconds) {
  checkRange("camera.shutter.exposure_time_s", seconds, 0.0, 1e6);
  d.camera.shutter = d.camera.shutter.scaled(seconds / d.camera.shutter.effectiveTime());
}

// As --f-number: the stop follows (PhysicalCameraParams::apertureDiameter).
void overrideFNumber(SceneDescription& d, double fNumber) {
  if (!std::isfinite(fNumber) || fNumber < 0.5 || fNumber > 1e4)
    fail("camera.f_number", "value " + shortest(fNumber) + " is out of range [0.5, 10000]");
  d.camera.fNumber = fNumber;
}

void overrideIso(SceneDescription& d, double iso) {
  if (!d.sensor) fail("sensor.iso", "needs a scene with a sensor (set_sensor or sensor:)");
  if (!std::isfinite(iso) || iso < 1.0 || iso > 1e7)
    fail("sensor.iso", "value " + shortest(iso) + " is out of range [1, 1e+07]");
  d.sensor->iso = iso;
}

void overrideNoise(SceneDescription& d, const std::string& mode) {
  if (!d.sensor) fail("sensor.noise", "needs a scene with a sensor (set_sensor or sensor:)");
  const std::optional<NoiseMode> m = noiseModeFromName(mode);
  if (!m)
    fail("sensor.noise", "unknown noise mode '" + mode + "' (known: " + noiseModeNames() + ")");
  d.sensor->noise = *m;
}

void overrideNoiseSeed(SceneDescription& d, std::uint64_t seed) {
  if (!d.sensor) fail("sensor.noise_seed", "needs a scene with a sensor (set_sensor or sensor:)");
  d.sensor->noiseSeed = seed;
}

// As the loader's `sensor: {model: …}`: the preset or file (relative: to the working
// directory), ISO at the sensor's base ISO, the camera's sensor size and fill factor from its
// pixel pitch; noise mode, seeds, auto-exposure and brackets of a sensor already there kept.
void overrideSensor(SceneDescription& d, const std::string& presetOrPath) {
  SensorSpec spec;
  try {
    spec = loadSensorSpec(presetOrPath, lutsDirectory());
  } catch (const InputError& e) {
    if (e.where().line > 0) throw;  // inside the sensor file: its own location
    fail("sensor.model", e.message());
  }
  SensorSettings s = d.sensor.value_or(SensorSettings{});
  s.spec = std::move(spec);
  s.iso = s.spec.baseIso;
  d.camera.sensorSize = glm::dvec2(d.camera.resolution) * s.spec.pixelPitchM;
  d.camera.fillFactor = s.spec.fillFactor;
  for (const auto& f : s.spec.sourceFiles)
    if (std::find(d.inputFiles.begin(), d.inputFiles.end(), f) == d.inputFiles.end())
      d.inputFiles.push_back(f);
  d.sensor = std::move(s);
}

void overridePoseLookAt(SceneDescription& d, const glm::dvec3& position, const glm::dvec3& lookAt,
                        const glm::dvec3& up) {
  setPose(d,
          "{position: " + vec(position) + ", look_at: " + vec(lookAt) + ", up: " + vec(up) + "}");
}

void overridePoseMatrix(SceneDescription& d, const glm::dmat4& worldFromCamera) {
  std::string rows;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col)
      rows += (rows.empty() ? "" : ", ") + shortest(worldFromCamera[col][row]);
  setPose(d, "{world_from_camera: [" + rows + "]}");
}

void applyOverrides(SceneDescription& d, const py::dict& overrides) {
  static const char* const kKnown[] = {"sensor",   "spp", "seed",  "exposure_time_s",
                                       "f_number", "iso", "noise", "noise_seed"};
  for (const auto& [k, v] : overrides) {
    const std::string key = py::str(k);
    if (std::find_if(std::begin(kKnown), std::end(kKnown),
                     [&](const char* n) { return key == n; }) == std::end(kKnown))
      fail("overrides." + key,
           "unknown override (known: sensor, spp, seed, exposure_time_s, f_number, iso, noise, "
           "noise_seed)");
  }
  // In this order: a new sensor sets the ISO that an iso override then replaces.
  const auto get = [&](const char* key) -> py::object {
    return overrides.contains(key) ? py::reinterpret_borrow<py::object>(overrides[key])
                                   : py::object();
  };
  const std::string o = "overrides.";
  if (auto v = get("sensor"))
    overrideSensor(d, castOverride<std::string>(v, o + "sensor", "a str"));
  if (auto v = get("spp")) overrideSpp(d, castOverride<long long>(v, o + "spp", "an int"));
  if (auto v = get("seed"))
    overrideSeed(d, castOverride<std::uint64_t>(v, o + "seed", "an int ≥ 0"));
  if (auto v = get("exposure_time_s"))
    overrideExposureTime(d, castOverride<double>(v, o + "exposure_time_s", "a number"));
  if (auto v = get("f_number"))
    overrideFNumber(d, castOverride<double>(v, o + "f_number", "a number"));
  if (auto v = get("iso")) overrideIso(d, castOverride<double>(v, o + "iso", "a number"));
  if (auto v = get("noise")) overrideNoise(d, castOverride<std::string>(v, o + "noise", "a str"));
  if (auto v = get("noise_seed"))
    overrideNoiseSeed(d, castOverride<std::uint64_t>(v, o + "noise_seed", "an int ≥ 0"));
}

}  // namespace camsim::python
