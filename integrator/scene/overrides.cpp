// The override table and its parsing, checking and application (overrides.h).
#include "integrator/scene/overrides.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "integrator/camera/lens_camera.h"
#include "integrator/scene/overrides_projection.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/model/sensor_noise.h"
#include "sensor/model/sensor_spec.h"

#include "sensor/base/format.h"

namespace camsim {
namespace {

namespace R = setting_ranges;

OverrideSetting integerSetting(std::string_view key, std::string_view sceneKey,
                               std::string_view help, IntegerRange range) {
  OverrideSetting s{key, sceneKey, "", "N", help, OverrideType::kInteger};
  s.integers = range;
  return s;
}

OverrideSetting numberSetting(std::string_view key, std::string_view sceneKey,
                              std::string_view unit, std::string_view valueName,
                              std::string_view help, SettingRange range) {
  OverrideSetting s{key, sceneKey, unit, valueName, help, OverrideType::kNumber};
  s.numbers = range;
  return s;
}

const std::vector<OverrideSetting> kSettings = {
    OverrideSetting{
        "sensor", "sensor.model", "", "MODEL",
        "sensor preset or sensor file (replaces the scene's sensor; ISO at its base ISO)",
        OverrideType::kSensor},
    integerSetting("spp", "render.spp", "samples per pixel (overrides the scene's render.spp)",
                   R::kSpp),
    integerSetting("seed", "render.seed", "render seed (overrides render.seed)", R::kSeed),
    numberSetting("target_error", "render.target_error", "", "E",
                  "render in passes until the estimated MRAE is at most E (spp: the first pass)",
                  R::kTargetError),
    numberSetting("time_limit_s", "render.time_limit_s", "s", "S",
                  "render in passes, stopping before S seconds of render time", R::kTimeLimitS),
    numberSetting("adaptive_threshold", "render.adaptive_threshold", "", "T",
                  "adaptive sampling: a pixel stops once its estimated relative error is below T "
                  "(at the image's mean brightness; spp: the most)",
                  R::kAdaptiveThreshold),
    numberSetting("exposure_time_s", "camera.shutter", "s", "S",
                  "effective exposure time in seconds (stretches the scene's shutter)",
                  R::kExposureTimeS),
    numberSetting("f_number", "camera.f_number", "", "N",
                  "lens f-number (overrides camera.f_number)", R::kFNumber),
    numberSetting("iso", "sensor.iso", "", "N", "sensor ISO (scenes with a sensor)", R::kIso),
    OverrideSetting{"noise", "sensor.noise", "", "MODE", "sensor noise (scenes with a sensor)",
                    OverrideType::kNoise},
    integerSetting("noise_seed", "sensor.noise_seed", "seed of the sensor's temporal noise",
                   R::kNoiseSeed),
    OverrideSetting{"pose", "camera.world_from_camera", "m", "POSE",
                    "camera pose: px,py,pz,lx,ly,lz,ux,uy,uz (position, look_at, up) or 16 "
                    "numbers (world_from_camera, row-major)",
                    OverrideType::kPose},
    OverrideSetting{"projection", "camera.projection", "", "MAP",
                    "camera model, the scene's camera.projection map as YAML/JSON flow text: "
                    "'{model: equidistant, max_field_angle_deg: 95}' (docs/camera.md)",
                    OverrideType::kProjection},
    integerSetting("guiding", "render.guiding",
                   "path guiding: 1 on, 0 off (overrides render.guiding; docs/scene-format.md)",
                   R::kGuiding),
};

std::string vec(const glm::dvec3& v) {
  return "[" + formatShortest(v.x) + ", " + formatShortest(v.y) + ", " + formatShortest(v.z) + "]";
}

[[noreturn]] void fail(const OverrideSource& source, const std::string& message) {
  throw InputError(source.where, source.name, message);
}

[[noreturn]] void outOfRange(const OverrideSetting& s, const std::string& value,
                             const OverrideSource& source) {
  fail(source, "value " + value + " is out of range " + overrideRangeText(s));
}

double readNumber(std::string_view text, const OverrideSource& source) {
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size() || text.empty())
    fail(source, "'" + std::string(text) + "' is not a number");
  if (!std::isfinite(v)) fail(source, "'" + std::string(text) + "' is not a finite number");
  return v;
}

std::vector<double> readNumbers(std::string_view text, const OverrideSource& source) {
  std::vector<double> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    std::string_view item =
        text.substr(start, comma == std::string_view::npos ? text.npos : comma - start);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    out.push_back(readNumber(item, source));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

PoseOverride readPose(std::string_view text, const OverrideSource& source) {
  const std::vector<double> v = readNumbers(text, source);
  PoseOverride p;
  if (v.size() == 9) {
    p.position = {v[0], v[1], v[2]};
    p.lookAt = {v[3], v[4], v[5]};
    p.up = {v[6], v[7], v[8]};
  } else if (v.size() == 16) {
    glm::dmat4 m(1.0);
    for (int row = 0; row < 4; ++row)
      for (int col = 0; col < 4; ++col) m[col][row] = v[static_cast<std::size_t>(row * 4 + col)];
    p.worldFromCamera = m;
  } else {
    fail(source,
         "expected 9 numbers (position, look_at, up) or 16 (world_from_camera, "
         "row-major), got " +
             std::to_string(v.size()));
  }
  return p;
}

std::string poseText(const PoseOverride& p) {
  std::string out;
  const auto add = [&out](double v) { out += (out.empty() ? "" : ",") + formatShortest(v); };
  if (p.worldFromCamera) {
    for (int row = 0; row < 4; ++row)
      for (int col = 0; col < 4; ++col) add((*p.worldFromCamera)[col][row]);
  } else {
    for (const glm::dvec3& v : {p.position, p.lookAt, p.up})
      for (int i = 0; i < 3; ++i) add(v[i]);
  }
  return out;
}

// The pose the loader builds from `camera: <cameraYaml>`, moved into d's render space
// (d's render origin is kept: shapes and lights stay where they are, bit for bit).
void setPose(SceneDescription& d, const PoseOverride& p, const SourceLocation& where) {
  std::string cameraYaml;
  if (p.worldFromCamera) {
    std::string rows;
    for (int row = 0; row < 4; ++row)
      for (int col = 0; col < 4; ++col)
        rows += (rows.empty() ? "" : ", ") + formatShortest((*p.worldFromCamera)[col][row]);
    cameraYaml = "{world_from_camera: [" + rows + "]}";
  } else {
    cameraYaml = "{position: " + vec(p.position) + ", look_at: " + vec(p.lookAt) +
                 ", up: " + vec(p.up) + "}";
  }
  SceneDescription probe;
  try {
    probe = loadSceneFromText("camera: " + cameraYaml +
                                  "\nmaterials: {m: {type: diffuse}}\nshapes: [{type: sphere, "
                                  "centre: [0, 0, 0], radius: 1, material: m}]\n",
                              "<override>", ".");
  } catch (const InputError& e) {
    throw InputError(where, e.key(), e.message());  // not the probe text's line and column
  }
  glm::dmat4 m = probe.camera.worldFromCamera;
  m[3] = glm::dvec4(probe.renderOrigin - d.renderOrigin, 1.0);
  d.camera.worldFromCamera = m;
}

// As the loader's `sensor: {model: …}`: the preset or file, ISO at the sensor's base ISO,
// the camera's sensor size and fill factor from its pixel pitch; noise mode, seeds,
// auto-exposure and brackets of a sensor already there kept.
void setSensor(SceneDescription& d, const std::string& presetOrPath, const SourceLocation& where) {
  SensorSpec spec;
  try {
    spec = loadSensorSpec(presetOrPath, lutsDirectory());
  } catch (const InputError& e) {
    if (e.where().line > 0) throw;  // inside the sensor file: its own location
    // Otherwise the option, and the file when the error names one (an empty file, say).
    const std::string& file = e.where().file;
    throw InputError(where, "sensor.model",
                     file.empty() || e.message().find(file) != std::string::npos
                         ? e.message()
                         : file + ": " + e.message());
  }
  SensorSettings s = d.sensor.value_or(SensorSettings{});
  s.spec = std::move(spec);
  d.keyPlaces.erase("sensor.model");  // the scene's sensor is not this one
  s.iso = s.spec.baseIso;
  // The camera's own pixel geometry is replaced (docs: "sensor size from its pitch"); said
  // so, with the field of view it changes (found by probing: a 36 mm sensor_width_mm became
  // 45 µm without a word).
  const glm::dvec2 size = glm::dvec2(d.camera.resolution) * s.spec.pixelPitchM;
  std::string replaced;
  for (const char* key : kSensorGeometryKeys)
    if (const auto at = d.keyPlaces.find(std::string("camera.") + key); at != d.keyPlaces.end())
      replaced += (replaced.empty() ? "" : ", ") + at->first + " (" + at->second.file + ":" +
                  std::to_string(at->second.line) + ")";
  if (!replaced.empty())
    d.notes.push_back("the sensor '" + s.spec.name + "' replaces the scene's " + replaced +
                      ": its sensor is " + formatNumber(size.x * 1e3, 4) + " × " +
                      formatNumber(size.y * 1e3, 4) + " mm (resolution × pixel pitch), fill " +
                      "factor " + formatNumber(s.spec.fillFactor, 4) +
                      ", so the field of view at the same focal length changes");
  d.camera.sensorSize = size;
  d.camera.fillFactor = s.spec.fillFactor;
  for (const auto& f : s.spec.sourceFiles)
    if (std::find(d.inputFiles.begin(), d.inputFiles.end(), f) == d.inputFiles.end())
      d.inputFiles.push_back(f);
  d.sensor = std::move(s);
}

const OverrideSetting& setting(std::string_view key) {
  const OverrideSetting* s = findOverrideSetting(key);
  if (s == nullptr) throw std::logic_error("no override " + std::string(key));
  return *s;
}

}  // namespace

bool Overrides::empty() const {
  return std::none_of(kSettings.begin(), kSettings.end(),
                      [this](const OverrideSetting& s) { return overrideIsSet(*this, s); });
}

const std::vector<OverrideSetting>& overrideSettings() {
  return kSettings;
}

const OverrideSetting* findOverrideSetting(std::string_view key) {
  for (const OverrideSetting& s : kSettings)
    if (s.key == key) return &s;
  return nullptr;
}

std::string overrideFlag(const OverrideSetting& setting) {
  std::string flag = "--" + std::string(setting.key);
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

std::string overrideRangeText(const OverrideSetting& s) {
  switch (s.type) {
    case OverrideType::kInteger:
      return s.integers.text();
    case OverrideType::kNumber:
      return s.numbers.text();
    case OverrideType::kNoise:
      return noiseModeNames();
    case OverrideType::kSensor:
      return "a preset name or a sensor file";
    case OverrideType::kPose:
      return "9 or 16 comma-separated numbers";
    case OverrideType::kProjection:
      return "a camera.projection map";
  }
  return "";
}

void setOverrideInteger(Overrides& o, const OverrideSetting& s, std::int64_t value,
                        const OverrideSource& source) {
  if (s.type != OverrideType::kInteger) fail(source, "expected " + overrideRangeText(s));
  if (!s.integers.contains(value)) outOfRange(s, std::to_string(value), source);
  if (s.key == "spp") o.spp = value;
  if (s.key == "seed") o.seed = value;
  if (s.key == "noise_seed") o.noiseSeed = value;
  if (s.key == "guiding") o.guiding = value;
}

void setOverrideNumber(Overrides& o, const OverrideSetting& s, double value,
                       const OverrideSource& source) {
  if (s.type != OverrideType::kNumber) fail(source, "expected " + overrideRangeText(s));
  if (!std::isfinite(value)) fail(source, "'" + formatShortest(value) + "' is not a finite number");
  if (!s.numbers.contains(value)) outOfRange(s, formatShortest(value), source);
  if (s.key == "target_error") o.targetError = value;
  if (s.key == "time_limit_s") o.timeLimitS = value;
  if (s.key == "adaptive_threshold") o.adaptiveThreshold = value;
  if (s.key == "exposure_time_s") o.exposureTimeS = value;
  if (s.key == "f_number") o.fNumber = value;
  if (s.key == "iso") o.iso = value;
}

void setOverrideText(Overrides& o, const OverrideSetting& s, std::string_view text,
                     const OverrideSource& source) {
  switch (s.type) {
    case OverrideType::kInteger: {
      std::int64_t v = 0;
      const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (ec == std::errc::result_out_of_range) outOfRange(s, std::string(text), source);
      if (ec != std::errc() || ptr != text.data() + text.size() || text.empty())
        fail(source, "'" + std::string(text) + "' is not an integer");
      setOverrideInteger(o, s, v, source);
      return;
    }
    case OverrideType::kNumber:
      setOverrideNumber(o, s, readNumber(text, source), source);
      return;
    case OverrideType::kNoise: {
      const std::optional<NoiseMode> m = noiseModeFromName(std::string(text));
      if (!m)
        fail(source,
             "unknown noise mode '" + std::string(text) + "' (known: " + noiseModeNames() + ")");
      o.noise = *m;
      return;
    }
    case OverrideType::kSensor:
      if (text.empty()) fail(source, "expected a sensor preset name or file");
      o.sensor = std::string(text);
      return;
    case OverrideType::kPose:
      o.pose = readPose(text, source);
      return;
    case OverrideType::kProjection:
      o.projection = readProjectionOverride(text, source.where);
      return;
  }
}

void applyOverrides(SceneDescription& d, const Overrides& o, const SourceLocation& where) {
  // Every value checked again, named by its scene key (the setters checked what they took).
  const auto src = [&where](std::string_view key) {
    return OverrideSource{where, std::string(setting(key).sceneKey)};
  };
  Overrides checked;
  if (o.spp) setOverrideInteger(checked, setting("spp"), *o.spp, src("spp"));
  if (o.seed) setOverrideInteger(checked, setting("seed"), *o.seed, src("seed"));
  if (o.noiseSeed)
    setOverrideInteger(checked, setting("noise_seed"), *o.noiseSeed, src("noise_seed"));
  if (o.guiding) setOverrideInteger(checked, setting("guiding"), *o.guiding, src("guiding"));
  if (o.targetError)
    setOverrideNumber(checked, setting("target_error"), *o.targetError, src("target_error"));
  if (o.timeLimitS)
    setOverrideNumber(checked, setting("time_limit_s"), *o.timeLimitS, src("time_limit_s"));
  if (o.adaptiveThreshold)
    setOverrideNumber(checked, setting("adaptive_threshold"), *o.adaptiveThreshold,
                      src("adaptive_threshold"));
  if (o.exposureTimeS)
    setOverrideNumber(checked, setting("exposure_time_s"), *o.exposureTimeS,
                      src("exposure_time_s"));
  if (o.fNumber) setOverrideNumber(checked, setting("f_number"), *o.fNumber, src("f_number"));
  if (o.iso) setOverrideNumber(checked, setting("iso"), *o.iso, src("iso"));

  if (o.sensor) setSensor(d, *o.sensor, where);
  if (o.spp) {
    // As the loader refuses render.spp above render.max_spp (found by probing: an override
    // above it rendered, and the sidecar said "stopped by max_spp" at more than max_spp).
    if (*o.spp > d.render.maxSpp)
      fail(src("spp"), "spp " + std::to_string(*o.spp) + " is above the scene's render.max_spp " +
                           std::to_string(d.render.maxSpp));
    d.render.spp = static_cast<int>(*o.spp);
  }
  if (o.seed) d.render.seed = static_cast<std::uint64_t>(*o.seed);
  if (o.targetError) d.render.targetError = *o.targetError;
  if (o.timeLimitS) d.render.timeLimitS = *o.timeLimitS;
  if (o.adaptiveThreshold) d.render.adaptiveThreshold = *o.adaptiveThreshold;
  if (o.guiding) d.render.guiding = *o.guiding != 0;
  if (o.exposureTimeS) {
    const std::string key(setting("exposure_time_s").sceneKey);
    try {
      d.camera.shutter =
          d.camera.shutter.scaled(*o.exposureTimeS / d.camera.shutter.effectiveTime());
    } catch (const InputError& e) {
      throw InputError(where, key, e.message());
    }
    // A sequence's shutter angle sets each frame's box (frameCamera): the exposure becomes
    // its angle (found by probing: the override changed the unused curve, and nothing).
    if (d.frames && d.frames->shutterAngleDeg) {
      const double angle = *o.exposureTimeS * d.frames->rateHz * 360.0;
      if (!(angle >= setting_ranges::kMinShutterAngleDeg))
        throw InputError(where, key,
                         formatShortest(*o.exposureTimeS) + " s is a shutter angle of " +
                             formatShortest(angle) + "° at frames.rate_hz " +
                             formatShortest(d.frames->rateHz) +
                             ", below frames.shutter_angle_deg's " +
                             formatShortest(setting_ranges::kMinShutterAngleDeg) + "°");
      d.frames->shutterAngleDeg = angle;
    }
    if (const std::string problem = frameTimingProblem(d); !problem.empty())
      throw InputError(where, key, problem);
  }
  if (o.fNumber) d.camera.fNumber = *o.fNumber;  // the stop follows (apertureDiameter)
  if (o.fNumber && d.camera.lens) {              // a traced lens: its stop, within the lens's range
    const std::string problem = LensSystem(d.camera.lens->prescription).fNumberProblem(*o.fNumber);
    if (!problem.empty()) throw InputError(where, "camera.lens.f_number", problem);
    d.camera.lens->fNumber = *o.fNumber;
    // The best focus depends on the stop: the loader's check again (found in review).
    if (const std::string noImage = realImageProblem(*d.camera.lens); !noImage.empty())
      throw InputError(where, "camera.lens.f_number",
                       "at f/" + formatShortest(*o.fNumber) + " " + noImage);
  }
  if (o.projection && d.camera.lens)
    throw InputError(where, "camera.projection",
                     "the scene's camera.lens replaces the camera model: no projection override");
  const std::pair<std::string_view, bool> needSensor[] = {{"iso", o.iso.has_value()},
                                                          {"noise", o.noise.has_value()},
                                                          {"noise_seed", o.noiseSeed.has_value()}};
  for (const auto& [key, given] : needSensor)
    if (given && !d.sensor)
      throw InputError(where, std::string(setting(key).sceneKey),
                       "needs a scene with a sensor (a sensor override or the scene's sensor:)");
  if (o.iso) {
    d.sensor->iso = *o.iso;
    try {
      (void)noiseAtIso(d.sensor->spec, *o.iso);  // a calibrated sensor's ISO range
    } catch (const InputError& e) {
      throw InputError(where, std::string(setting("iso").sceneKey), e.message());
    }
  }
  if (o.noise) d.sensor->noise = *o.noise;
  if (o.noiseSeed) d.sensor->noiseSeed = static_cast<std::uint64_t>(*o.noiseSeed);
  if (o.pose) setPose(d, *o.pose, where);
  if (o.projection) setProjection(d, *o.projection, where);
}

bool overrideIsSet(const Overrides& o, const OverrideSetting& setting) {
  const std::string_view k = setting.key;
  const std::pair<std::string_view, bool> set[] = {
      {"sensor", o.sensor.has_value()},
      {"spp", o.spp.has_value()},
      {"seed", o.seed.has_value()},
      {"target_error", o.targetError.has_value()},
      {"time_limit_s", o.timeLimitS.has_value()},
      {"adaptive_threshold", o.adaptiveThreshold.has_value()},
      {"exposure_time_s", o.exposureTimeS.has_value()},
      {"f_number", o.fNumber.has_value()},
      {"iso", o.iso.has_value()},
      {"noise", o.noise.has_value()},
      {"noise_seed", o.noiseSeed.has_value()},
      {"pose", o.pose.has_value()},
      {"projection", o.projection.has_value()},
      {"guiding", o.guiding.has_value()}};
  for (const auto& [key, isSet] : set)
    if (key == k) return isSet;
  throw std::logic_error("overrideIsSet: no override " + std::string(k));
}

InputError namedByOverride(const InputError& e, const Overrides& o, const SourceLocation& where,
                           std::string (*name)(const OverrideSetting&)) {
  for (const OverrideSetting& s : kSettings)
    if (s.sceneKey == e.key() && overrideIsSet(o, s))
      return InputError(where, name(s), e.message());
  return e;
}

std::string overridesText(const Overrides& o) {
  std::string out;
  const auto add = [&out](std::string_view key, const std::string& value) {
    out += std::string(key) + "=" + value + "\n";
  };
  if (o.sensor) add("sensor", *o.sensor);
  if (o.spp) add("spp", std::to_string(*o.spp));
  if (o.seed) add("seed", std::to_string(*o.seed));
  if (o.targetError) add("target_error", formatShortest(*o.targetError));
  if (o.timeLimitS) add("time_limit_s", formatShortest(*o.timeLimitS));
  if (o.adaptiveThreshold) add("adaptive_threshold", formatShortest(*o.adaptiveThreshold));
  if (o.exposureTimeS) add("exposure_time_s", formatShortest(*o.exposureTimeS));
  if (o.fNumber) add("f_number", formatShortest(*o.fNumber));
  if (o.iso) add("iso", formatShortest(*o.iso));
  if (o.noise) add("noise", noiseModeName(*o.noise));
  if (o.noiseSeed) add("noise_seed", std::to_string(*o.noiseSeed));
  if (o.pose) add("pose", poseText(*o.pose));
  if (o.projection) add("projection", projectionOverrideText(*o.projection));
  if (o.guiding) add("guiding", std::to_string(*o.guiding));
  return out;
}

Overrides parseOverridesText(const std::string& text, const std::string& file) {
  Overrides o;
  std::istringstream in(text);
  int lineNumber = 0;
  for (std::string line; std::getline(in, line);) {
    ++lineNumber;
    if (line.empty()) continue;
    const SourceLocation where{file, lineNumber, 0};
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos)
      throw InputError(where, "", "expected key=value, got '" + line + "'");
    const std::string key = line.substr(0, eq);
    const OverrideSetting* s = findOverrideSetting(key);
    if (s == nullptr) throw InputError(where, key, "unknown override");
    setOverrideText(o, *s, std::string_view(line).substr(eq + 1), {where, key});
  }
  return o;
}

}  // namespace camsim
