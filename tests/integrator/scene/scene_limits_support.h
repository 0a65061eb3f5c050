// The small scenes and the error catcher shared by the scene-limit tests
// (scene_limits_test.cpp, scene_refusals_test.cpp): a header, a 16×16 camera, a sun, a
// grey diffuse material and a unit ball, and errorOf(f), the InputError f throws.
#pragma once

#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"

namespace camsim::test {

inline const std::string kHeader = "format: camsim-scene/1\nrender: {spp: 4, max_depth: 3}\n";
inline const std::string kLimitsCamera =
    "camera: {position: [0, 0, 5], look_at: [0, 0, 0], resolution: [16, 16]}\n";
inline const std::string kSun =
    "lights: [{type: distant, direction: [0, 0, -1], illuminance: 1000}]\n";
inline const std::string kMaterial = "materials: {m: {type: diffuse, reflectance: 0.5}}\n";
inline const std::string kBall = "  - {type: sphere, centre: [0, 0, 0], radius: 1, material: m}\n";

// The InputError `f` throws (a test failure, and an empty error, if it throws none).
inline InputError errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError({}, "", "");
}

}  // namespace camsim::test
