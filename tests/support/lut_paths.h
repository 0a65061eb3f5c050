// Test support: the look-up tables shipped in luts/ (CAMSIM_LUTS_DIR, camsim_sensor's
// public definition) and the ColorChecker chart the colour tests fit against.
#pragma once

#include <filesystem>

namespace camsim::test {

inline const std::filesystem::path kLuts(CAMSIM_LUTS_DIR);
inline const std::filesystem::path kColorChecker =
    kLuts / "spectra" / "colorchecker_classic_reflectance.csv";

}  // namespace camsim::test
