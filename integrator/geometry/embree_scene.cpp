#include "integrator/geometry/embree_scene.h"

#include <embree3/rtcore.h>

#include <atomic>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "integrator/geometry/embree_memory.h"
#include "integrator/geometry/sphere.h"
#include "integrator/geometry/triangle_mesh.h"
#include "sensor/base/check.h"

namespace camsim {
namespace {

void reportEmbreeError(void*, RTCError code, const char* message) {
  if (code == RTC_ERROR_NONE) return;
  std::fprintf(stderr, "embree error %d: %s\n", static_cast<int>(code), message ? message : "");
}

// Embree reports errors through the device; an error leaves the scene unusable, so stop
// here (an internal error, exit code 1) instead of tracing rays through bad buffers.
void throwOnEmbreeError(RTCDevice device, const std::string& what) {
  const RTCError code = rtcGetDeviceError(device);
  if (code != RTC_ERROR_NONE)
    throw std::runtime_error("Embree error " + std::to_string(static_cast<int>(code)) + " while " +
                             what);
}

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "Embree reads the vertices as packed float3");

// The shape's pose at rest, or a moving shape's reference pose, as a static Embree
// geometry (committed).
RTCGeometry makeGeometry(RTCDevice device, const Shape& shape) {
  RTCGeometry geom = nullptr;
  const auto k = static_cast<size_t>(shape.instanceMotion().reference);
  if (const auto* mesh = dynamic_cast<const TriangleMesh*>(&shape)) {
    geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Shared, not copied: Embree reads the mesh's arrays in place. It may load 16 bytes
    // from the last vertex (and index triple), so TriangleMesh allocates one element
    // more than it uses; checked here because reading past it would be out of bounds.
    const std::vector<glm::vec3>& p = mesh->positions();
    CAMSIM_CHECK(p.capacity() >= p.size() + TriangleMesh::kSpareVertices);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, p.data(), 0,
                               sizeof(glm::vec3), p.size());
    const std::vector<std::uint32_t>& idx = mesh->indices();
    CAMSIM_CHECK(idx.capacity() >= idx.size() + TriangleMesh::kSpareIndices);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, idx.data(), 0,
                               3 * sizeof(std::uint32_t), mesh->triangleCount());
  } else if (const auto* sphere = dynamic_cast<const Sphere*>(&shape)) {
    geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT4, sizeof(float) * 4, 1));
    const glm::vec3& c = sphere->centres()[k];
    v[0] = c.x;
    v[1] = c.y;
    v[2] = c.z;
    v[3] = sphere->radii()[k];
  } else {
    CAMSIM_CHECK(false && "unknown shape type");
  }
  rtcCommitGeometry(geom);
  return geom;
}

// A moving shape: its reference pose in a scene of its own (built at `quality`), placed by
// a motion-blurred instance with one transform per time step.
RTCGeometry makeInstance(RTCDevice device, const Shape& shape, RTCBuildQuality quality) {
  const InstanceMotion& motion = shape.instanceMotion();
  RTCScene object = rtcNewScene(device);
  rtcSetSceneBuildQuality(object, quality);
  RTCGeometry geom = makeGeometry(device, shape);
  rtcAttachGeometry(object, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(object);
  RTCGeometry instance = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(instance, object);
  rtcReleaseScene(object);  // the instance holds it
  rtcSetGeometryTimeStepCount(instance, static_cast<unsigned>(motion.steps.size()));
  for (size_t k = 0; k < motion.steps.size(); ++k)
    rtcSetGeometryTransform(instance, static_cast<unsigned>(k), RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR,
                            &motion.steps[k][0][0]);
  rtcCommitGeometry(instance);
  return instance;
}

}  // namespace

bool countEmbreeMemory(void* count, ssize_t bytes, bool /*post*/) {
  auto* c = static_cast<EmbreeMemoryCount*>(count);
  const std::int64_t now = c->bytes.fetch_add(bytes, std::memory_order_relaxed) + bytes;
  std::int64_t peak = c->peak.load(std::memory_order_relaxed);
  while (now > peak && !c->peak.compare_exchange_weak(peak, now, std::memory_order_relaxed)) {
  }
  return true;
}

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  EmbreeMemoryCount memory;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

