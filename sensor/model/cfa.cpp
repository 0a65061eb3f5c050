#include "sensor/model/cfa.h"

#include "sensor/base/input_error.h"

namespace camsim {

CfaLayout CfaLayout::fromName(const std::string& name) {
  const std::vector<std::string> rgb = {"R", "G", "B"};
  constexpr int R = 0, G = 1, B = 2;
  // Tiles are row-major: {(0,0), (1,0), (0,1), (1,1)} as (x, y).
  if (name == "RGGB") return {2, 2, {R, G, G, B}, rgb, name};
  if (name == "BGGR") return {2, 2, {B, G, G, R}, rgb, name};
  if (name == "GRBG") return {2, 2, {G, R, B, G}, rgb, name};
  if (name == "GBRG") return {2, 2, {G, B, R, G}, rgb, name};
  if (name == "mono") return {1, 1, {0}, {"Y"}, name};
  if (name == "xyz") return {1, 1, {0}, {"X", "Y", "Z"}, name};
  throw InputError({}, "cfa",
                   "unknown CFA layout '" + name +
                       "' (known: RGGB, BGGR, GRBG, GBRG, mono, xyz, "
                       "or a custom {tile: [[...], ...], channels: [...]})");
}

}  // namespace camsim
