// Embree probes for `camsim bench`: measurements that need Embree itself (this and
// embree_scene.cpp are the only modules that include it).
//
// probeMeshBuild() builds a standalone Embree scene of one static triangle mesh the way
// EmbreeScene does (vertex and index arrays shared with Embree, not copied into it; default
// scene flags) at a chosen build quality (EmbreeScene picks high up to 250 k triangles, medium
// above), on a device with a memory monitor (integrator/geometry/embree_memory.h), so every byte
// Embree allocates — BVH nodes, primitive blocks and build temporaries — is counted.
// Reported: the build time (rtcCommitScene only), bytes in use after the build and the peak
// during it.
#pragma once

#include <cstdint>

#include "integrator/geometry/mesh_io.h"

namespace camsim {

struct MeshBuildProbe {
  std::uint64_t triangles = 0;
  double buildSeconds = 0.0;         // rtcCommitScene: the BVH build
  std::int64_t bytesAfterBuild = 0;  // Embree's allocations in use once built
  std::int64_t bytesPeak = 0;        // the most in use at any time (build temporaries)
  double bytesPerTriangle() const {
    return triangles ? static_cast<double>(bytesAfterBuild) / static_cast<double>(triangles) : 0.0;
  }
};

enum class BvhQuality { kMedium, kHigh };  // RTC_BUILD_QUALITY_MEDIUM / _HIGH

// `threads`: the TBB threads Embree builds with (0: all cores; set through a task_arena).
MeshBuildProbe probeMeshBuild(const MeshData& mesh, int threads, BvhQuality quality);

}  // namespace camsim
