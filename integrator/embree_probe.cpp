#include "integrator/embree_probe.h"

#include <embree3/rtcore.h>

#include <atomic>
#include <chrono>
#include <stdexcept>

#include <tbb/info.h>
#include <tbb/task_arena.h>

namespace camsim {
namespace {

struct MemoryCount {
  std::atomic<std::int64_t> inUse{0};
  std::atomic<std::int64_t> peak{0};
};

// Called by Embree before (post = false) and after every allocation and free; bytes < 0
// for frees. Returning true lets the allocation proceed.
bool countMemory(void* user, ssize_t bytes, bool post) {
  auto* count = static_cast<MemoryCount*>(user);
  if (post) return true;
  const std::int64_t now = count->inUse.fetch_add(bytes) + bytes;
  std::int64_t seen = count->peak.load();
  while (now > seen && !count->peak.compare_exchange_weak(seen, now)) {
  }
  return true;
}

struct DeviceGuard {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~DeviceGuard() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

}  // namespace

MeshBuildProbe probeMeshBuild(const MeshData& mesh, int threads, BvhQuality quality) {
  MeshBuildProbe probe;
  probe.triangles = mesh.indices.size() / 3;
  MemoryCount count;
  DeviceGuard g;
  g.device = rtcNewDevice(nullptr);
  if (!g.device) throw std::runtime_error("cannot create Embree device");
  rtcSetDeviceMemoryMonitorFunction(g.device, countMemory, &count);
  g.scene = rtcNewScene(g.device);
  rtcSetSceneBuildQuality(g.scene, quality == BvhQuality::kHigh ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM);
  RTCGeometry geom = rtcNewGeometry(g.device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        sizeof(float) * 3, mesh.positions.size()));
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    v[3 * i] = mesh.positions[i].x;
    v[3 * i + 1] = mesh.positions[i].y;
    v[3 * i + 2] = mesh.positions[i].z;
  }
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             sizeof(unsigned) * 3, probe.triangles));
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) idx[i] = mesh.indices[i];
  rtcCommitGeometry(geom);
  rtcAttachGeometry(g.scene, geom);
  rtcReleaseGeometry(geom);
  tbb::task_arena arena(threads > 0 ? threads : tbb::info::default_concurrency());
  const auto start = std::chrono::steady_clock::now();
  arena.execute([&] { rtcCommitScene(g.scene); });
  probe.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (rtcGetDeviceError(g.device) != RTC_ERROR_NONE) throw std::runtime_error("Embree error while building the BVH");
  probe.bytesAfterBuild = count.inUse.load();
  probe.bytesPeak = count.peak.load();
  return probe;
}

}  // namespace camsim
