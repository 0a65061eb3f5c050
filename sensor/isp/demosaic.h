// Demosaicking: a one-channel Bayer mosaic → a full RGB image, every channel at every pixel.
// Each output value is a linear filter of the mosaic around the pixel,
//
//   v_c(x, y) = Σ_(dx,dy) k(dx, dy) · m(x + dx, y + dy)     (m = mosaic; own channel: v = m)
//
// with the kernel k chosen by the pixel's own CFA colour and the wanted colour c:
//   bilinear — the mean of the nearest samples of colour c: G at R/B: the 4 edge
//     neighbours (¼ each); R/B at G: the 2 neighbours in the row or the column holding that
//     colour (½ each); R at B and B at R: the 4 diagonal neighbours (¼ each).
//   Malvar–He–Cutler — H. S. Malvar, L.-W. He, R. Cutler, "High-quality linear
//     interpolation for demosaicing of Bayer-patterned color images", ICASSP 2004: the
//     bilinear estimate plus a gain times the Laplacian of the pixel's own channel
//     (gradient correction, α = ½, β = ⅝, γ = ¾), i.e. the paper's 5×5 kernels (× ⅛):
//       G at R/B:   centre 4, edge neighbours 2, distance-2 neighbours in the row and
//                   column −1
//       R/B at G, colour in the row: centre 5, (±1, 0) 4, (±2, 0) −1, diagonals −1,
//                   (0, ±2) +½ (colour in the column: the same, transposed)
//       R at B, B at R: centre 6, diagonals 2, distance-2 neighbours in row and column −3/2
//   Every kernel sums to 1 and its gradient-correction part to 0, so a constant colour
//   image is reproduced exactly.
// Borders are handled by mirroring about the edge photosite (x = −k reads x = k,
// x = W − 1 + k reads x = W − 1 − k): the mirrored photosite has the same CFA colour, so the
// interior kernels apply unchanged. No clipping: the gradient correction may overshoot
// slightly below 0 or above the input range near edges, as in the paper.
//
// | parameter | unit | default | meaning                                               |
// |-----------|------|---------|-------------------------------------------------------|
// | cfa       | —    | —       | RGGB, BGGR, GRBG or GBRG (2×2 tile of R, G, G, B)     |
// | method    | —    | —       | kBilinear or kMalvarHeCutler                          |
//
// Monochrome sensors (one channel) and stacked sensors (cfa "xyz": every photosite already
// records every channel) have nothing to interpolate: demosaic() returns their image
// unchanged. Any other non-Bayer tile (RGBW, RCCB, …) is an InputError.
#pragma once

#include "sensor/base/enum_names.h"
#include "sensor/base/image.h"
#include "sensor/model/cfa.h"

namespace camsim {

enum class DemosaicMethod { kBilinear, kMalvarHeCutler };
// The scene's `isp.demosaic` names, also Python's and the sidecar's
// (sensor/base/enum_names.h). "malvar-he-cutler" is an alias: sidecars before issue 35
// wrote it, so their `isp` block still reads.
template <>
struct EnumNames<DemosaicMethod> {
  static constexpr EnumName<DemosaicMethod> kTable[] = {
      {DemosaicMethod::kMalvarHeCutler, "malvar"},
      {DemosaicMethod::kBilinear, "bilinear"},
      {DemosaicMethod::kMalvarHeCutler, "malvar-he-cutler"}};
};

// A 2×2 tile with channels named R, G, B: one R, one B and two G on a diagonal.
bool isBayer(const CfaLayout& cfa);

// mosaic: one channel (e.g. normalizeRaw's output, optionally white-balanced). The result
// has cfa.channels as its channels (R, G, B for the standard layouts) and the same size.
Image demosaic(const Image& mosaic, const CfaLayout& cfa, DemosaicMethod method);

}  // namespace camsim
