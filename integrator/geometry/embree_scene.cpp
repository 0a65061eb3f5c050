#include "integrator/geometry/embree_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "integrator/geometry/embree_memory.h"
#include "integrator/geometry/mesh_instance.h"
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

// Embree's intersection and occlusion filter: asks the hit shape's HitFilter (the user
// data: one per shape, by instance id for instanced geometry, else by geometry id) and
// rejects the candidate hit if the surface is not there; traversal then goes on.
void filterHit(const RTCFilterFunctionNArguments* args) {
  const auto& filters = *static_cast<const std::vector<const HitFilter*>*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned instance = RTCHitN_instID(args->hit, args->N, i, 0);
    const unsigned shape =
        instance != RTC_INVALID_GEOMETRY_ID ? instance : RTCHitN_geomID(args->hit, args->N, i);
    const HitFilter* filter = filters[shape];
    if (filter &&
        !filter->opaque(static_cast<int>(RTCHitN_primID(args->hit, args->N, i)),
                        RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i)))
      args->valid[i] = 0;
  }
}

// The intersection context of EmbreeScene::crossedShapes: Embree hands it to the filter,
// which lists there every shape a candidate hit is on (base first: Embree's pointer to the
// context is a pointer to this).
struct CrossingContext {
  RTCIntersectContext base;
  int* shapes;   // the list: distinct shape indices, in the order traversal met them
  int capacity;  // its room
  int count;     // shapes met; more than capacity when some did not fit
};
static_assert(std::is_standard_layout_v<CrossingContext>);

// A crossings scene's filter: the holes as filterHit makes them, then every remaining
// candidate is listed (once per shape) and rejected, so that traversal goes on to the next.
void collectCrossing(const RTCFilterFunctionNArguments* args) {
  filterHit(args);
  auto* c = reinterpret_cast<CrossingContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    args->valid[i] = 0;
    const unsigned instance = RTCHitN_instID(args->hit, args->N, i, 0);
    const int shape = static_cast<int>(
        instance != RTC_INVALID_GEOMETRY_ID ? instance : RTCHitN_geomID(args->hit, args->N, i));
    const int listed = std::min(c->count, c->capacity);
    if (std::find(c->shapes, c->shapes + listed, shape) != c->shapes + listed) continue;
    if (c->count < c->capacity) c->shapes[c->count] = shape;
    ++c->count;
  }
}

// The intersection context of EmbreeScene::occluded(ray, ignored): the shapes whose hits
// do not count (base first, as for CrossingContext).
struct IgnoringContext {
  RTCIntersectContext base;
  const char* ignored;  // per shape: non-zero to ignore
  std::size_t count;    // shapes listed
};
static_assert(std::is_standard_layout_v<IgnoringContext>);

// The context filter of occluded(ray, ignored): rejects the candidate hits on ignored
// shapes, so that traversal goes on to the others.
void skipIgnored(const RTCFilterFunctionNArguments* args) {
  const auto* c = reinterpret_cast<const IgnoringContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned instance = RTCHitN_instID(args->hit, args->N, i, 0);
    const unsigned shape =
        instance != RTC_INVALID_GEOMETRY_ID ? instance : RTCHitN_geomID(args->hit, args->N, i);
    if (shape < c->count && c->ignored[shape]) args->valid[i] = 0;
  }
}

// How a geometry's candidate hits are vetted: the per-shape filters (Embree's user data)
// and the function asking them (filterHit, collectCrossing); null function: every hit
// stands.
struct Vetting {
  const std::vector<const HitFilter*>* filters = nullptr;
  RTCFilterFunctionN function = nullptr;
};

// Makes Embree vet every candidate hit on geom (before it is committed).
void attachFilter(RTCGeometry geom, Vetting vet) {
  if (!vet.function) return;
  rtcSetGeometryUserData(geom, const_cast<std::vector<const HitFilter*>*>(vet.filters));
  rtcSetGeometryIntersectFilterFunction(geom, vet.function);
  rtcSetGeometryOccludedFilterFunction(geom, vet.function);
}

