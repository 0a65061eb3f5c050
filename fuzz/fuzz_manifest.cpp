// libFuzzer harness: dataset manifests → camsim::parseManifest and resolveItem
// (integrator/dataset/manifest.h, dataset_item.h). Bad input must end in InputError;
// anything else (crash, sanitizer report, another exception, an abort) is a finding.
//
// The manifest's `scene:` resolves against a private directory made once per process
// (mkdtemp) holding one small base scene, base.yaml, written at start and removed at exit.
// The first eight items are resolved (key-path edits applied, the scene loaded).
#include <stdlib.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "fuzz/fuzz_check.h"
#include "integrator/dataset/dataset_item.h"
#include "sensor/base/input_error.h"

namespace {

std::filesystem::path gBaseDir;

void removeBaseDir() {
  std::error_code ignored;
  std::filesystem::remove_all(gBaseDir, ignored);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::string pattern =
      (std::filesystem::temp_directory_path() / "camsim_fuzz_manifest_XXXXXX").string();
  FUZZ_CHECK(::mkdtemp(pattern.data()) != nullptr);
  gBaseDir = pattern;
  std::atexit(removeBaseDir);
  std::ofstream(gBaseDir / "base.yaml")
      << "format: camsim-scene/1\nname: probe\nrender: {spp: 4}\n"
         "camera: {position: [0, 0, -3], look_at: [0, 0, 0], resolution: [16, 16]}\n"
         "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
         "shapes:\n"
         "  - {name: ball, type: sphere, centre: [0, 0, 0], radius: 1, material: grey}\n"
         "  - {name: lamp, type: sphere, centre: [0, 2, 0], radius: 0.5, emission: {luminance: "
         "10}}\n";
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const camsim::Manifest m = camsim::parseManifest(text, "fuzz.yaml", gBaseDir);
    FUZZ_CHECK(!m.items.empty());
    for (std::size_t i = 0; i < m.items.size() && i < 8; ++i) {
      FUZZ_CHECK(m.items[i].index == i);
      const camsim::ResolvedItem r = camsim::resolveItem(m, m.items[i], "");
      FUZZ_CHECK(r.hash.size() == 16);
      FUZZ_CHECK(!r.description.shapes.empty());
    }
  } catch (const camsim::InputError&) {
  }
  return 0;
}
