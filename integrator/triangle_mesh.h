// TriangleMesh: indexed triangles in world space (m). Optional per-vertex normals give
// the shading normal. Points are sampled uniformly by area (triangle chosen ∝ area).
//   p = b0·p0 + b1·p1 + b2·p2,  error bound γ(7)·(|b0 p0| + |b1 p1| + |b2 p2|)
//   geometric normal n = normalize((p1 − p0) × (p2 − p0))  (counter-clockwise front)
#pragma once

#include <cstdint>
#include <vector>

#include "integrator/distribution.h"
#include "integrator/shape.h"

namespace camsim {

class TriangleMesh final : public Shape {
 public:
  // indices: 3 per triangle. Degenerate (zero-area) triangles are kept for intersection
  // (Embree never hits them) and get zero sampling weight.
  TriangleMesh(std::vector<glm::vec3> positions, std::vector<glm::vec3> normals,
               std::vector<std::uint32_t> indices);

  const std::vector<glm::vec3>& positions() const { return positions_; }
  const std::vector<std::uint32_t>& indices() const { return indices_; }
  size_t triangleCount() const { return indices_.size() / 3; }

  float area() const override { return area_; }
  SurfaceInteraction interaction(const Hit& hit, const Ray& ray) const override;
  std::optional<ShapeSample> sample(const glm::vec3& ref, float u1, glm::vec2 u2) const override;
  float pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const override;

 private:
  SurfaceInteraction pointOn(size_t tri, float b1, float b2) const;

  std::vector<glm::vec3> positions_;
  std::vector<glm::vec3> normals_;
  std::vector<std::uint32_t> indices_;
  DiscreteDistribution areaDistribution_;
  float area_ = 0.0f;
};

}  // namespace camsim
