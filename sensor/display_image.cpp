#include "sensor/display_image.h"

#include <algorithm>
#include <cmath>

namespace camsim {
namespace {

std::array<int, 3> xyzChannels(const Image& image) {
  const std::array<int, 3> c{image.channelIndex("X"), image.channelIndex("Y"), image.channelIndex("Z")};
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
      const glm::dvec3 v = m * glm::dvec3(xyz.at(x, y, c[0]), xyz.at(x, y, c[1]), xyz.at(x, y, c[2]));
      for (int k = 0; k < 3; ++k) rgb.at(x, y, k) = static_cast<float>(v[k]);
    }
  return rgb;
}

QuickLook quickLookSrgb8(const Image& xyz) {
  const auto c = xyzChannels(xyz);
  double sumY = 0.0;
  size_t finite = 0;
  for (int y = 0; y < xyz.height; ++y)
    for (int x = 0; x < xyz.width; ++x)
      if (const float v = xyz.at(x, y, c[1]); std::isfinite(v)) {
        sumY += static_cast<double>(v);
        ++finite;
      }
  const double meanY = finite > 0 ? sumY / static_cast<double>(finite) : 0.0;
  QuickLook out;
  out.exposure = meanY > 0.0 ? 0.18 / meanY : 1.0;
  const Image rgb = xyzToRgb(xyz, RgbColorSpace::linearRec709());
  out.rgb8.resize(rgb.pixels.size());
  for (size_t i = 0; i < rgb.pixels.size(); ++i) {
    const double v = std::clamp(static_cast<double>(rgb.pixels[i]) * out.exposure, 0.0, 1.0);
    out.rgb8[i] = static_cast<std::uint8_t>(std::lround(srgbEncode(std::isfinite(v) ? v : 0.0) * 255.0));
  }
  return out;
}

}  // namespace camsim
