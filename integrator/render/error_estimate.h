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
// the converged image without one. The estimate needs n ≥ 2. What stands in for r, and for
// |e| in the MRAE, is the hard part where rare bright paths carry a pixel's value (a small
// lamp seen through a lens or lighting a room): a 16–256-spp pixel there is mostly its
// typical paths, with now and then one very bright one, and r is mostly the bright ones'
// mean. The rule, per pixel (windows: the part inside the image, the pixel itself left out):
//
// | quantity | window                  | definition                                          |
// |----------|-------------------------|-----------------------------------------------------|
// | m        | 3 × 3 (with the pixel)  | median of I: the typical paths (keeps edges)        |
// | s        | 3 × 3 (with the pixel)  | median of |ê|: the local noise                      |
// | h        | the pixel               | sign(I − m) · max(min(|I − m|, |ê|) − s, 0): rare   |
// | share    | 15 × 15, or smaller     | mean of h (below)                                   |
// | r̂        | 3 × 3 (carried pixels)  | m + share, at least 0; where h > max(0, 0.9 I) at   |
// |          |                         | least the neighbours' mean of I: the metrics' r     |
// | |e|      | 7 × 7, 15 × 15 halves   | max(|ê|, min(mean of h, 3 × least half mean of h))  |
//
// h is the part of a pixel's departure from m that its two halves disagree on (a firefly lands in
// one half: |ê| ≈ |I − m|; an edge or texture is in both: |ê| ≪ |I − m|) beyond the local noise
// (Gaussian noise adds nothing on average); its mean over a window is the rare paths' share of r,
// which m misses. The pixel's own h is left out, so that a firefly does not divide itself. Rare
// paths spread over a wall (a room lit by a small lamp) need the wide window; rare paths in a
// small cluster with sharp edges (a lamp's bokeh disc seen through a defocused lens) need a window
// no wider than the cluster, else their share is spread over the dark around it. So the share is
// the wide window's mean, or, where it is more, the mean over the smallest square window
// (3 × 3 … 13 × 13) that holds 4 other pixels with h > 0. At a cluster's edge even that window is
// half outside: a pixel carried by a rare path of its own (h > max(0, 0.9 I)) takes at least its
// neighbours' mean. The MRAE needs more: when neither half caught a rare path, |I − r| is that
// share while ê is 0 (for one rare kind of path E|ê| → E|I − r|/2), so |e| is at least the rare
// share nearby — but not across a cluster's edge: at most 3 × the least of the means over the four
// halves (left, right, top, bottom, each with the pixel's column or row) of the 15 × 15 window,
// which is small unless rare paths lie on every side. Memory: 24 bytes per pixel (three float
// images, a double and a 32-bit summed-area table). Measured (docs/performance.md, "Error
// estimate"; 128 px, 16–256 spp, both samplers, against 16384-spp references): in the bench's run
// est/true MRAE is within [0.79, 1.05] on cornell_box, motion_blur, metals_glass, small_light and
// dof_chart (over 16 seeds per cell the medians are 0.79–0.96; a draw that catches a lone lamp
// path goes down to 0.42 on dof_chart), rMSE within [0.70, 1.20] but for dof_chart with the
// independent sampler, whose true rMSE is carried by single rare paths into pixels at the edge of
// a bokeh disc (r ≈ 1/20 of the disc's; in the bench's render at 16 spp one such catch, of
// probability ≈ 0.4 % per such pixel and render, held 77 % of the rMSE): no estimate from the
// image knows that r. Before the cluster rules dof_chart's MRAE was 1.26–3.17× over, its rMSE up
// to 317×. Over is the safe side for the passes (they take more samples).
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
    if (e == 0.0) continue;  // also where r = 0 and ε underflows (a black image): 0, not 0/0
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
