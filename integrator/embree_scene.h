// EmbreeScene: every ray query goes through here; this module is the only one that
// includes Embree. Geometry id == shape index, so a Hit names its Shape directly.
// Triangle meshes become RTC_GEOMETRY_TYPE_TRIANGLE (copied into Embree-owned, padded
// buffers), spheres RTC_GEOMETRY_TYPE_SPHERE_POINT. BVH: RTC_BUILD_QUALITY_HIGH.
// Moving shapes use Embree's motion blur: one vertex buffer per time step
// (rtcSetGeometryTimeStepCount), steps uniform over the scene's motion span [t0, t1];
// a ray's time t (s) is passed to Embree as (t − t0)/(t1 − t0). Nothing is rebuilt per sample.
#pragma once

#include <memory>
#include <vector>

#include "integrator/ray.h"
#include "integrator/shape.h"

namespace camsim {

class EmbreeScene {
 public:
  // motionSpan: the time interval moving shapes' steps cover (ignored if nothing moves).
  EmbreeScene(const std::vector<std::unique_ptr<Shape>>& shapes, double motionStart, double motionEnd);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Closest hit with t in (0, ray.tMax]; false if none.
  bool intersect(const Ray& ray, Hit& hit) const;
  // True if anything is hit with t in (0, ray.tMax).
  bool occluded(const Ray& ray) const;
  // Axis-aligned bounds of all geometry over all time steps (m); lower > upper if empty.
  glm::vec3 boundsLower() const { return lower_; }
  glm::vec3 boundsUpper() const { return upper_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double timeOffset_ = 0.0, timeScale_ = 0.0;
  glm::vec3 lower_{1.0f}, upper_{-1.0f};
};

}  // namespace camsim
