#include "sensor/base/luts_directory.h"

#include <cstdlib>

namespace camsim {

std::filesystem::path lutsDirectory() {
  if (const char* env = std::getenv("CAMSIM_LUTS"); env && *env) return env;
  return CAMSIM_LUTS_DIR;
}

}  // namespace camsim
