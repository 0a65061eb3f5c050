#include "integrator/scene/setting_ranges.h"

#include "sensor/base/format.h"

namespace camsim {
std::string SettingRange::text() const {
  return formatRange(lo, hi, loOpen);
}

std::string IntegerRange::text() const {
  return "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}

}  // namespace camsim
