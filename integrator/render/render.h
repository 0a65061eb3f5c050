// render(): the render loop. The image is cut into 16×16 tiles that TBB schedules over
// the threads; each pixel sample draws its numbers from its own stream (seed, pixel,
// sample index), so the result is bit-identical for any thread count.
//
// Per pixel sample (dimension slots in sampler.h): wavelengths → film position, uniform
// over the photosite → lens position (only if the camera has an aperture) → time from the
// shutter curve, offset by the row for a rolling shutter (only if something moves) →
// camera ray and its measurement weight → traceRadiance → film.
//
// Tiles are numbered row by row from the top left: tile t covers x from (t % tilesX)·16 and
// y from (t / tilesX)·16, clipped to the image. RenderOptions::tiles renders a share of
// them (one frame split across processes: camsim render --tiles, docs/output.md): share k
// of M holds the tiles t with t % M == k — interleaved, so that every share gets some of
// each region of the image and the shares take about the same time. Its pixels are the
// whole render's, bit for bit, since a pixel's samples depend only on (seed, pixel, sample
// index); the other pixels stay 0, and the stats count its own samples only. A share may
// hold no tile (M larger than the tile count): an image of zeros.
//
// Error and passes (issue 38). Every render of ≥ 2 spp estimates its own error from its
// two half-sample images (error_estimate.h) into stats.estimatedError. With a target error
// or a time limit it renders in passes: the first of options.spp samples per pixel (the
// minimum; the AOVs come from these samples only), then more samples per pixel — indices
// n … n' − 1, so that after each pass the image is, bit for bit, the render at n' spp —
// until the estimate's MRAE is at most targetError, or the next pass would end after
// timeLimitS, or maxSpp is reached. With a target alone, pass totals are the first pass's
// spp times powers of two: n' = 2n or 4n, the smallest reaching n·(MRAE/target)² (MRAE
// falls as n^−½), so the same scene and seed stop at the same spp on any thread count. A
// time limit sizes the last pass from the rate so far, so where it stops depends on the
// machine; the image is still the render at the spp it reports.
//
// Adaptive sampling (options.adaptive; adaptive_sampling.h): the first pass takes M samples
// per pixel (in passes: spp), then each tile's pixels go on while their own estimated error
// is above the threshold, checked every M samples, up to options.spp (in passes: each pass's
// end). A pixel's value is the mean of its own samples 0 … n_p − 1.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "integrator/render/adaptive_sampling.h"
#include "integrator/render/error_estimate.h"
#include "integrator/render/path_guide.h"
#include "integrator/render/path_tracer.h"
#include "integrator/scene/scene.h"
#include "sensor/base/image.h"
#include "sensor/base/share.h"
#include "sensor/model/spectral_response.h"

namespace camsim {

constexpr int kRenderTileSize = 16;  // px per tile side

struct TileRect {
  glm::ivec2 lo{0}, hi{0};  // pixels lo ≤ p < hi
};
int renderTileCount(glm::ivec2 resolution);
TileRect renderTileRect(glm::ivec2 resolution, int tile);

struct RenderOptions {
  int spp = 16;
  std::uint64_t seed = 0;
  int threads = 0;  // 0 = all hardware threads
  // Called from worker threads (serialised) as tiles finish: (tiles done, tiles total).
  std::function<void(int, int)> progress;
  // When set, the render stops within 64 samples of every pixel in flight and reports
  // cancelled: the tiles that finished hold their values (all spp), the others are 0.
  const std::atomic<bool>* cancel = nullptr;
  // Sample time even when the scene analysis says nothing moves (for tests: the image
  // must not change).
  bool forceTime = false;
  // Overrides the scene's render.sampler (benchmarks compare samplers).
  std::optional<SamplerKind> sampler;
  // When set, sees every ray cast, from the thread that casts it (ray_stats.h; camsim
  // bench records them with a RayRecorder and replays them).
  RayObserver* rayObserver = nullptr;
  // The share of the tiles (above, numbered 0 … renderTileCount − 1) to render; the
  // others stay 0. Progress counts the share's tiles. Passes need the whole image (no share).
  Share tiles;
  // Passes (above): the estimated MRAE to reach, and the render time not to pass, s.
  std::optional<double> targetError;
  std::optional<double> timeLimitS;
  int maxSpp = 1 << 20;  // passes stop here (setting_ranges::kSpp's maximum)
  // Adaptive sampling (above); needs the whole image (no share).
  std::optional<AdaptiveSampling> adaptive;
  // Overrides the scene's render.guiding (integrator/render/path_guide.h): trains a guide
  // on a quarter of spp before the first pass; its time is in the render's.
  std::optional<bool> guiding;
};

// Why a render stopped adding samples.
// kConverged: in passes with adaptive sampling, every pixel reached the adaptive threshold,
// so further passes would add no samples.
enum class RenderStop { kSpp, kTargetError, kTimeLimit, kMaxSpp, kConverged, kCancelled };
const char* renderStopName(RenderStop stop);  // "spp", "target_error", …

struct RenderStats {
  double seconds = 0.0;
  std::uint64_t samples = 0;          // pixel samples traced
  std::uint64_t rejectedSamples = 0;  // NaN/Inf radiance, dropped from the film
  RayCounts rays;
  int threads = 0;
  bool cancelled = false;
  ModelledDimensions modelled;  // what was integrated over
  int spp = 0;                  // samples per pixel in the image (all passes; adaptive: the most)
  double meanSpp = 0.0;         // samples per pixel of the share, averaged (adaptive: < spp)
  int passes = 0;
  RenderStop stop = RenderStop::kSpp;
  // The image's estimate of its own error (error_estimate.h); none below 2 spp, for a share
  // of the tiles, or when cancelled.
  std::optional<ErrorEstimate> estimatedError;
  std::optional<GuideStats> guide;  // with path guiding: its training and memory

  double samplesPerSecond() const {
    return seconds > 0.0 ? static_cast<double>(samples) / seconds : 0.0;
  }
  double raysPerSecond() const {
    return seconds > 0.0 ? static_cast<double>(rays.total()) / seconds : 0.0;
  }
};

struct RenderResult {
  Image image;                // the first response's image (pixel means)
  std::vector<Image> images;  // one per response, in order
  Image aovs;                 // the scene's render.aovs (aov_film.h); empty without
  // The error channel's mean over the odd-indexed samples (Film::oddHalfImage), for a share
  // of the tiles to carry to the merge; empty below 2 spp.
  Image oddHalf;
  // Adaptive renders: each pixel's samples, one channel "spp"; empty otherwise.
  Image sampleCounts;
  RenderStats stats;
};

RenderResult render(const Scene& scene, const SpectralResponse& response,
                    const RenderOptions& options);
// Several responses filled by the same samples (e.g. CIE XYZ and a sensor's electrons).
RenderResult render(const Scene& scene, const std::vector<const SpectralResponse*>& responses,
                    const RenderOptions& options);

}  // namespace camsim