EmbreeScene::EmbreeScene(const std::vector<std::unique_ptr<Shape>>& shapes, double motionStart,
                         double motionEnd)
    : impl_(std::make_unique<Impl>()) {
  setMotionSpan(motionStart, motionEnd);
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw std::runtime_error("cannot create Embree device");
  rtcSetDeviceErrorFunction(impl_->device, reportEmbreeError, nullptr);
  rtcSetDeviceMemoryMonitorFunction(impl_->device, countEmbreeMemory, &impl_->memory);
  impl_->scene = rtcNewScene(impl_->device);
  size_t triangles = 0;
  for (const auto& shape : shapes)
    if (const auto* mesh = dynamic_cast<const TriangleMesh*>(shape.get()))
      triangles += mesh->triangleCount();
  const RTCBuildQuality quality =
      triangles > kHighQualityTriangles ? RTC_BUILD_QUALITY_MEDIUM : RTC_BUILD_QUALITY_HIGH;
  rtcSetSceneBuildQuality(impl_->scene, quality);
  for (size_t id = 0; id < shapes.size(); ++id) {
    const Shape& shape = *shapes[id];
    hasInstances_ = hasInstances_ || !shape.instanceMotion().empty();
    RTCGeometry geom = shape.instanceMotion().empty() ? makeGeometry(impl_->device, shape)
                                                      : makeInstance(impl_->device, shape, quality);
    rtcAttachGeometryByID(impl_->scene, geom, static_cast<unsigned>(id));
    rtcReleaseGeometry(geom);
    throwOnEmbreeError(impl_->device, "adding shape " + std::to_string(id));
  }
  rtcCommitScene(impl_->scene);
  throwOnEmbreeError(impl_->device, "building the BVH");
  RTCBounds b;
  rtcGetSceneBounds(impl_->scene, &b);
  lower_ = glm::vec3(b.lower_x, b.lower_y, b.lower_z);
  upper_ = glm::vec3(b.upper_x, b.upper_y, b.upper_z);
}

EmbreeScene::~EmbreeScene() = default;

void EmbreeScene::setMotionSpan(double motionStart, double motionEnd) {
  CAMSIM_CHECK(!hasInstances_);
  timeOffset_ = 0.0;
  timeScale_ = 0.0;
  if (motionEnd > motionStart) {
    timeOffset_ = motionStart;
    timeScale_ = 1.0 / (motionEnd - motionStart);
  }
}

std::int64_t EmbreeScene::embreeBytes() const {
  return impl_->memory.bytes.load();
}
std::int64_t EmbreeScene::embreePeakBytes() const {
  return impl_->memory.peak.load();
}

bool EmbreeScene::intersect(const Ray& ray, Hit& hit) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = ray.o.x;
  rh.ray.org_y = ray.o.y;
  rh.ray.org_z = ray.o.z;
  rh.ray.dir_x = ray.d.x;
  rh.ray.dir_y = ray.d.y;
  rh.ray.dir_z = ray.d.z;
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = ray.tMax;
  rh.ray.time = static_cast<float>((static_cast<double>(ray.time) - timeOffset_) * timeScale_);
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  // A shape traced as an instance is named by the instance's id (its scene holds one geometry).
  hit.shape = static_cast<int>(rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID ? rh.hit.instID[0]
                                                                           : rh.hit.geomID);
  hit.prim = static_cast<int>(rh.hit.primID);
  hit.u = rh.hit.u;
  hit.v = rh.hit.v;
  hit.t = rh.ray.tfar;
  return true;
}

bool EmbreeScene::occluded(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r;
  r.org_x = ray.o.x;
  r.org_y = ray.o.y;
  r.org_z = ray.o.z;
  r.dir_x = ray.d.x;
  r.dir_y = ray.d.y;
  r.dir_z = ray.d.z;
  r.tnear = 0.0f;
  r.tfar = ray.tMax;
  r.time = static_cast<float>((static_cast<double>(ray.time) - timeOffset_) * timeScale_);
  r.mask = 0xFFFFFFFFu;
  r.id = 0;
  r.flags = 0;
  rtcOccluded1(impl_->scene, &context, &r);
  return r.tfar < 0.0f;  // Embree sets tfar = −inf on occlusion
}

}  // namespace camsim
