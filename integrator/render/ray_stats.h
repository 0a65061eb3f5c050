// The rays the path tracer casts, counted per thread (as pbrt-v4's STAT_COUNTER) and shown
// to one optional observer (the benchmark's RayRecorder), so that no tracer function takes
// a counter or recorder parameter. The tracer calls countRay() for every ray it casts; the
// render loop reads the calling thread's counters around each range of tiles (their
// difference is that range's rays) and installs RenderOptions::rayObserver on the thread
// for that range (RayStatsScope).
#pragma once

#include <cstdint>

#include "integrator/geometry/ray.h"

namespace camsim {

enum class RayKind : std::uint8_t { kCamera = 0, kBounce = 1, kShadow = 2 };
inline constexpr int kRayKindCount = 3;
const char* rayKindName(RayKind kind);  // "camera", "bounce", "shadow"

struct RayCounts {
  std::uint64_t camera = 0;  // primary rays
  std::uint64_t bounce = 0;  // closest-hit rays after a scattering event
  std::uint64_t shadow = 0;  // occlusion rays for next-event estimation

  std::uint64_t total() const { return camera + bounce + shadow; }
  RayCounts& operator+=(const RayCounts& o) {
    camera += o.camera;
    bounce += o.bounce;
    shadow += o.shadow;
    return *this;
  }
  RayCounts operator-(const RayCounts& o) const {
    return {camera - o.camera, bounce - o.bounce, shadow - o.shadow};
  }
};

// Sees every ray a thread casts while installed; called from that thread only.
class RayObserver {
 public:
  virtual void observe(RayKind kind, const Ray& ray) = 0;

 protected:
  ~RayObserver() = default;
};

struct ThreadRayStats {
  RayCounts counts;                 // since the thread started; only differences matter
  RayObserver* observer = nullptr;  // null: one predictable branch per ray
};

inline ThreadRayStats& threadRayStats() {
  static thread_local ThreadRayStats stats;
  return stats;
}

inline void countRay(RayKind kind, const Ray& ray) {
  ThreadRayStats& t = threadRayStats();
  switch (kind) {
    case RayKind::kCamera:
      ++t.counts.camera;
      break;
    case RayKind::kBounce:
      ++t.counts.bounce;
      break;
    case RayKind::kShadow:
      ++t.counts.shadow;
      break;
  }
  if (t.observer) [[unlikely]]
    t.observer->observe(kind, ray);
}

// For the lifetime of the scope, this thread's rays go to `observer` as well; rays()
// is what the thread cast since the scope began.
class RayStatsScope {
 public:
  explicit RayStatsScope(RayObserver* observer)
      : start_(threadRayStats().counts), previous_(threadRayStats().observer) {
    threadRayStats().observer = observer;
  }
  ~RayStatsScope() { threadRayStats().observer = previous_; }
  RayStatsScope(const RayStatsScope&) = delete;
  RayStatsScope& operator=(const RayStatsScope&) = delete;
  RayCounts rays() const { return threadRayStats().counts - start_; }

 private:
  RayCounts start_;
  RayObserver* previous_;
};

}  // namespace camsim
