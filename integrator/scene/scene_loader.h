// Scene loader: scene files (YAML; JSON parses too) → SceneDescription.
// The format is documented in docs/scene-format.md. Every error — syntax, unknown key,
// wrong type, out-of-range value, missing file — is an InputError naming file, line,
// column and key. Nothing is rendered or written before the whole scene has loaded.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "integrator/scene/scene_description.h"
#include "integrator/scene/setting_ranges.h"
#include "sensor/base/luts_directory.h"  // lutsDirectory(), used with scenes

namespace camsim {

struct LoadOptions {
  // Extra directories searched for spectral CSV tables, after the scene's own directory
  // and its `spectra_path`, before the installed luts/spectra/.
  std::vector<std::filesystem::path> spectraPath;
};

// Limits checked before any work starts (resource guards). Raise them only knowingly.
struct SceneLimits {
  static constexpr std::int64_t kMaxResolution = 32768;             // px per side
  static constexpr std::int64_t kMaxPixels = 268435456;             // 2^28 px (16k × 16k)
  static constexpr std::int64_t kMaxSpp = setting_ranges::kSpp.hi;  // setting_ranges.h
  static constexpr std::int64_t kMaxDepth = 10000;
  static constexpr std::int64_t kMaxTrianglesInline = 10000000;
  // Every coordinate of render space (positions, translations, geometry over its motion), m:
  // Embree refuses rays whose origin or direction exceeds ~1.8e18 in any component.
  static constexpr double kMaxCoordinate = 1e15;
  static constexpr std::size_t kMaxNameBytes = 128;  // the scene's name (output file stem)
  // An emitter's luminance, cd/m² (scene emission and glTF emission alike): past it a float
  // spectrum overflows and every path that sees the shape is infinite.
  static constexpr double kMaxLuminance = 1e15;
  // A sphere's radius, m: Embree squares it in single precision.
  static constexpr double kMinSphereRadius = 1e-9;
  // A sun disc's angular diameter (°) when not 0: smaller discs are lost to float rounding
  // in the cone test (use 0, parallel light).
  static constexpr double kMinSunDiameterDeg = 1e-3;
};

SceneDescription loadScene(const std::filesystem::path& file, const LoadOptions& options = {});
// The text of a scene file (InputError naming the file if it cannot be read) and the
// directory its relative paths resolve against ("." for a bare file name).
std::string readSceneFile(const std::filesystem::path& file);
std::filesystem::path sceneBaseDir(const std::filesystem::path& file);
// "" when the scene's exports (BOP, KITTI: a pinhole matrix describes the camera) can
// describe a camera of `projection` (and the scene's lens); else why not. The loader's rule
// for `exports`, and the --projection override's.
std::string pinholeExportProblem(const SceneDescription& scene, const Projection& projection);
// "" when each frame of the scene's sequence fits in its frame period 1 / frames.rate_hz (or
// there is no sequence); else why not. A row exposes for the shutter curve's length and a
// rolling shutter reads its rows row_time apart, so a camera must finish a frame's exposure
// and its readout (rows × row_time) within the period before the next begins. The loader's
// rule for `frames`, and the exposure_time_s override's.
std::string frameTimingProblem(const SceneDescription& scene);

// `displayName` names the text in messages; relative paths resolve against baseDir.
SceneDescription loadSceneFromText(const std::string& text, const std::string& displayName,
                                   const std::filesystem::path& baseDir,
                                   const LoadOptions& options = {});

}  // namespace camsim
