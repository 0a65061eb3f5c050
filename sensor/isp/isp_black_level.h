// Black level and normalisation, the first ISP stage: digital numbers → signal relative
// to the usable range of the ADC, still one value per photosite (a mosaic for a CFA).
//
//   v(x, y) = (DN(x, y) − B) / (W − B)
//
// v = 0 is black, v = 1 the white level: a clipped photosite (DN = W, the ADC or the full
// well saturated there when the preset sets them together) is flagged by v ≥ 1
// (isClipped). Values below 0 (read noise, DSNU and FPN under the black level) are kept,
// so that the mean of a dark region stays unbiased; nothing is clipped or rescaled else.
//
// | parameter | unit | default (RawImage)   | meaning                         |
// |-----------|------|----------------------|---------------------------------|
// | B         | DN   | blackLevelDn = 0     | black level (offset, pedestal)  |
// | W         | DN   | whiteLevelDn = 65535 | white level (saturated output)  |
//
// The output channel is "CFA" for a mosaic (the CfaLayout travels with the RawImage) and
// the channel's own name for a monochrome sensor ("Y"). A stacked sensor (cfa "xyz")
// delivers one RawImage per channel: normalizeStackedRaw puts them side by side as one
// image with channels X, Y, Z, which needs no demosaicking.
#pragma once

#include <vector>

#include "sensor/base/image.h"
#include "sensor/model/raw_image.h"

namespace camsim {

// The normalised one-channel image. Throws InputError if W ≤ B or the sizes disagree.
Image normalizeRaw(const RawImage& raw);
// planes[c] is channel c (cfa.channels order) of a stacked sensor; all the same size.
Image normalizeStackedRaw(const std::vector<RawImage>& planes);

inline bool isClipped(float normalised) {
  return normalised >= 1.0f;
}

}  // namespace camsim
