// EmbreeScene: every ray query goes through here; this module is the only one that
// includes Embree. Geometry id (static shapes) or instance id (moving shapes, mesh
// instances) == shape index, so a Hit names its Shape directly.
// Triangle meshes become RTC_GEOMETRY_TYPE_TRIANGLE on the mesh's own vertex and index
// arrays (shared, not copied: TriangleMesh keeps the 16 bytes of padding Embree reads past
// the last element), spheres RTC_GEOMETRY_TYPE_SPHERE_POINT (small Embree-owned buffers).
// BVH quality: RTC_BUILD_QUALITY_HIGH (spatial splits, the fastest traversal) up to
// kHighQualityTriangles triangles; above, MEDIUM (binned SAH): on large meshes HIGH's build
// time and peak memory outweigh its faster traversal (figures: docs/performance.md, "What was
// changed, and why").
// Moving shapes use Embree's motion blur, with steps uniform over the scene's motion span
// [t0, t1]; a ray's time t (s) is passed to Embree as (t − t0)/(t1 − t0). Each is a static
// geometry of its reference pose in a scene of its own (same build quality), placed by a
// motion-blurred instance with one transform per step (Shape::instanceMotion; instance id =
// shape index): the top-level BVH over a few instances is cheap to traverse, where motion-
// blurred triangles (one vertex buffer per step) cost twice the static BVH per ray
// (docs/performance.md). Nothing is rebuilt per sample.
// Instanced meshes (MeshInstance): one BVH per distinct shared TriangleMesh, built once at
// the quality its own triangle count gives, and per instance an Embree instance of it
// (RTC_GEOMETRY_TYPE_INSTANCE; instance id = shape index) with its static placement or one
// transform per time step; the top-level BVH counts an instance as one primitive.
// Hit filters (alpha cut-outs, hit_filter.h): a shape given one has Embree's intersection
// and occlusion filter functions on its triangles (for an instanced mesh: on the shared
// geometry, asking the filter of the instance hit), so every kind of ray skips the hits it
// rejects; shapes without one pay nothing.
// Crossings scenes (the amodal masks, integrator/render/mask_film.h): built from some of the
// shapes only (the others' ids stay free), they answer crossedShapes() — every shape a ray
// passes through, as if nothing occluded anything — with one traversal: a filter on every
// geometry lists the shape of each candidate hit and rejects it, so Embree goes on to the
// ray's end. The holes of the shapes' HitFilters are skipped there too.
// An occlusion query may ignore some shapes (occluded(ray, ignored)): a filter passed with
// the query (Embree's context filter, run on every geometry after its own HitFilter)
// rejects their hits; the other queries carry no such filter and pay nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "integrator/geometry/hit_filter.h"
#include "integrator/geometry/ray.h"
#include "integrator/geometry/shape.h"

namespace camsim {

class EmbreeScene {
 public:
  // [motionStart, motionEnd] (s): the interval moving shapes' steps cover (ignored if nothing
  // moves). filters: empty, or one per shape (null: opaque; triangle meshes and mesh
  // instances only), not owned: they must outlive this scene. crossingsOf: empty, or one per
  // shape: a crossings scene of the shapes it marks (non-zero), for crossedShapes() only.
  EmbreeScene(const std::vector<std::unique_ptr<Shape>>& shapes, double motionStart,
              double motionEnd, const std::vector<const HitFilter*>& filters = {},
              const std::vector<char>& crossingsOf = {});
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Closest hit with t in (0, ray.tMax]; false if none.
  bool intersect(const Ray& ray, Hit& hit) const;
  // True if anything is hit with t in (0, ray.tMax).
  bool occluded(const Ray& ray) const;
  // The same, hits on the shapes `ignored` marks (non-zero; one entry per shape, or
  // empty: none ignored) not counting: one traversal, whose filter rejects their hits.
  bool occluded(const Ray& ray, std::span<const char> ignored) const;
  // A crossings scene's: the shapes the ray passes through with t in (0, ray.tMax], each
  // once, whatever lies in front of them. Writes the first shapes.size() of them (shape
  // indices, in the order traversal met them) and returns how many there are (more than
  // shapes.size() when some did not fit).
  int crossedShapes(const Ray& ray, std::span<int> shapes) const;
  // Axis-aligned bounds of all geometry over all time steps (m); lower > upper if empty.
  glm::vec3 boundsLower() const { return lower_; }
  glm::vec3 boundsUpper() const { return upper_; }
  // Bytes Embree has allocated and not freed (BVH, sphere buffers; the shared mesh arrays
  // are not Embree's), counted by the device's memory monitor; and the most at any time.
  std::int64_t embreeBytes() const;
  std::int64_t embreePeakBytes() const;

  // Moves the motion span to [motionStart, motionEnd] (s), as if built over it: only for a
  // scene without moving shapes (no instances), whose BVH does not depend on the span — the
  // ray-time mapping is then all that changes (Scene::retarget).
  void setMotionSpan(double motionStart, double motionEnd);
  // The time Embree is handed for a ray at `time` (s): its fraction of the motion span,
  // worked out in double from the absolute time and clamped into [0, 1] (a sample at the
  // close can round an ulp past it; Embree asserts the range); NaN gives 0.
  float embreeTime(double time) const;

  static constexpr std::size_t kHighQualityTriangles = 250000;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double timeOffset_ = 0.0, timeScale_ = 0.0;
  bool hasInstances_ = false;  // some shape moves: its steps cover the span it was built over
                               // (static mesh instances do not count)
  glm::vec3 lower_{1.0f}, upper_{-1.0f};
};

}  // namespace camsim
