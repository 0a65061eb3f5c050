// Sphere: centre (m) and radius (m); the front (normal) faces outward.
// Sampling from a reference point outside: uniform over the cone of directions it
// subtends, pdf = 1 / (2π (1 − cos θmax)),  sin²θmax = r² / |c − ref|²;
// from inside: uniform by area, pdf = d² / (|cos θ| · 4πr²).
// Hit points are re-projected onto the surface, error bound γ(5)·|p|.
#pragma once

#include "integrator/shape.h"

namespace camsim {

class Sphere final : public Shape {
 public:
  Sphere(glm::vec3 centre, float radius);

  const glm::vec3& centre() const { return centre_; }
  float radius() const { return radius_; }

  float area() const override;
  SurfaceInteraction interaction(const Hit& hit, const Ray& ray) const override;
  std::optional<ShapeSample> sample(const glm::vec3& ref, float u1, glm::vec2 u2) const override;
  float pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const override;

 private:
  SurfaceInteraction surfacePoint(const glm::vec3& direction) const;
  bool inside(const glm::vec3& ref) const;

  glm::vec3 centre_;
  float radius_;
};

}  // namespace camsim
