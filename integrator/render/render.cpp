#include "integrator/render/render.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "integrator/render/adaptive_sampling.h"
#include "integrator/render/aov_film.h"
#include "integrator/render/film.h"
#include "integrator/render/path_guide.h"
#include "integrator/render/pixel_sample.h"
#include "integrator/sampling/sobol_sampler.h"
#include "sensor/base/check.h"

namespace camsim {
namespace {

struct TileStats {
  std::uint64_t samples = 0, rejected = 0;
  RayCounts rays;
};

// A pixel checks options.cancel at its first sample and every kCancelStride samples after:
// a stop within a few milliseconds at any spp (64 paths), for one relaxed load per 64
// samples. (Checked only between tiles, a 48² image at 10⁵ spp went on for 17 s.)
constexpr int kCancelStride = 64;

bool cancelRequested(const RenderOptions& options) {
  return options.cancel && options.cancel->load(std::memory_order_relaxed);
}

// One pass's samples of a pixel: indices [first, end). The functions below are compiled for
// each concrete sampler (final classes), so that drawing a number is an inlined call, not a
// virtual one.
struct SampleRange {
  int first = 0, end = 0;
};

// What every pixel of a pass shares.
template <typename SamplerT>
struct TileContext {
  const Scene& scene;
  Film& film;
  const RenderOptions& options;
  const ModelledDimensions& dims;
  SamplerT& sampler;
  TileStats& stats;
  AovFilm& aovs;
  AovPixel& aovPixel;
  const PathGuide* guide;  // null: unguided (path_guide.h)
};

// Samples [range.first, range.end) of one pixel (pbrt-v4's EvaluatePixelSample, in a loop);
// AOVs only in the first pass (range.first = 0). False when cancelled part way.
template <typename SamplerT>
bool renderPixel(const TileContext<SamplerT>& t, glm::ivec2 pixel, SampleRange range) {
  const PhysicalCamera& camera = t.scene.camera();
  const float side = photositeSide(camera);
  const bool withAovs = range.first == 0 && t.aovs.enabled();  // the first pass's samples
  SamplerT& sampler = t.sampler;
  AovFilm& aovs = t.aovs;
  if (withAovs) aovs.startPixel(t.aovPixel, pixel);
  for (int s = range.first; s < range.end; ++s) {
    if ((s - range.first) % kCancelStride == 0 && cancelRequested(t.options)) return false;
    PixelSample ps = drawPixelSample(sampler, camera, t.dims, pixel, s, side);
    SampledWavelengths& lambda = ps.lambda;
    const CameraSample& cs = ps.camera;
    // The ground truth's depth and normals need the camera's pose at the sample's time:
    // computed once for the ray and for them.
    const bool sharePose = aovs.wantsCamera();
    glm::dmat4 pose;
    if (sharePose) pose = camera.worldFromCameraAt(cs.time);
    const glm::dmat4* posePtr = sharePose ? &pose : nullptr;
    const std::optional<CameraRay> cr =
        sharePose ? camera.generateRay(cs, lambda, pose) : camera.generateRay(cs, lambda);
    ++t.stats.samples;
    if (!cr) {
      if (withAovs) aovs.addNoRaySample(t.aovPixel, {cs.time, lambda, posePtr});
      continue;
    }
    countRay(RayKind::kCamera, cr->ray);
    // The spectral control variate's bins (spectral_control_variate.h); the camera weight is
    // the same at every wavelength when the film has a reference.
    SpectralBins cv;
    SpectralBins* const cvPtr = t.film.hasSpectralReference() ? &cv : nullptr;
    if (!withAovs) {
      const SampledSpectrum L =
          traceRadiance(t.scene, cr->ray, lambda, sampler, nullptr, t.guide, nullptr, cvPtr);
      if (cvPtr) cv *= cr->weight[0];
      if (!t.film.addSample(pixel, s, L * cr->weight, lambda, cvPtr)) ++t.stats.rejected;
      continue;
    }
    // The first hit is recorded in place, in the pixel's AOV record.
    VisibleSurface& visible = aovs.nextSurface(t.aovPixel);
    const SampledWavelengths lambdaAtCamera = lambda;  // before a dispersive hit ends some
    const SampledSpectrum L =
        traceRadiance(t.scene, cr->ray, lambda, sampler, &visible, t.guide, nullptr, cvPtr);
    if (cvPtr) cv *= cr->weight[0];
    if (!t.film.addSample(pixel, s, L * cr->weight, lambda, cvPtr)) ++t.stats.rejected;
    aovs.addSample(t.aovPixel, {cs.time, lambdaAtCamera, posePtr, &cr->ray});
  }
  if (withAovs) aovs.endPixel(t.aovPixel);
  t.film.setSamples(pixel, range.end);
  return true;
}

// One pass's samples of the tile lo ≤ p < hi. Adaptive (after the first pass): the active
// pixels go on to the next multiple of M (or the pass's end), the tile is checked there,
// and so on (adaptive_sampling.h). False when cancelled part way: the tile's pixels hold
// some of their samples only (render() sets them to 0).
template <typename SamplerT>
bool renderTile(const TileContext<SamplerT>& t, glm::ivec2 lo, glm::ivec2 hi, SampleRange range,
                AdaptiveState* adaptive) {
  if (!adaptive || range.first == 0) {
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x)
        if (!renderPixel(t, glm::ivec2(x, y), range)) return false;
    return true;
  }
  const int m = adaptive->settings().minSpp;
  for (int s = range.first; s < range.end;) {
    const int check = std::min((s / m + 1) * m, range.end);
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x)
        if (adaptive->active({x, y}) && !renderPixel(t, glm::ivec2(x, y), {s, check})) return false;
    if (!adaptive->check(t.film, lo, hi)) break;
    s = check;
  }
  return true;
}

