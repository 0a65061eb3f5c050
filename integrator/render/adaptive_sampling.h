// Adaptive sampling (issue 38, part 3): pixels stop taking samples once their own estimated
// error is small enough, so the samples go where the noise is. Cycles' metric is the anchor.
//
// | parameter | scene key                 | unit | default         | meaning                      |
// |-----------|---------------------------|------|-----------------|------------------------------|
// | T         | render.adaptive_threshold | —    | none (off)      | the error a pixel stops at   |
// | M         | render.adaptive_min_spp   | —    | max(4, √N) even | samples before, and between, |
// |           |                           |      |                 | the checks                   |
// | N         | render.spp                | —    | 64              | the most samples of a pixel  |
//
// The render first takes M samples in every pixel (one pass over the whole image; the AOVs
// come from these samples), and Ī, the mean of the error channel (the film's Y) over the
// image, is taken from them. Each tile then goes on by itself: its pixels that are still
// active take samples up to the next multiple of M (or N), and at that check a pixel p with
// n samples, value I_p and odd-indexed samples' mean b_p scores
//
//   e_p = |I_p − b_p| / √(Ī · (|I_p| + 0.01 Ī))
//
// — Cycles' |I − A| / √I on the image scaled to mean 1 (so T does not depend on the film's
// absolute units), with the bench's ε = 1 % of the mean keeping black pixels finite. For
// even n, |I − b| = |a − b|/2 = |ê|, the pixel's estimated standard error (error_estimate.h):
// a pixel as bright as the image's mean stops at a relative error of about T, one 4× darker
// at about 2T, one 4× brighter at T/2 (as Cycles' √I weighting). A pixel is converged when
// e_p < T; it stays active while it or any pixel of its 3 × 3 neighbourhood in the tile is
// not (Cycles' dilation: a pixel whose estimate came out low by chance keeps sampling beside
// a noisy neighbour). A pixel that stops never restarts. The checks use only the tile's own
// pixels, in a fixed order, after a fixed sample count, so the result is the same on any
// thread count; Ī = 0 (an image black after M samples) leaves every pixel active.
//
// Every pixel's value is still the mean of its own samples: indices 0 … n_p − 1, the same
// numbers a fixed-spp render draws, so a pixel that runs to N equals the fixed-N render's
// bit for bit. Stopping on the samples' own estimate makes the mean slightly biased towards
// values whose halves agree (all adaptive samplers share this; Cycles too); the bias is
// measured in tests/integrator/render/adaptive_sampling_test.cpp and docs/performance.md.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "integrator/render/film.h"

namespace camsim {

struct AdaptiveSampling {
  double threshold = 0.01;  // T
  int minSpp = 16;          // M, even, ≥ 2
};

// M for N samples per pixel: the setting when given (≠ 0), else max(4, ⌈√N⌉) rounded up to
// even.
int adaptiveMinSppFor(int spp, int minSppSetting);

// The per-pixel state of an adaptive render: which pixels still take samples.
class AdaptiveState {
 public:
  AdaptiveState(AdaptiveSampling settings, glm::ivec2 resolution);

  const AdaptiveSampling& settings() const { return settings_; }
  // Ī, from the first pass's film.
  void setImageMean(double mean) { imageMean_ = mean; }
  bool active(glm::ivec2 pixel) const { return active_[index(pixel)] != 0; }
  // The check of the active pixels of the tile lo ≤ p < hi after their samples so far (the
  // film's): marks the converged ones inactive, keeping the 3 × 3 dilation. Returns whether
  // any stays active.
  bool check(const Film& film, glm::ivec2 lo, glm::ivec2 hi);
  // Whether any pixel still takes samples (between passes: every tile has been checked).
  bool anyActive() const;

 private:
  std::size_t index(glm::ivec2 p) const {
    return static_cast<std::size_t>(p.y) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(p.x);
  }

  AdaptiveSampling settings_;
  int width_ = 0;
  double imageMean_ = 0.0;
  std::vector<std::uint8_t> active_;  // per pixel; each written by its own tile only
};

}  // namespace camsim