// A triangle mesh's own arrays as an Embree geometry (not committed).
RTCGeometry makeTriangles(RTCDevice device, const TriangleMesh& mesh) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  // Shared, not copied: Embree reads the mesh's arrays in place. It may load 16 bytes
  // from the last vertex (and index triple), so TriangleMesh allocates one element
  // more than it uses; checked here because reading past it would be out of bounds.
  const std::vector<glm::vec3>& p = mesh.positions();
  CAMSIM_CHECK(p.capacity() >= p.size() + TriangleMesh::kSpareVertices);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, p.data(), 0,
                             sizeof(glm::vec3), p.size());
  const std::vector<std::uint32_t>& idx = mesh.indices();
  CAMSIM_CHECK(idx.capacity() >= idx.size() + TriangleMesh::kSpareIndices);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, idx.data(), 0,
                             3 * sizeof(std::uint32_t), mesh.triangleCount());
  return geom;
}

// The shape's pose at rest, or a moving shape's reference pose, as a static Embree
// geometry (committed), its hits vetted by `vet`.
RTCGeometry makeGeometry(RTCDevice device, const Shape& shape, Vetting vet) {
  RTCGeometry geom = nullptr;
  const auto k = static_cast<size_t>(shape.instanceMotion().reference);
  if (const auto* mesh = dynamic_cast<const TriangleMesh*>(&shape)) {
    geom = makeTriangles(device, *mesh);
    attachFilter(geom, vet);
  } else if (const auto* sphere = dynamic_cast<const Sphere*>(&shape)) {
    // A sphere has no HitFilter (they take triangles' barycentrics): only the crossings'.
    CAMSIM_CHECK(vet.function != filterHit && "hit filters: meshes only");
    geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    attachFilter(geom, vet);
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

// An instance of `object` with one transform per time step (one: static), committed.
RTCGeometry instanceOf(RTCDevice device, RTCScene object, const std::vector<glm::mat4>& steps) {
  RTCGeometry instance = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(instance, object);
  rtcSetGeometryTimeStepCount(instance, static_cast<unsigned>(steps.size()));
  for (size_t k = 0; k < steps.size(); ++k)
    rtcSetGeometryTransform(instance, static_cast<unsigned>(k), RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR,
                            &steps[k][0][0]);
  rtcCommitGeometry(instance);
  return instance;
}

// A scene holding one committed geometry (built at `quality`).
RTCScene sceneOf(RTCDevice device, RTCGeometry geom, RTCBuildQuality quality) {
  RTCScene object = rtcNewScene(device);
  rtcSetSceneFlags(object, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);  // occluded(ray, ignored)
  rtcSetSceneBuildQuality(object, quality);
  rtcAttachGeometry(object, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(object);
  return object;
}

// A moving shape: its reference pose in a scene of its own (built at `quality`), placed by
// a motion-blurred instance with one transform per time step.
RTCGeometry makeInstance(RTCDevice device, const Shape& shape, RTCBuildQuality quality,
                         Vetting vet) {
  RTCScene object = sceneOf(device, makeGeometry(device, shape, vet), quality);
  RTCGeometry instance = instanceOf(device, object, shape.instanceMotion().steps);
  rtcReleaseScene(object);  // the instance holds it
  return instance;
}

RTCBuildQuality qualityFor(size_t triangles) {
  return triangles > EmbreeScene::kHighQualityTriangles ? RTC_BUILD_QUALITY_MEDIUM
                                                        : RTC_BUILD_QUALITY_HIGH;
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
  std::vector<const HitFilter*> filters;  // per shape (null: opaque); Embree's filter reads it
  std::map<const TriangleMesh*, RTCScene> meshScenes;  // one BVH per instanced mesh
  bool crossings = false;  // a crossings scene: every hit vetted by collectCrossing

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    for (const auto& [mesh, object] : meshScenes) rtcReleaseScene(object);
    if (device) rtcReleaseDevice(device);
  }

  // How the hits on shape `id` are vetted (an instanced mesh: `filtered`, whether any of
  // its instances has a filter).
  Vetting vetting(bool filtered) const {
    if (crossings) return {&filters, collectCrossing};
    return filtered ? Vetting{&filters, filterHit} : Vetting{};
  }
  // The BVH of an instanced mesh, built on first use; filtered if any of its instances is.
  RTCScene meshScene(const TriangleMesh& mesh, bool filtered) {
    RTCScene& object = meshScenes[&mesh];
    if (!object) {
      RTCGeometry geom = makeTriangles(device, mesh);
      attachFilter(geom, vetting(filtered));
      rtcCommitGeometry(geom);
      object = sceneOf(device, geom, qualityFor(mesh.triangleCount()));
    }
    return object;
  }
};

EmbreeScene::EmbreeScene(const std::vector<std::unique_ptr<Shape>>& shapes, double motionStart,
                         double motionEnd, const std::vector<const HitFilter*>& filters,
                         const std::vector<char>& crossingsOf)
    : impl_(std::make_unique<Impl>()) {
  CAMSIM_CHECK(filters.empty() || filters.size() == shapes.size());
  CAMSIM_CHECK(crossingsOf.empty() || crossingsOf.size() == shapes.size());
  impl_->crossings = !crossingsOf.empty();
  setMotionSpan(motionStart, motionEnd);
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw std::runtime_error("cannot create Embree device");
  rtcSetDeviceErrorFunction(impl_->device, reportEmbreeError, nullptr);
  rtcSetDeviceMemoryMonitorFunction(impl_->device, countEmbreeMemory, &impl_->memory);
  impl_->filters = filters;
  impl_->filters.resize(shapes.size(), nullptr);
  const bool anyFilter = std::any_of(impl_->filters.begin(), impl_->filters.end(),
                                     [](const HitFilter* f) { return f != nullptr; });
  if ((anyFilter || impl_->crossings) &&
      !rtcGetDeviceProperty(impl_->device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED))
    throw std::runtime_error("this Embree library was built without filter functions");
  // An instanced mesh is filtered if any of its instances is (the filter asks per instance).
  std::set<const TriangleMesh*> filteredMeshes;
  for (size_t id = 0; id < shapes.size(); ++id)
    if (const auto* instance = dynamic_cast<const MeshInstance*>(shapes[id].get()))
      if (impl_->filters[id]) filteredMeshes.insert(instance->mesh().get());
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);  // occluded(ray, ignored)
  size_t triangles = 0;  // in the top-level BVH: an instance counts as none
  for (size_t id = 0; id < shapes.size(); ++id)
    if (const auto* mesh = dynamic_cast<const TriangleMesh*>(shapes[id].get()))
      if (!impl_->crossings || crossingsOf[id]) triangles += mesh->triangleCount();
  const RTCBuildQuality quality = qualityFor(triangles);
  rtcSetSceneBuildQuality(impl_->scene, quality);
  for (size_t id = 0; id < shapes.size(); ++id) {
    if (impl_->crossings && !crossingsOf[id]) continue;  // left out; its id stays free
    const Shape& shape = *shapes[id];
    const Vetting vet = impl_->vetting(impl_->filters[id] != nullptr);
    hasInstances_ = hasInstances_ || !shape.instanceMotion().empty();
    RTCGeometry geom = nullptr;
    if (const auto* instance = dynamic_cast<const MeshInstance*>(&shape)) {
      const TriangleMesh& mesh = *instance->mesh();
      RTCScene object = impl_->meshScene(mesh, filteredMeshes.count(&mesh) > 0);
      geom = instanceOf(impl_->device, object,
                        instance->instanceMotion().empty()
                            ? std::vector<glm::mat4>{instance->placement()}
                            : instance->instanceMotion().steps);
    } else if (shape.instanceMotion().empty()) {
      geom = makeGeometry(impl_->device, shape, vet);
    } else {
      geom = makeInstance(impl_->device, shape, quality, vet);
    }
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

float EmbreeScene::embreeTime(double time) const {
  const double x = (time - timeOffset_) * timeScale_;
  return x > 0.0 ? (x < 1.0 ? static_cast<float>(x) : 1.0f) : 0.0f;  // NaN → 0
}

std::int64_t EmbreeScene::embreeBytes() const {
  return impl_->memory.bytes.load();
}
std::int64_t EmbreeScene::embreePeakBytes() const {
  return impl_->memory.peak.load();
}

namespace {

// Embree's own precondition (ray.valid(): origin and direction components within ±1.844e18,
// no NaN, t range not NaN), asserted in its traversal. The loader keeps geometry within
// ±1e15 m (SceneLimits::kMaxCoordinate) and Scene checks the built bounds, so no scene
// should make such a ray; if one does, it hits nothing rather than aborting the process.
bool traceable(const Ray& r) {
  constexpr float kLarge = 1.844e18f;
  return std::abs(r.o.x) <= kLarge && std::abs(r.o.y) <= kLarge && std::abs(r.o.z) <= kLarge &&
         std::abs(r.d.x) <= kLarge && std::abs(r.d.y) <= kLarge && std::abs(r.d.z) <= kLarge &&
         r.tMax >= 0.0f;
}

// A closest-hit query for Embree: the ray with t in (0, tMax], at Embree's `time`, no hit yet.
RTCRayHit rayHitOf(const Ray& ray, float time) {
  RTCRayHit rh;
  rh.ray.org_x = ray.o.x;
  rh.ray.org_y = ray.o.y;
  rh.ray.org_z = ray.o.z;
  rh.ray.dir_x = ray.d.x;
  rh.ray.dir_y = ray.d.y;
  rh.ray.dir_z = ray.d.z;
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = ray.tMax;
  rh.ray.time = time;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

}  // namespace

bool EmbreeScene::intersect(const Ray& ray, Hit& hit) const {
  if (!traceable(ray)) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = rayHitOf(ray, embreeTime(ray.time));
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
  return occluded(ray, {});
}

bool EmbreeScene::occluded(const Ray& ray, std::span<const char> ignored) const {
  if (!traceable(ray)) return false;
  IgnoringContext context;
  rtcInitIntersectContext(&context.base);
  context.ignored = ignored.data();
  context.count = ignored.size();
  if (!ignored.empty()) context.base.filter = skipIgnored;
  RTCRay r;
  r.org_x = ray.o.x;
  r.org_y = ray.o.y;
  r.org_z = ray.o.z;
  r.dir_x = ray.d.x;
  r.dir_y = ray.d.y;
  r.dir_z = ray.d.z;
  r.tnear = 0.0f;
  r.tfar = ray.tMax;
  r.time = embreeTime(ray.time);
  r.mask = 0xFFFFFFFFu;
  r.id = 0;
  r.flags = 0;
  rtcOccluded1(impl_->scene, &context.base, &r);
  return r.tfar < 0.0f;  // Embree sets tfar = −inf on occlusion
}

int EmbreeScene::crossedShapes(const Ray& ray, std::span<int> shapes) const {
  CAMSIM_CHECK(impl_->crossings);
  if (!traceable(ray)) return 0;
  CrossingContext c;
  rtcInitIntersectContext(&c.base);
  c.shapes = shapes.data();
  c.capacity = static_cast<int>(shapes.size());
  c.count = 0;
  RTCRayHit rh = rayHitOf(ray, embreeTime(ray.time));
  rtcIntersect1(impl_->scene, &c.base, &rh);  // every candidate rejected: traversal runs to tMax
  return c.count;
}

}  // namespace camsim
