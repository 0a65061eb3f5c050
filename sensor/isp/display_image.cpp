#include "sensor/isp/display_image.h"

#include <algorithm>
#include <cmath>

namespace camsim {
namespace {

std::array<int, 3> xyzChannels(const Image& image) {
  const std::array<int, 3> c{image.channelIndex("X"), image.channelIndex("Y"),
                             image.channelIndex("Z")};
  CAMSIM_CHECK(c[0] >= 0 && c[1] >= 0 && c[2] >= 0);
  return c;
}

}  // namespace

Image xyzToRgb(const Image& xyz, const RgbColorSpace& space) {
  const auto c = xyzChannels(xyz);
  Image rgb(xyz.width, xyz.height, {"R", "G", "B"});
  const glm::dmat3& m = space.rgbFromXyz();
  for (int y = 0; y < xyz.height; ++y)
    for (int x = 0; x < xyz.width; ++x) {
      const glm::dvec3 v =
          m * glm::dvec3(xyz.at(x, y, c[0]), xyz.at(x, y, c[1]), xyz.at(x, y, c[2]));
      for (int k = 0; k < 3; ++k) rgb.at(x, y, k) = static_cast<float>(v[k]);
    }
  return rgb;
}

}  // namespace camsim
