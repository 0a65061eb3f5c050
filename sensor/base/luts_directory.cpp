#include "sensor/base/luts_directory.h"

#include <cstdlib>

namespace camsim {

std::filesystem::path lutsDirectory() {
  if (const char* env = std::getenv("CAMSIM_LUTS"); env && *env) return env;
  return CAMSIM_LUTS_DIR;
}

std::filesystem::path colorCheckerCsvPath() {
  return lutsDirectory() / "spectra" / "colorchecker_classic_reflectance.csv";
}

}  // namespace camsim