void zeroRect(Image& image, const TileRect& r) {
  for (int y = r.lo.y; y < r.hi.y; ++y)
    for (int x = r.lo.x; x < r.hi.x; ++x)
      for (int c = 0; c < image.channelCount(); ++c) image.at(x, y, c) = 0.0f;
}

}  // namespace

int renderTileCount(glm::ivec2 resolution) {
  const int tilesX = (resolution.x + kRenderTileSize - 1) / kRenderTileSize;
  const int tilesY = (resolution.y + kRenderTileSize - 1) / kRenderTileSize;
  return tilesX * tilesY;
}

TileRect renderTileRect(glm::ivec2 resolution, int tile) {
  const int tilesX = (resolution.x + kRenderTileSize - 1) / kRenderTileSize;
  TileRect r;
  r.lo = glm::ivec2((tile % tilesX) * kRenderTileSize, (tile / tilesX) * kRenderTileSize);
  r.hi = glm::min(r.lo + kRenderTileSize, resolution);
  return r;
}

RenderResult render(const Scene& scene, const SpectralResponse& response,
                    const RenderOptions& options) {
  return render(scene, std::vector<const SpectralResponse*>{&response}, options);
}

const char* renderStopName(RenderStop stop) {
  switch (stop) {
    case RenderStop::kSpp:
      return "spp";
    case RenderStop::kTargetError:
      return "target_error";
    case RenderStop::kTimeLimit:
      return "time_limit";
    case RenderStop::kMaxSpp:
      return "max_spp";
    case RenderStop::kConverged:
      return "converged";
    case RenderStop::kCancelled:
      return "cancelled";
  }
  return "spp";
}

namespace {

double elapsedSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The spp after the next pass, or `spp` to stop (render.h: passes). elapsed: the render's
// seconds so far, for `spp` samples per pixel.
int nextPassEnd(const RenderOptions& o, int spp, const std::optional<ErrorMetrics>& estimate,
                double elapsed, RenderStop& stop) {
  if (!o.targetError && !o.timeLimitS) return spp;
  if (o.targetError && estimate && estimate->mrae <= *o.targetError) {
    stop = RenderStop::kTargetError;
    return spp;
  }
  if (spp >= o.maxSpp) {
    stop = RenderStop::kMaxSpp;
    return spp;
  }
  std::int64_t next = 2 * static_cast<std::int64_t>(spp);
  if (o.targetError && estimate) {
    const double ratio = estimate->mrae / *o.targetError;
    if (static_cast<double>(spp) * ratio * ratio > static_cast<double>(next)) next *= 2;
  }
  next = std::min<std::int64_t>(next, o.maxSpp);
  if (o.timeLimitS) {
    const double perSpp = elapsed / spp;  // s per sample per pixel, from the passes so far
    const double room = (*o.timeLimitS - elapsed) / std::max(perSpp, 1e-12);
    const std::int64_t fits = spp + static_cast<std::int64_t>(std::min(room, 1e9));
    if (fits <= spp) {
      stop = RenderStop::kTimeLimit;
      return spp;
    }
    next = std::min(next, fits);
  }
  return static_cast<int>(next);
}

}  // namespace

