// RawImage: what the sensor reports — digital numbers per photosite, with the CFA layout
// and levels needed to interpret them (the input of raw writers and of the ISP).
#pragma once

#include <cstdint>
#include <vector>

#include "sensor/model/cfa.h"

namespace camsim {

struct RawImage {
  int width = 0, height = 0;
  std::vector<std::uint16_t> dn;  // row-major, row 0 = top
  CfaLayout cfa;
  double blackLevelDn = 0.0;
  double whiteLevelDn = 65535.0;
  int adcBits = 16;

  std::uint16_t at(int x, int y) const {
    return dn[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)];
  }
};

}  // namespace camsim
