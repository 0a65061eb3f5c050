#include "integrator/geometry/embree_probe.h"

#include <embree3/rtcore.h>

#include <chrono>
#include <stdexcept>
#include <vector>

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include "integrator/geometry/embree_memory.h"
#include "integrator/geometry/triangle_mesh.h"

namespace camsim {
namespace {

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
  EmbreeMemoryCount count;
  // Shared buffers as in EmbreeScene, padded the same way (Embree may read 16 bytes from the
  // last vertex and index triple); the copies are ours, so Embree counts only its own memory.
  // Declared before the guard: they must outlive the scene that points into them.
  std::vector<glm::vec3> positions;
  positions.reserve(mesh.positions.size() + TriangleMesh::kSpareVertices);
  positions.assign(mesh.positions.begin(), mesh.positions.end());
  std::vector<std::uint32_t> indices;
  indices.reserve(mesh.indices.size() + TriangleMesh::kSpareIndices);
  indices.assign(mesh.indices.begin(), mesh.indices.end());
  DeviceGuard g;
  g.device = rtcNewDevice(nullptr);
  if (!g.device) throw std::runtime_error("cannot create Embree device");
  rtcSetDeviceMemoryMonitorFunction(g.device, countEmbreeMemory, &count);
  g.scene = rtcNewScene(g.device);
  rtcSetSceneBuildQuality(
      g.scene, quality == BvhQuality::kHigh ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM);
  RTCGeometry geom = rtcNewGeometry(g.device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, positions.data(),
                             0, sizeof(glm::vec3), positions.size());
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices.data(), 0,
                             3 * sizeof(std::uint32_t), probe.triangles);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(g.scene, geom);
  rtcReleaseGeometry(geom);
  tbb::task_arena arena(threads > 0 ? threads : tbb::info::default_concurrency());
  const auto start = std::chrono::steady_clock::now();
  arena.execute([&] { rtcCommitScene(g.scene); });
  probe.buildSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (rtcGetDeviceError(g.device) != RTC_ERROR_NONE)
    throw std::runtime_error("Embree error while building the BVH");
  probe.bytesAfterBuild = count.bytes.load();
  probe.bytesPeak = count.peak.load();
  return probe;
}

}  // namespace camsim
