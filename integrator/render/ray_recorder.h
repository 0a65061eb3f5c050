// RayRecorder: captures the rays the path tracer casts during one render (camera, bounce
// and shadow rays, with their tMax and time), so that `camsim bench` can replay exactly
// that workload through EmbreeScene alone and compare the tracer's ray rate with the rate
// of bare traversal ("the limit"). It is a RayObserver (ray_stats.h), hooked in through
// RenderOptions::rayObserver; none (the default) costs one branch per ray.
//
// Thread safety: record() may be called from any number of TBB worker threads at once.
// Each thread appends to its own buffer (no locks, no shared cache lines but one counter;
// the buffers are TBB thread-local storage, kept in ray_recorder.cpp so that this header
// exposes no TBB type; record() is a call per ray, paid only while recording),
// so each buffer holds the rays of the tiles that thread rendered in the order it cast
// them — the coherence the tracer saw. takeRays() concatenates the buffers.
//
// replayRays() traces recorded rays again with EmbreeScene::intersect / occluded (closest
// hit for camera and bounce rays, any hit for shadow rays), in chunks of 256 consecutive
// rays (one 16×16 tile's worth) scheduled by tbb::parallel_for in a task_arena of the
// given thread count. Only the traversal loop is timed: the rays are in memory already,
// and nothing is shaded.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "integrator/geometry/embree_scene.h"
#include "integrator/geometry/ray.h"
#include "integrator/render/ray_stats.h"

namespace camsim {

struct RecordedRay {
  Ray ray;
  RayKind kind = RayKind::kCamera;
};

class RayRecorder final : public RayObserver {
 public:
  // Keeps at most maxRays rays (those past it are counted in dropped(), not stored).
  explicit RayRecorder(std::size_t maxRays = std::size_t{1} << 22);
  ~RayRecorder();
  RayRecorder(const RayRecorder&) = delete;
  RayRecorder& operator=(const RayRecorder&) = delete;

  void record(RayKind kind, const Ray& ray);
  void observe(RayKind kind, const Ray& ray) override { record(kind, ray); }

  // Every stored ray, each thread's in the order that thread cast them. Call once, after the
  // render: each thread's buffer is freed once appended (not kept beside the result; while
  // concatenating, both exist), and the recorder keeps nothing.
  std::vector<RecordedRay> takeRays();
  std::uint64_t dropped() const { return dropped_.load(); }

 private:
  std::size_t maxRays_;
  std::atomic<std::size_t> taken_{0};
  std::atomic<std::uint64_t> dropped_{0};
  struct Buffers;  // one std::vector<RecordedRay> per thread (ray_recorder.cpp)
  std::unique_ptr<Buffers> buffers_;
};

// The rays of one kind, in their recorded order.
std::vector<RecordedRay> raysOfKind(const std::vector<RecordedRay>& rays, RayKind kind);

struct ReplayResult {
  std::uint64_t rays = 0;
  std::uint64_t hits = 0;  // closest hits found plus shadow rays occluded
  double seconds = 0.0;    // wall time of the fastest pass over all the rays
  int passes = 0;
  double raysPerSecond() const { return seconds > 0.0 ? static_cast<double>(rays) / seconds : 0.0; }
};

// Traces `rays` through `geometry` with `threads` threads (0: all cores): one untimed
// warm-up pass, then whole passes until minSeconds have been spent and at least minPasses
// were made (at most 50); reports the fastest pass
// (deterministic work: the fastest is the least disturbed by other load).
ReplayResult replayRays(const EmbreeScene& geometry, const std::vector<RecordedRay>& rays,
                        int threads, double minSeconds = 0.5, int minPasses = 3);

}  // namespace camsim
