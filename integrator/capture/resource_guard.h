// The memory guard of every front end (camsim render, camsim dataset's check of each item,
// camsim.capture), checked after the
// scene has loaded and before any work (no output directory, no Embree scene, no render):
// the memory the run will need, estimated from the scene, against a limit. The scene loader
// already bounds resolution, spp and inline mesh size (integrator/scene/scene_loader.h,
// SceneLimits); this catches scenes within those bounds that still do not fit the machine.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "integrator/scene/scene_description.h"

namespace camsim {

// Bytes, an estimate of the large allocations (not a bound on the process size).
struct MemoryEstimate {
  std::uint64_t film = 0;    // accumulators: 8 bytes per channel per pixel
  std::uint64_t images = 0;  // output images (EXR, quick look, sensor frames) in memory
  std::uint64_t meshes = 0;  // ~100 bytes per triangle (description, Embree geometry, BVH)
  std::uint64_t guide = 0;   // path guiding's training records (PathGuide::trainingBytes)
  std::uint64_t total() const { return film + images + meshes + guide; }
};

MemoryEstimate estimateRenderMemory(const SceneDescription& desc);

// Physical memory (sysconf), 0 if unknown.
std::uint64_t physicalMemoryBytes();

// A limit given by a front end: (0, kMaxMemoryGb] GB.
inline constexpr double kMaxMemoryGb = 1e9;
// InputError at `where`, key `option`, unless 0 < gb ≤ kMaxMemoryGb (a front end's value).
double checkMaxMemoryGb(double gb, const SourceLocation& where, const std::string& option);

// The default limit: 75 % of physical memory (no limit if that is unknown).
constexpr double kDefaultMemoryFraction = 0.75;

// Throws InputError naming the estimate, the limit and how to raise it when the estimate
// exceeds `maxMemoryGb` GB (10^9 bytes) or, without it, the default limit. option: how the
// front end sets the limit ("--max-memory-gb", Python's "max_memory_gb"), for the message.
void checkMemoryLimit(const SceneDescription& desc, std::optional<double> maxMemoryGb,
                      const std::string& option = "--max-memory-gb");

}  // namespace camsim
