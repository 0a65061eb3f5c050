// CfaLayout: which spectral channel each photosite sees, as a repeating tile of channel
// indices — data, so RGBW, RCCB or any other pattern is just another tile.
//   channelAt(x, y) = tile[(y mod h)·w + (x mod w)],  (x, y) = (column, row), row 0 = top.
// One special layout is not a mosaic: "xyz" (1×1 tile, channels X, Y, Z) is a stacked
// sensor where every photosite records all three channels (the ideal-xyz preset). For it
// isStacked() is true and channelAt() is meaningless (always 0): the film stores three
// values per pixel and the sensor model is applied to each channel's image separately.
#pragma once

#include <string>
#include <vector>

namespace camsim {

struct CfaLayout {
  int width = 1, height = 1;                  // tile size, photosites
  std::vector<int> tile = {0};                // channel index per tile position, row-major
  std::vector<std::string> channels = {"Y"};  // channel names ("R", "G", "B", …)
  std::string name = "mono";                  // "RGGB", "BGGR", "GRBG", "GBRG", "mono" or custom

  int channelAt(int x, int y) const {
    return tile[static_cast<size_t>((y % height) * width + (x % width))];
  }
  bool isMonochrome() const { return channels.size() == 1; }
  bool isStacked() const { return name == "xyz"; }

  // The four Bayer layouts (channels R, G, B), "mono" (channel Y) and "xyz" (stacked,
  // channels X, Y, Z); InputError (without a location) for another name.
  static CfaLayout fromName(const std::string& name);
};

}  // namespace camsim
