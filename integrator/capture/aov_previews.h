// Quick-look pictures of the ground-truth layers (camsim render --aov-previews), 8-bit
// false colour — for eyes, not for measurement (the EXR layers are the data):
//
// | file               | from                 | mapping |
// |--------------------|----------------------|---------|
// | NAME_depth.png     | depth.Z              | grey falling with log z from white (the covered pixels' 1st percentile) to 15 % (their 99th); no hit black |
// | NAME_normal.png    | N.X, N.Y, N.Z        | (n + 1) / 2 per axis (world axes) |
// | NAME_albedo.png    | albedo.R, .G, .B     | sRGB-encoded, clipped to [0, 1] |
// | NAME_instance.png, NAME_class.png, NAME_material.png | KIND.id | a colour per id (id 0 black) |
// | NAME_motion.png    | motion_fw.X, .Y      | hue: direction, saturation: length over the 99th percentile length |
// | NAME_amodal.png, NAME_visible.png | amodal_<n>.A, visible_<n>.A | each labelled shape's pixels (coverage ≥ ½) in its instance's colour (as NAME_instance.png), the mean colour where several overlap; none black |
// | NAME_valid.png     | valid.A              | grey: the fraction of the pixel inside the camera model's image (white inside, black outside) |
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sensor/base/image.h"

namespace camsim {

struct AovPreview {
  std::string suffix;  // e.g. "depth": written as NAME_depth.png
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  bool srgb = false;  // albedo only: the pixels are sRGB-encoded
};

// The previews of the layers present in `aovs` (an AovFilm image), in the table's order.
std::vector<AovPreview> aovPreviews(const Image& aovs);

}  // namespace camsim
