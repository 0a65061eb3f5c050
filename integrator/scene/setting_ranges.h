// The allowed range of every scene setting a front end can override (overrides.h), defined
// once: the scene loader reads the scene file's keys with these bounds and the overrides
// module checks CLI flags, Python arguments and tile-part records against the same ones, so
// a value the loader refuses is refused everywhere (issue 35, "settings defined once").
//
// | setting         | scene key                    | unit | range          |
// |-----------------|------------------------------|------|----------------|
// | spp             | render.spp                   | —    | [1, 2^20]      |
// | seed            | render.seed                  | —    | [0, 2^63 − 1]  |
// | exposure_time_s | camera.shutter (close−open)  | s    | (0, 1e6]       |
// | f_number        | camera.f_number              | —    | [0.5, 1e4]     |
// | iso             | sensor.iso                   | —    | [1, 1e7]       |
// | noise_seed      | sensor.noise_seed            | —    | [0, 2^63 − 1]  |
// | adaptive_threshold | render.adaptive_threshold | —    | (0, 1]         |
#pragma once

#include <cstdint>
#include <limits>
#include <string>

#include "sensor/model/sensor_noise.h"

namespace camsim {

// [lo, hi], or (lo, hi] when loOpen. Integer settings hold integral bounds.
struct SettingRange {
  double lo = 0.0;
  double hi = 0.0;
  bool loOpen = false;

  bool contains(double v) const { return v <= hi && (loOpen ? v > lo : v >= lo); }
  // "[0.5, 10000]", "(0, 1000000]": the bounds as the scene loader prints them (%.10g).
  std::string text() const;
};

struct IntegerRange {
  std::int64_t lo = 0;
  std::int64_t hi = 0;

  bool contains(std::int64_t v) const { return v >= lo && v <= hi; }
  std::string text() const;  // "[1, 1048576]"
};

namespace setting_ranges {

inline constexpr IntegerRange kSpp{1, std::int64_t{1} << 20};
inline constexpr IntegerRange kSeed{0, std::numeric_limits<std::int64_t>::max()};
inline constexpr IntegerRange kNoiseSeed{0, std::numeric_limits<std::int64_t>::max()};
// A lens in air is no faster than f/0.5 (NA ≤ 1).
inline constexpr SettingRange kFNumber{0.5, 1e4, false};
inline constexpr SettingRange kIso{kMinIso, kMaxIso, false};  // sensor_noise.h
// The shutter's open and close times (s) lie within ±kShutterTime, so an exposure that
// opens at 0 lasts at most kShutterTime: the effective exposure time's range.
inline constexpr double kShutterTime = 1e6;
inline constexpr SettingRange kExposureTimeS{0.0, kShutterTime, true};
// frames.shutter_angle_deg ∈ [this, 360] °: the exposure_time_s override of a sequence
// with a shutter angle sets the angle, within the same range.
inline constexpr double kMinShutterAngleDeg = 1e-3;
// render.target_error: an estimated MRAE (error_estimate.h), a fraction of the pixel values.
inline constexpr SettingRange kTargetError{0.0, 1.0, true};
// render.time_limit_s: s of render time (a year).
inline constexpr SettingRange kTimeLimitS{0.0, 3.2e7, true};
// render.adaptive_threshold: a pixel's estimated relative error at the image's mean
// brightness (integrator/render/adaptive_sampling.h).
inline constexpr SettingRange kAdaptiveThreshold{0.0, 1.0, true};
// render.adaptive_min_spp: samples per pixel before (and between) convergence checks; even.
inline constexpr IntegerRange kAdaptiveMinSpp{2, std::int64_t{1} << 20};
// render.guiding as an override (the scene file's is a boolean): 1 on, 0 off.
inline constexpr IntegerRange kGuiding{0, 1};

}  // namespace setting_ranges
}  // namespace camsim
