// Counting what an Embree device allocates (for EmbreeScene and the bench's build probe, the
// two modules that include Embree): register countEmbreeMemory with
// rtcSetDeviceMemoryMonitorFunction(device, countEmbreeMemory, &count). Embree calls it
// before each allocation (bytes > 0, post = false) and after each free (bytes < 0,
// post = true); both change the count.
//   bytes = Σ reported bytes (in use now),   peak = max over time of bytes
#pragma once

#include <sys/types.h>

#include <atomic>
#include <cstdint>

namespace camsim {

struct EmbreeMemoryCount {
  std::atomic<std::int64_t> bytes{0};  // B in use
  std::atomic<std::int64_t> peak{0};   // B, the most in use at any time
};

// Always lets the allocation proceed (returns true). `count` is an EmbreeMemoryCount*.
bool countEmbreeMemory(void* count, ssize_t bytes, bool post);

}  // namespace camsim
