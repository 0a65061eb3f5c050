// The embedded default scene: scenes/cornell_box.yaml, compiled into the library at build
// time (integrator/CMakeLists.txt), so that `camsim render` without a scene and
// `camsim.default_scene()` render the same scene without reading a file.
#pragma once

#include <string_view>

namespace camsim {

// The embedded file at `relPath` under scenes/ (only cornell_box.yaml is embedded); empty
// if it is not embedded.
std::string_view defaultSceneFile(std::string_view relPath);
inline std::string_view defaultSceneText() {
  return defaultSceneFile("cornell_box.yaml");
}

// The display name of the embedded default scene (NAME.json's "scene").
inline constexpr std::string_view kDefaultSceneName = "<default: scenes/cornell_box.yaml>";

}  // namespace camsim
