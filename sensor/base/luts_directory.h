// Where camsim's luts/ folder is (spectral tables, camera curves, the OpenColorIO config):
// $CAMSIM_LUTS if set and non-empty, else the source tree's luts/ (CAMSIM_LUTS_DIR, fixed
// at build time). One place for every command (render, ptc, bench) and for the OCIO config.
#pragma once

#include <filesystem>

namespace camsim {

std::filesystem::path lutsDirectory();

// The 24 ColorChecker Classic reflectances the ISP fits its colour matrix on (developRaw,
// the DNG's matrices): lutsDirectory()/spectra/colorchecker_classic_reflectance.csv.
std::filesystem::path colorCheckerCsvPath();

}  // namespace camsim
