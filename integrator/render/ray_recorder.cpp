#include "integrator/render/ray_recorder.h"

#include <algorithm>
#include <chrono>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "integrator/geometry/shape.h"

namespace camsim {
namespace {

constexpr std::size_t kChunk = 16 * 16;  // rays per task: one 16×16 tile's worth

// One pass over all rays; returns its wall time. `hits` is the sink that keeps the
// compiler from dropping the queries.
double replayPass(const EmbreeScene& geometry, const std::vector<RecordedRay>& rays,
                  tbb::task_arena& arena, std::uint64_t& hits) {
  const std::size_t chunks = (rays.size() + kChunk - 1) / kChunk;
  tbb::combinable<std::uint64_t> found([] { return std::uint64_t{0}; });
  const auto start = std::chrono::steady_clock::now();
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        std::uint64_t local = 0;
                        for (std::size_t c = r.begin(); c != r.end(); ++c) {
                          const std::size_t end = std::min(rays.size(), (c + 1) * kChunk);
                          for (std::size_t i = c * kChunk; i < end; ++i) {
                            const RecordedRay& rr = rays[i];
                            if (rr.kind == RayKind::kShadow) {
                              local += geometry.occluded(rr.ray) ? 1u : 0u;
                            } else {
                              Hit hit;
                              local += geometry.intersect(rr.ray, hit) ? 1u : 0u;
                            }
                          }
                        }
                        found.local() += local;
                      });
  });
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  hits = found.combine([](std::uint64_t a, std::uint64_t b) { return a + b; });
  return seconds;
}

}  // namespace

struct RayRecorder::Buffers {
  tbb::enumerable_thread_specific<std::vector<RecordedRay>> perThread;
};

RayRecorder::RayRecorder(std::size_t maxRays)
    : maxRays_(maxRays), buffers_(std::make_unique<Buffers>()) {}

RayRecorder::~RayRecorder() = default;

void RayRecorder::record(RayKind kind, const Ray& ray) {
  if (taken_.fetch_add(1, std::memory_order_relaxed) >= maxRays_) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  buffers_->perThread.local().push_back(RecordedRay{ray, kind});
}

std::vector<RecordedRay> RayRecorder::takeRays() {
  std::size_t total = 0;
  for (const auto& buffer : buffers_->perThread) total += buffer.size();
  std::vector<RecordedRay> all;
  all.reserve(total);
  for (auto& buffer : buffers_->perThread) {
    all.insert(all.end(), buffer.begin(), buffer.end());
    std::vector<RecordedRay>().swap(buffer);
  }
  return all;
}

std::vector<RecordedRay> raysOfKind(const std::vector<RecordedRay>& rays, RayKind kind) {
  std::vector<RecordedRay> out;
  for (const RecordedRay& r : rays)
    if (r.kind == kind) out.push_back(r);
  return out;
}

ReplayResult replayRays(const EmbreeScene& geometry, const std::vector<RecordedRay>& rays,
                        int threads, double minSeconds, int minPasses) {
  ReplayResult result;
  result.rays = rays.size();
  if (rays.empty()) return result;
  tbb::task_arena arena(threads > 0 ? threads : tbb::info::default_concurrency());
  std::uint64_t hits = 0;
  replayPass(geometry, rays, arena, hits);  // warm-up: caches, TBB workers, page faults
  std::vector<double> times;
  double spent = 0.0;
  const auto passes = static_cast<std::size_t>(std::max(1, minPasses));
  while (times.size() < passes || (spent < minSeconds && times.size() < 50)) {
    times.push_back(replayPass(geometry, rays, arena, hits));
    spent += times.back();
  }
  result.seconds = *std::min_element(times.begin(), times.end());
  result.passes = static_cast<int>(times.size());
  result.hits = hits;
  return result;
}

}  // namespace camsim
