#include "integrator/render/path_guide.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "integrator/render/path_tracer.h"
#include "integrator/render/pixel_sample.h"
#include "integrator/render/render.h"
#include "integrator/sampling/sampler.h"
#include "integrator/scene/scene.h"

namespace camsim {
namespace {

constexpr float kInvFourPi = 0.0795774715459476679f;
// Tiles, and samples per pixel, traced between two insertions of their records: bound the
// records held at once to 32 tiles × 16² px × 32 spp × ≈ 4 vertices × 40 bytes ≈ 42 MB at
// any spp (an iteration of more samples is traced in chunks of kChunkSpp; without them a
// 16384-spp render held 2048 spp of records per tile, 84 MB each). A chunk of a tile is
// also how long a cancel waits.
constexpr int kBatchTiles = 32;
constexpr int kChunkSpp = 32;
constexpr std::uint64_t kGuideSeedSalt = 0x6775696465ull;  // "guide"

// One training iteration's samples [first, end) of a tile's pixels, their camera samples
// drawn as the render's (pixel_sample.h), traced with `guide` (null: the BSDF alone) into
// `records` in pixel and sample order.
void traceTile(const Scene& scene, const TileRect& rect, int first, int end,
               IndependentSampler& sampler, const PathGuide* guide,
               std::vector<GuideRecord>& records) {
  const PhysicalCamera& camera = scene.camera();
  const ModelledDimensions& dims = scene.modelled();
  const float side = photositeSide(camera);
  GuideRecorder recorder;
  recorder.out = &records;
  for (int y = rect.lo.y; y < rect.hi.y; ++y) {
    for (int x = rect.lo.x; x < rect.hi.x; ++x) {
      const glm::ivec2 pixel(x, y);
      for (int s = first; s < end; ++s) {
        PixelSample ps = drawPixelSample(sampler, camera, dims, pixel, s, side);
        SampledWavelengths& lambda = ps.lambda;
        const CameraSample& cs = ps.camera;
        const std::optional<CameraRay> cr = camera.generateRay(cs, lambda);
        if (!cr) continue;
        traceRadiance(scene, cr->ray, lambda, sampler, nullptr, guide, &recorder);
      }
    }
  }
}

}  // namespace

float PathGuide::pdf(const DirectionalQuadtree& d, const glm::vec3& w) {
  return d.pdf(directionToSquare(w)) * kInvFourPi;
}

glm::vec3 PathGuide::sample(const DirectionalQuadtree& d, glm::vec2 u, float* pdf) {
  float density = 0.0f;
  const glm::vec3 w = squareToDirection(d.sample(u, &density));
  *pdf = density * kInvFourPi;
  return w;
}

std::uint64_t PathGuide::trainingBytes(glm::ivec2 resolution, int spp, int maxDepth) {
  const int budget = std::max(1, spp / 4);
  int last = 1, total = 1;  // the largest iteration's samples per pixel, as train's loop
  while (total + 2 * last <= budget) {
    last *= 2;
    total += last;
  }
  const auto tiles = static_cast<std::uint64_t>(std::min(renderTileCount(resolution), kBatchTiles));
  const auto samples = static_cast<std::uint64_t>(std::min(last, kChunkSpp));
  const auto vertices = static_cast<std::uint64_t>(std::clamp(maxDepth, 1, 8));
  return tiles * static_cast<std::uint64_t>(kRenderTileSize * kRenderTileSize) * samples *
         vertices * sizeof(GuideRecord);
}

PathGuide PathGuide::train(const Scene& scene, int spp, std::uint64_t seed, int threads,
                           const std::atomic<bool>* cancel) {
  const auto cancelled = [cancel] { return cancel && cancel->load(std::memory_order_relaxed); };
  const auto start = std::chrono::steady_clock::now();
  // The scene's bounds (all geometry, all time steps), 0.1 % larger: no vertex on a face.
  const glm::vec3 lo = scene.geometry().boundsLower(), hi = scene.geometry().boundsUpper();
  const glm::vec3 pad = 1e-3f * glm::max(hi - lo, glm::vec3(0.0f)) + 1e-6f;
  PathGuide guide(SDTree(lo - pad, glm::max(hi, lo) + pad));
  const glm::ivec2 res = scene.camera().resolution();
  const int tileCount = renderTileCount(res);
  const IndependentSampler prototype(hashValues(seed, kGuideSeedSalt));
  tbb::task_arena arena(threads > 0 ? threads : tbb::info::default_concurrency());
  const int budget = std::max(1, spp / 4);
  std::vector<std::vector<GuideRecord>> records(static_cast<std::size_t>(kBatchTiles));
  int first = 0;  // sample index: each iteration draws new streams
  for (int k = 0; k < 30; ++k) {
    const int n = 1 << k;
    if (k > 0 && first + n > budget) break;
    // Iteration 0 samples the BSDF alone (the guide is still empty everywhere anyway).
    const PathGuide* sampling = k == 0 ? nullptr : &guide;
    for (int chunk = first; chunk < first + n; chunk += kChunkSpp) {
      const int chunkEnd = std::min(first + n, chunk + kChunkSpp);
      for (int batch = 0; batch < tileCount; batch += kBatchTiles) {
        const int batchEnd = std::min(tileCount, batch + kBatchTiles);
        arena.execute([&] {
          tbb::parallel_for(
              tbb::blocked_range<int>(batch, batchEnd, 1),
              [&](const tbb::blocked_range<int>& range) {
                IndependentSampler sampler = prototype;
                for (int t = range.begin(); t != range.end(); ++t) {
                  std::vector<GuideRecord>& out = records[static_cast<std::size_t>(t - batch)];
                  out.clear();
                  if (cancelled()) continue;
                  traceTile(scene, renderTileRect(res, t), chunk, chunkEnd, sampler, sampling, out);
                }
              });
        });
        // A cancelled render writes nothing: the guide is left as it is, the render's
        // first pass sees the cancel too.
        if (cancelled()) break;
        // Chunk, tile, then each tile's own order: the same sums for any thread count.
        for (int t = batch; t < batchEnd; ++t)
          for (const GuideRecord& r : records[static_cast<std::size_t>(t - batch)]) {
            guide.tree_.record(r.p, r.square, r.weight, r.source, r.sourceWeight);
            ++guide.stats_.records;
          }
      }
      if (cancelled()) break;
    }
    if (cancelled()) break;
    guide.tree_.refine(k);
    first += n;
    ++guide.stats_.iterations;
  }
  guide.tree_.freeze();
  guide.stats_.trainSpp = first;
  guide.stats_.leaves = guide.tree_.leafCount();
  guide.stats_.bytes = guide.tree_.bytes();
  guide.stats_.trainSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return guide;
}

}  // namespace camsim
