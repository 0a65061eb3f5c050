// Sphere: centre (m) and radius (m); the front (normal) faces outward.
// Sampling from a reference point outside: uniform over the cone of directions it
// subtends, pdf = 1 / (2π (1 − cos θmax)),  sin²θmax = r² / |c − ref|²;
// from inside: uniform by area, pdf = d² / (|cos θ| · 4πr²).
// Hit points are re-projected onto the surface, error bound γ(5)·(|p| + |c|), plus the
// instance term (Shape) for a moving sphere.
// A moving sphere holds a centre and radius per time step, interpolated linearly; its
// instance transforms (Shape) are X_k = T(c_k) · S(r_k / r_ref) · T(−c_ref).
#pragma once

#include <vector>

#include "integrator/geometry/shape.h"

namespace camsim {

class Sphere final : public Shape {
 public:
  Sphere(std::vector<glm::vec3> centres, std::vector<float> radii, TimeSteps steps);

  const std::vector<glm::vec3>& centres() const { return centres_; }
  const std::vector<float>& radii() const { return radii_; }
  const TimeSteps& timeSteps() const override { return steps_; }
  const InstanceMotion& instanceMotion() const override { return instance_; }

  float area() const override;
  SurfaceInteraction interaction(const Hit& hit, const Ray& ray) const override;
  // ∂p/∂u along the parallel (∝ (z, 0, −x) of n) and ∂p/∂v towards the top pole;
  // zero at the poles (a normal map does not bend there).
  std::optional<SurfaceTangents> tangentFrame(const Hit& hit,
                                              const SurfaceInteraction& si) const override;
  std::optional<ShapeSample> sample(const glm::vec3& ref, float u1, glm::vec2 u2,
                                    double time) const override;
  float pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const override;

 private:
  struct Pose {
    glm::vec3 centre;
    float radius;
  };
  Pose at(double time) const;
  // The point in `direction` from the centre: position, normals, error bound, time; no uv
  // (a light sample does not read it: its atan2 and acos were 4 % of a small_light render).
  SurfaceInteraction surfacePoint(const Pose& pose, const glm::vec3& direction, double time) const;
  static glm::vec2 uvOf(const glm::vec3& n);  // the texture coordinates at normal n
  static bool inside(const Pose& pose, const glm::vec3& ref);

  std::vector<glm::vec3> centres_;
  std::vector<float> radii_;
  TimeSteps steps_;
  InstanceMotion instance_;
};

}  // namespace camsim
