// Test helpers for the traced lens (integrator/camera/lens_*.h): the lens files of
// luts/lenses/ by name, and a lens from a prescription's text.
#pragma once

#include <filesystem>
#include <string>

#include "integrator/camera/lens_file.h"
#include "integrator/camera/lens_system.h"

namespace camsim::test {

inline std::filesystem::path lensPath(const std::string& name) {
  return std::filesystem::path(CAMSIM_SOURCE_DIR) / "luts" / "lenses" / name;
}

// A lens file as the camera takes it (LensSystem::forCamera: converging, finite pupils).
inline LensSystem cameraLens(const std::string& name) {
  return LensSystem::forCamera(readLensPrescription(lensPath(name)));
}

// Any prescription, unchecked (test.dat in messages).
inline LensSystem lensFromText(const std::string& text) {
  return LensSystem(parseLensPrescription(text, "test.dat"));
}

}  // namespace camsim::test
