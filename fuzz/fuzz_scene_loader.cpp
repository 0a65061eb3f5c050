// libFuzzer harness: scene files (YAML / JSON) → camsim::loadSceneFromText
// (integrator/scene/scene_loader.h). Bad input must end in InputError; anything else (crash,
// sanitizer report, another exception, an abort) is a finding.
//
// Relative paths in the scene (mesh files, CSV tables) resolve against an empty private
// directory made once per process (mkdtemp) and removed at exit; the loader may still read
// files named by absolute or `..` paths and the installed luts/spectra/ tables, which is
// what a user's scene can do too. Neither the loader nor this harness writes files.
#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#include "fuzz/fuzz_check.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"

namespace {

std::filesystem::path gBaseDir;

void removeBaseDir() {
  std::error_code ignored;
  std::filesystem::remove(gBaseDir, ignored);  // only if still empty
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::string pattern =
      (std::filesystem::temp_directory_path() / "camsim_fuzz_scene_XXXXXX").string();
  FUZZ_CHECK(::mkdtemp(pattern.data()) != nullptr);
  gBaseDir = pattern;
  std::atexit(removeBaseDir);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const camsim::SceneDescription desc = camsim::loadSceneFromText(text, "fuzz.yaml", gBaseDir);
    // What the loader promises before anything is rendered (scene_loader.h, SceneLimits).
    FUZZ_CHECK(!desc.shapes.empty());
    FUZZ_CHECK(desc.camera.resolution.x >= 1 && desc.camera.resolution.y >= 1);
    FUZZ_CHECK(desc.camera.resolution.x <= camsim::SceneLimits::kMaxResolution &&
               desc.camera.resolution.y <= camsim::SceneLimits::kMaxResolution);
    FUZZ_CHECK(std::int64_t{desc.camera.resolution.x} * desc.camera.resolution.y <=
               camsim::SceneLimits::kMaxPixels);
    FUZZ_CHECK(desc.render.spp >= 1 && desc.render.spp <= camsim::SceneLimits::kMaxSpp);
    for (const auto& shape : desc.shapes) {
      FUZZ_CHECK(shape.material >= -1 && shape.material < static_cast<int>(desc.materials.size()));
      if (shape.kind == camsim::ShapeDescription::Kind::kMesh)
        camsim::fuzz::checkMesh(shape.sharedMesh ? *shape.sharedMesh : shape.mesh);  // instances
      else
        FUZZ_CHECK(std::isfinite(shape.radius) && shape.radius > 0.0f);
    }
  } catch (const camsim::InputError&) {
  }
  return 0;
}
