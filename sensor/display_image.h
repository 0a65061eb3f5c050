// Conversions of absolute XYZ images for output, before OpenColorIO takes over (later).
//
//   xyzToRgb:  RGB = M_rgb←xyz · XYZ  (per pixel; units kept: Y = 1 cd/m² ↔ luminance 1)
//   quickLookSrgb8: exposure k = 0.18 / mean(Y) over finite pixels (mean luminance → mid-grey), then
//     linear Rec.709 = k · M · XYZ, clipped to [0, 1], sRGB-encoded, rounded to 8 bits.
#pragma once

#include <cstdint>
#include <vector>

#include "sensor/color_space.h"
#include "sensor/image.h"

namespace camsim {

// Input: an image with channels named xName, yName, zName. Output: channels R, G, B.
Image xyzToRgb(const Image& xyz, const RgbColorSpace& space);

struct QuickLook {
  std::vector<std::uint8_t> rgb8;  // width·height·3, sRGB-encoded
  double exposure = 0.0;           // k, multiplier applied to the absolute values
};
// Image with channels X, Y, Z (absolute) → 8-bit sRGB picture for a quick look.
QuickLook quickLookSrgb8(const Image& xyz);

}  // namespace camsim
