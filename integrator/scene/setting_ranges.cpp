#include "integrator/scene/setting_ranges.h"

#include <cstdio>

namespace camsim {
namespace {

// As the scene loader prints a bound (yaml_reader.cpp): 0.5, 10000, 1e+30.
std::string bound(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

}  // namespace

std::string SettingRange::text() const {
  return (loOpen ? "(" : "[") + bound(lo) + ", " + bound(hi) + "]";
}

std::string IntegerRange::text() const {
  return "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}

}  // namespace camsim
