// Overrides: every setting a front end can change on a loaded scene, defined once (issue 35).
// The CLI's render flags, Python's keyword arguments and overrides dict, and the record a
// tile part keeps for camsim merge all go through this table; ranges are the scene
// loader's own (setting_ranges.h), so a value the loader refuses is refused everywhere.
//
// | key             | scene key                | unit | value                              |
// |-----------------|--------------------------|------|------------------------------------|
// | sensor          | sensor.model             | —    | a preset name or a sensor file     |
// | spp             | render.spp               | —    | integer, setting_ranges::kSpp      |
// | seed            | render.seed              | —    | integer, kSeed                     |
// | target_error    | render.target_error      | —    | number, kTargetError (an MRAE)     |
// | time_limit_s    | render.time_limit_s      | s    | number, kTimeLimitS                |
// | adaptive_threshold | render.adaptive_threshold | — | number, kAdaptiveThreshold         |
// | exposure_time_s | camera.shutter           | s    | number, kExposureTimeS (the scene's|
// |                 |                          |      | shutter curve stretched to it; a   |
// |                 |                          |      | sequence's shutter angle set to it;|
// |                 |                          |      | within the frame period)           |
// | f_number        | camera.f_number          | —    | number, kFNumber (the stop follows)|
// | iso             | sensor.iso               | —    | number, kIso (needs a sensor)      |
// | noise           | sensor.noise             | —    | none, photon or full (a sensor)    |
// | noise_seed      | sensor.noise_seed        | —    | integer, kNoiseSeed (a sensor)     |
// | pose            | camera.world_from_camera | m    | look-at or 4x4 matrix (text below) |
// | projection      | camera.projection        | —    | the camera model: the scene key's  |
// |                 |                          |      | map as YAML/JSON flow text         |
// | guiding         | render.guiding           | —    | integer, kGuiding: 1 on, 0 off     |
//
// The CLI flag of a key is "--" + the key with '_' → '-' (--f-number). Text forms (CLI,
// tile parts): numbers and integers as C++ from_chars reads them; pose as 9 comma-separated
// numbers (position, look_at, up) or 16 (world_from_camera, row-major); projection as the
// scene's camera.projection map, e.g. {model: equidistant, max_field_angle_deg: 95}.
// overridesText() writes one "key=value" line per set override in table order, numbers in
// their shortest round-trip form (a projection as one line of JSON), so parseOverridesText()
// gives back the same doubles.
//
// Nothing geometric is touched by applyOverrides: no mesh, texture or environment map is
// read again. The pose and the projection go through the scene loader itself (a camera-only
// scene text), so their checks and messages are the loader's (a projection's name the key
// camera.projection.<key>); a projection replaces the scene's camera.projection (or
// camera.distortion) whole, and one other than opencv is refused on a scene whose
// camera.aperture.pupil is flat, as the loader refuses it; a sensor reads its preset or file (relative: to the working
// directory) as the loader's `sensor: {model: …}` does.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "integrator/scene/setting_ranges.h"
#include "sensor/base/input_error.h"
#include "sensor/model/sensor_model.h"

namespace camsim {

struct SceneDescription;

struct PoseOverride {
  // Set: the camera's world_from_camera (columns right, up, forward, position, in the scene
  // file's world coordinates); otherwise position / lookAt / up.
  std::optional<glm::dmat4> worldFromCamera;
  glm::dvec3 position{0.0}, lookAt{0.0, 0.0, -1.0}, up{0.0, 1.0, 0.0};
};

// camera.projection's keys as given: the model's name and each number key with its value
// (k1, max_field_angle_deg, fx, …), in the order given; the loader checks them when set and
// again when applied.
struct ProjectionOverride {
  std::string model;
  std::vector<std::pair<std::string, double>> values;
};

struct Overrides {
  std::optional<std::string> sensor;
  std::optional<std::int64_t> spp;
  std::optional<std::int64_t> seed;
  std::optional<double> targetError;
  std::optional<double> timeLimitS;
  std::optional<double> adaptiveThreshold;
  std::optional<double> exposureTimeS;
  std::optional<double> fNumber;
  std::optional<double> iso;
  std::optional<NoiseMode> noise;
  std::optional<std::int64_t> noiseSeed;
  std::optional<PoseOverride> pose;
  std::optional<ProjectionOverride> projection;
  std::optional<std::int64_t> guiding;  // 0 or 1

  bool empty() const;
};

enum class OverrideType { kInteger, kNumber, kNoise, kSensor, kPose, kProjection };

struct OverrideSetting {
  std::string_view key;        // snake_case: Python keyword, tile-part key, CLI flag's stem
  std::string_view sceneKey;   // the scene file's key it overrides
  std::string_view unit;       // "s", or "" when none
  std::string_view valueName;  // the value in usage text: "N", "S", "MODE", …
  std::string_view help;       // one line for usage text
  OverrideType type;
  IntegerRange integers{};  // kInteger
  SettingRange numbers{};   // kNumber
};

// Every override, in the order applyOverrides applies them (a sensor first: it sets the ISO
// that an iso override then replaces).
const std::vector<OverrideSetting>& overrideSettings();
// The setting of `key` (snake_case), or nullptr.
const OverrideSetting* findOverrideSetting(std::string_view key);
// "--f-number" for f_number.
std::string overrideFlag(const OverrideSetting& setting);
// "[0.5, 10000]", "(0, 1000000]", "none|photon|full", …: what the setting accepts.
std::string overrideRangeText(const OverrideSetting& setting);

// Where a value comes from, for InputError: the location (file; "" for a command line) and
// the name the user gave it ("--f-number", "f_number", "camera.f_number").
struct OverrideSource {
  SourceLocation where;
  std::string name;
};

// Parses `text` as the setting's value and stores it in o. InputError (key = source.name)
// naming the value and the range when it does not read or is out of range; a projection is
// read by the scene loader (key camera.projection.<key>, at source.where).
void setOverrideText(Overrides& o, const OverrideSetting& setting, std::string_view text,
                     const OverrideSource& source);
// Typed values (Python): the same checks, the same messages.
void setOverrideInteger(Overrides& o, const OverrideSetting& setting, std::int64_t value,
                        const OverrideSource& source);
void setOverrideNumber(Overrides& o, const OverrideSetting& setting, double value,
                       const OverrideSource& source);

// Applies o to d in table order, checking every value again (an Overrides filled by hand
// gets the same refusals). InputError (file where.file, key = the scene key) for a value out
// of range, iso/noise/noise_seed without a sensor, a sensor, pose or projection the loader
// refuses (key camera.projection.<key>), a projection other than opencv with a flat pupil.
void applyOverrides(SceneDescription& d, const Overrides& o, const SourceLocation& where);

// Whether o sets the setting's value.
bool overrideIsSet(const Overrides& o, const OverrideSetting& setting);
// `e` named by where its value came from: an error a later stage found in a setting o set
// (its key the setting's scene key, e.g. render.target_error when --target-error gave it) is
// the same message at `where` with key name(setting) ("--target-error" for the CLI), not at
// the scene file, which may not even have the key. Any other error is returned unchanged.
InputError namedByOverride(const InputError& e, const Overrides& o, const SourceLocation& where,
                           std::string (*name)(const OverrideSetting&));

// One "key=value" line per set override (table order); "" when none.
std::string overridesText(const Overrides& o);
// Back from overridesText (lines; blank lines skipped). InputError at `where` (its file,
// the line's number) for an unknown key, a line without '=', or a bad value.
Overrides parseOverridesText(const std::string& text, const std::string& file);

}  // namespace camsim
