// XYZ images in an RGB colour space (for the linear Rec.709 channels of NAME.exr):
//   xyzToRgb:  RGB = M_rgb←xyz · XYZ per pixel, units kept (no white adaptation).
// Pictures go through OpenColorIO (sensor/isp/color_management.h).
#pragma once

#include "sensor/base/image.h"
#include "sensor/spectra/color_space.h"

namespace camsim {

// Input: an image with channels named xName, yName, zName. Output: channels R, G, B.
Image xyzToRgb(const Image& xyz, const RgbColorSpace& space);

}  // namespace camsim
