// Image: a plain float image, the data every stage hands to the next and every writer
// takes. Channels are interleaved, rows top to bottom (row 0 is the top of the picture).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "sensor/base/check.h"

namespace camsim {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::string> channels;  // e.g. {"R","G","B"} or {"XYZ.X","XYZ.Y","XYZ.Z"}
  std::vector<float> pixels;          // width·height·channels.size()

  Image() = default;
  Image(int w, int h, std::vector<std::string> names)
      : width(w),
        height(h),
        channels(std::move(names)),
        pixels(static_cast<size_t>(w) * static_cast<size_t>(h) * channels.size(), 0.0f) {
    CAMSIM_CHECK(w >= 0 && h >= 0);
  }

  int channelCount() const { return static_cast<int>(channels.size()); }
  size_t index(int x, int y, int c) const {
    return (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) *
               channels.size() +
           static_cast<size_t>(c);
  }
  float& at(int x, int y, int c) { return pixels[index(x, y, c)]; }
  float at(int x, int y, int c) const { return pixels[index(x, y, c)]; }
  // -1 if absent.
  int channelIndex(const std::string& name) const {
    for (size_t i = 0; i < channels.size(); ++i)
      if (channels[i] == name) return static_cast<int>(i);
    return -1;
  }
  // Channel c alone, as a one-channel image named `name` (default: its own name).
  Image channel(int c, std::string name = {}) const {
    CAMSIM_CHECK(c >= 0 && c < channelCount());
    Image out(width, height, {name.empty() ? channels[static_cast<size_t>(c)] : std::move(name)});
    const size_t n = channels.size();
    for (size_t p = 0; p < out.pixels.size(); ++p)
      out.pixels[p] = pixels[p * n + static_cast<size_t>(c)];
    return out;
  }
};

// String key/value metadata written as EXR header attributes (and JSON sidecars later).
using Metadata = std::vector<std::pair<std::string, std::string>>;

// The value of `key` (the first entry of that name), or null.
inline const std::string* findMetadata(const Metadata& meta, const std::string& key) {
  for (const auto& [k, v] : meta)
    if (k == key) return &v;
  return nullptr;
}

}  // namespace camsim