RenderResult render(const Scene& scene, const std::vector<const SpectralResponse*>& responses,
                    const RenderOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const glm::ivec2 res = scene.camera().resolution();
  ModelledDimensions dims = scene.modelled();
  dims.time = dims.time || options.forceTime;
  Film film(res, responses);
  AovFilm aovs(scene);
  const Share share = options.tiles;
  CAMSIM_CHECK(share.count >= 1 && share.index >= 0 && share.index < share.count);
  const int tileCount = share.itemsOf(renderTileCount(res));  // of this share
  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();

  const SamplerKind kind = options.sampler.value_or(scene.settings().sampler);
  tbb::enumerable_thread_specific<TileStats> perThread;
  std::atomic<int> tilesDone{0};
  std::mutex progressMutex;
  std::atomic<bool> cancelled{false};
  // Per tile of the share: it finished the current pass (a cancel zeroes the others).
  std::vector<std::uint8_t> finished(static_cast<std::size_t>(tileCount), 0);
  // Path guiding (integrator/render/path_guide.h): trained before the first pass, frozen.
  std::optional<PathGuide> guide;
  if (options.guiding.value_or(scene.settings().guiding))
    guide = PathGuide::train(scene, options.spp, options.seed, threads, options.cancel);
  const PathGuide* guidePtr = guide ? &*guide : nullptr;
  // The spectral control variate: unguided paths, a camera that treats every wavelength
  // alike, an emitting shape for the reference (spectral_control_variate.h).
  if (const Spectrum* reference = scene.spectralReference();
      reference && !guidePtr && scene.camera().wavelengthIndependent())
    film.setSpectralReference(*reference);
  dims.spectralControlVariate = film.hasSpectralReference();

  // Adaptive sampling: which pixels still take samples (adaptive_sampling.h).
  std::optional<AdaptiveState> adaptive;
  if (options.adaptive) adaptive.emplace(*options.adaptive, res);
  AdaptiveState* const adaptivePtr = adaptive ? &*adaptive : nullptr;

  // One pass over the share's tiles; prototype: a SobolSampler or an IndependentSampler,
  // copied per range of tiles.
  auto renderPass = [&](const auto& prototype, SampleRange samples) {
    tilesDone = 0;
    std::fill(finished.begin(), finished.end(), 0);
    tbb::parallel_for(tbb::blocked_range<int>(0, tileCount, 1),
                      [&](const tbb::blocked_range<int>& range) {
                        auto sampler = prototype;
                        AovPixel aovPixel;
                        const RayStatsScope rays(options.rayObserver);
                        TileStats& stats = perThread.local();
                        const TileContext<decltype(sampler)> context{
                            scene, film, options, dims, sampler, stats, aovs, aovPixel, guidePtr};
                        struct AddRays {  // on every exit, also a cancelled one
                          const RayStatsScope& scope;
                          TileStats& stats;
                          ~AddRays() { stats.rays += scope.rays(); }
                        } addRays{rays, stats};
                        for (int i = range.begin(); i != range.end(); ++i) {
                          if (cancelRequested(options)) {
                            cancelled = true;
                            return;
                          }
                          const TileRect rect = renderTileRect(res, share.item(i));
                          if (!renderTile(context, rect.lo, rect.hi, samples, adaptivePtr)) {
                            cancelled = true;
                            return;
                          }
                          finished[static_cast<std::size_t>(i)] = 1;
                          const int done = ++tilesDone;
                          if (options.progress) {
                            std::lock_guard<std::mutex> lock(progressMutex);
                            options.progress(done, tileCount);
                          }
                        }
                      });
  };
  const bool whole = share.count == 1;
  CAMSIM_CHECK(whole || (!options.targetError && !options.timeLimitS && !options.adaptive));
  RenderStats stats;
  stats.stop = RenderStop::kSpp;
  const bool inPasses = options.targetError || options.timeLimitS;
  std::optional<ErrorMetrics> estimate;  // in passes: the last pass's, which decides the next
  tbb::task_arena arena(threads);
  // Adaptive without passes: M samples everywhere first, then the rest adaptively.
  const int firstEnd =
      adaptive && !inPasses ? std::min(adaptive->settings().minSpp, options.spp) : options.spp;
  for (SampleRange pass{0, firstEnd}; pass.end > pass.first;) {
    arena.execute([&] {
      if (kind == SamplerKind::kSobol)
        renderPass(SobolSampler(options.seed), pass);
      else
        renderPass(IndependentSampler(options.seed), pass);
    });
    stats.spp = pass.end;
    ++stats.passes;
    if (cancelled) {
      stats.stop = RenderStop::kCancelled;
      break;
    }
    if (adaptive && pass.first == 0) adaptive->setImageMean(film.errorMean());
    if (inPasses && pass.end >= 2) estimate = film.estimateError(pass.end);
    // Every pixel converged: the next passes would trace nothing (found by probing: with a
    // target the threshold never met, passes doubled an empty spp up to max_spp and
    // reported 1048576 spp for pixels of at most 64 samples; a time limit never stopped it).
    if (inPasses && adaptive && !adaptive->anyActive()) {
      if (!(options.targetError && estimate && estimate->mrae <= *options.targetError))
        stats.stop = RenderStop::kConverged;
      else
        stats.stop = RenderStop::kTargetError;
      // The most samples a pixel got: the last pixels may have stopped at a check inside
      // this pass, before its end (found in review: 256 reported for pixels of at most 128).
      float most = 0.0f;
      for (const float count : film.sampleCountImage().pixels) most = std::max(most, count);
      stats.spp = static_cast<int>(most);
      break;
    }
    const int next = inPasses
                         ? nextPassEnd(options, pass.end, estimate, elapsedSince(start), stats.stop)
                         : options.spp;
    pass = {pass.end, next};
  }

  RenderResult result;
  result.stats = stats;
  result.images = film.toImages();
  if (stats.spp >= 2 && !cancelled) {
    result.oddHalf = film.oddHalfImage();
    if (!estimate &&
        whole)  // from the images just made (Film::estimateError would make them again)
      estimate = estimateFromHalves(result.images[film.errorImage()], film.errorImageChannel(),
                                    result.oddHalf, stats.spp);
    if (estimate) result.stats.estimatedError = ErrorEstimate{*estimate, film.errorChannel()};
  }
  if (adaptive) result.sampleCounts = film.sampleCountImage();
  if (aovs.enabled()) result.aovs = aovs.takeImage();
  // A cancelled render holds only the tiles that finished its last pass, each with all its
  // samples.
  for (int i = 0; cancelled && i < tileCount; ++i) {
    if (finished[static_cast<std::size_t>(i)]) continue;
    const TileRect r = renderTileRect(res, share.item(i));
    for (Image& image : result.images) zeroRect(image, r);
    if (!result.aovs.pixels.empty()) zeroRect(result.aovs, r);
    if (!result.sampleCounts.pixels.empty()) zeroRect(result.sampleCounts, r);
  }
  result.image = result.images.front();
  for (const TileStats& t : perThread) {
    result.stats.samples += t.samples;
    result.stats.rejectedSamples += t.rejected;
    result.stats.rays += t.rays;
  }
  const double sharePixels = [&] {
    double n = 0.0;
    for (int i = 0; i < tileCount; ++i) {
      const TileRect r = renderTileRect(res, share.item(i));
      n += static_cast<double>(r.hi.x - r.lo.x) * static_cast<double>(r.hi.y - r.lo.y);
    }
    return n;
  }();
  result.stats.meanSpp =
      sharePixels > 0.0 ? static_cast<double>(result.stats.samples) / sharePixels : 0.0;
  result.stats.threads = threads;
  if (guide) result.stats.guide = guide->stats();
  result.stats.modelled = dims;
  result.stats.cancelled = cancelled;
  result.stats.seconds = elapsedSince(start);
  return result;
}

}  // namespace camsim
