// Shape: geometry that Embree intersects and lights sample. Small closed set: triangle
// meshes (which also carry rectangles) and spheres. Intersection itself is done by
// EmbreeScene; a Shape turns Embree's hit into a SurfaceInteraction and samples points.
// Lengths in metres.
#pragma once

#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/ray.h"

namespace camsim {

// What Embree reports for a hit: the shape (= geometry id), the primitive, the
// barycentric (u, v) and the ray parameter.
struct Hit {
  int shape = -1;
  int prim = -1;
  float u = 0.0f, v = 0.0f;
  float t = 0.0f;
};

struct SurfaceInteraction {
  glm::vec3 p{0.0f};       // position, m
  glm::vec3 pError{0.0f};  // absolute floating-point error bound on p, m
  glm::vec3 n{0.0f};       // geometric normal, unit; its side is the shape's front
  glm::vec3 ns{0.0f};      // shading normal, unit, in n's hemisphere
  int shape = -1;
  float time = 0.0f;

  // Origin for a ray leaving towards w, offset against self-intersection.
  glm::vec3 spawnOrigin(const glm::vec3& w) const;
};

struct ShapeSample {
  SurfaceInteraction point;
  float pdf = 0.0f;  // solid angle (sr⁻¹) as seen from the reference point
};

class Shape {
 public:
  virtual ~Shape() = default;
  virtual float area() const = 0;  // m²
  virtual SurfaceInteraction interaction(const Hit& hit, const Ray& ray) const = 0;
  // A point on the shape seen from ref (u1 in [0,1), u2 in [0,1)²), with its solid-angle pdf.
  virtual std::optional<ShapeSample> sample(const glm::vec3& ref, float u1, glm::vec2 u2) const = 0;
  // Solid-angle density of sample() producing `onShape` as seen from ref.
  virtual float pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const = 0;
};

// Solid-angle pdf of a point sampled by area with density pdfArea (m⁻²).
float areaToSolidAnglePdf(float pdfArea, const glm::vec3& ref, const SurfaceInteraction& onShape);

}  // namespace camsim
