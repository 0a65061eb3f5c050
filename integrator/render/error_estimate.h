// The relative error metrics (camsim bench's, docs/performance.md) and the estimate of a
// render's own error from two interleaved half-sample images (issue 38).
//
// | quantity | unit | meaning                                                          |
// |----------|------|------------------------------------------------------------------|
// | rmse     | —    | mean over pixels of e² / (r² + ε²), ε = 0.01 · mean(r)           |
// | mrae     | —    | mean over pixels of |e| / (|r| + ε)                               |
//
// e is a pixel's error and r its reference value, on one channel: luminance Y of the CIE
// XYZ film when the render has one, else the first response's first channel (a sensor's
// mosaic: each photosite's own). ε keeps black pixels from dominating: such a pixel counts
// like one at 1 % of the mean. The metrics do not depend on the film's absolute scale.
//
// The estimate. A pixel's n samples split by sample index into the even ones (A, n_A =
// ⌈n/2⌉ of them) and the odd ones (B, n_B = ⌊n/2⌋), independent draws of the same
// integrand (each sample has its own stream). With a, b their means and I = (A + B)/n the
// pixel's value, Var(a − b) = σ²(1/n_A + 1/n_B) while Var(I) = σ²/n, so
//
//   ê = (a − b) / √k,   k = n (1/n_A + 1/n_B)   (k = 4 for even n)
//
// has E[ê²] = Var(I): the pixel's mean squared error. For Gaussian pixel noise E|ê| also
// equals E|I − r|, so rmse and mrae above, with e = ê, estimate the render's errors against
// the converged image without one. For r the estimate takes r̂, the median of I over the
// pixel's 3×3 neighbourhood (the part inside the image): robust to the pixel's own noise and
// to fireflies, and it keeps edges. With r = I, a pixel whose samples caught a firefly
// divides its large ê² by the firefly's own large I², and the Cornell box's rMSE came out at
// 0.4–0.7 of its true value; with the mean of the 8 neighbours, dark pixels beside bright
// ones got large denominators (0.5–0.8 of it); with the median, 0.96–1.10 at 64 spp. The
// estimate needs n ≥ 2; with few samples the rMSE of one image is itself a wild draw (rare
// bright paths carry it) and the MRAE is the steadier of the two. The bench measures both
// against converged references (docs/performance.md, "Error estimate").
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "sensor/base/image.h"

namespace camsim {

struct ErrorMetrics {
  double rmse = 0.0;  // relative MSE (see above)
  double mrae = 0.0;  // mean relative absolute error
};

// The metrics over `count` pixels: error(i) and reference(i) give pixel i's e and r;
// refMean is the reference's mean (for ε).
template <typename ErrorAt, typename ReferenceAt>
ErrorMetrics relativeErrors(std::size_t count, ErrorAt error, ReferenceAt reference,
                            double refMean) {
  const double eps = 0.01 * std::abs(refMean) + std::numeric_limits<double>::min();
  double se = 0.0, ae = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const double e = error(i), r = reference(i);
    se += e * e / (r * r + eps * eps);
    ae += std::abs(e) / (std::abs(r) + eps);
  }
  const double n = count > 0 ? static_cast<double>(count) : 1.0;
  return {se / n, ae / n};
}

// A render's estimate of its own error (above), as RenderStats carries it.
struct ErrorEstimate {
  ErrorMetrics error;
  std::string channel;  // the channel it is on: "Y" (the XYZ film's), or the response's
};

// The estimate from a width × height image's pixel values I (every `stride`-th float, row
// by row) and the means b of their odd-indexed samples (contiguous), n ≥ 2 samples per
// pixel: the film's values as written, so that a render and the merge of its tile parts
// (which carry b) compute the same bits.
ErrorMetrics estimateFromHalves(const float* values, std::size_t stride, const float* oddMeans,
                                int width, int height, int samplesPerPixel);
// The same from images: channel `channel` of `image` and the one-channel `oddMeans`.
ErrorMetrics estimateFromHalves(const Image& image, int channel, const Image& oddMeans,
                                int samplesPerPixel);

}  // namespace camsim
