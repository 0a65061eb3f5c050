// TriangleMesh: indexed triangles in world space (m), possibly moving (K poses at uniform
// time steps, vertices interpolated linearly in time). Optional per-vertex normals give
// the shading normal. Points are sampled uniformly by area: a triangle is chosen with
// probability ∝ its area at rest, then a uniform point on it at the sample's time.
//   p = b0·p0 + b1·p1 + b2·p2,  error bound γ(7)·(|b0 p0| + |b1 p1| + |b2 p2|), for a
//   moving mesh plus γ(3)·(|p0| + |p1| + |p2|) (time lerp) and the instance term (Shape)
//   geometric normal n = normalize((p1 − p0) × (p2 − p0))  (counter-clockwise front)
//   pdf_area(p on triangle k at t) = P(k) / area_k(t)
//   texture coordinates uv = b0·uv0 + b1·uv1 + b2·uv2 with per-vertex uvs; a mesh without
//   them uses (0,0), (1,0), (1,1) at each triangle's corners: uv = (b1 + b2, b2) (pbrt)
//
// Memory and speed: Embree traces the mesh's own position and index arrays (shared, see
// EmbreeScene), so they are allocated with one spare element for Embree's 16-byte loads.
// Only a mesh that a light samples (an emitter) keeps the per-triangle area distribution.
// A static mesh (one time step) skips the time interpolation, and its area pdf is 1/area:
// P(k)/area_k with P(k) = area_k/area.
#pragma once

#include <cstdint>
#include <vector>

#include "integrator/distribution.h"
#include "integrator/shape.h"

namespace camsim {

class TriangleMesh final : public Shape {
 public:
  // positions[k] / normals[k]: pose at time step k (normals may be empty). indices: 3 per
  // triangle. uvs: empty or one per vertex (they do not move). Zero-area triangles are kept
  // for intersection (Embree never hits them) and are never sampled. samplable: false for
  // a mesh no light samples (sample() and pdf() must then not be called). instance: how
  // Embree traces a moving mesh (Shape), one transform per pose.
  TriangleMesh(std::vector<std::vector<glm::vec3>> positions,
               std::vector<std::vector<glm::vec3>> normals, std::vector<std::uint32_t> indices,
               TimeSteps steps, std::vector<glm::vec2> uvs = {}, bool samplable = true,
               InstanceMotion instance = {});

  // Embree may load 16 bytes from the last vertex (float3) and the last index triple, so
  // the arrays it shares keep this many spare elements of capacity past their end.
  // TriangleMesh reserves them itself; a caller that allocates them up front saves a copy.
  static constexpr size_t kSpareVertices = 1;
  static constexpr size_t kSpareIndices = 3;

  const std::vector<glm::vec3>& positions(int step = 0) const {
    return positions_[static_cast<size_t>(step)];
  }
  const std::vector<std::uint32_t>& indices() const { return indices_; }
  size_t triangleCount() const { return indices_.size() / 3; }
  const TimeSteps& timeSteps() const override { return steps_; }
  const InstanceMotion& instanceMotion() const override { return instance_; }

  float area() const override { return area_; }
  SurfaceInteraction interaction(const Hit& hit, const Ray& ray) const override;
  std::optional<ShapeSample> sample(const glm::vec3& ref, float u1, glm::vec2 u2,
                                    float time) const override;
  float pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const override;

 private:
  glm::vec3 vertex(std::uint32_t index, int step, float f) const;
  SurfaceInteraction pointOn(size_t tri, float b1, float b2, float time) const;
  float triangleArea(size_t tri, float time) const;
  float areaPdf(size_t tri, float time) const;

  std::vector<std::vector<glm::vec3>> positions_;
  std::vector<std::vector<glm::vec3>> normals_;
  std::vector<std::uint32_t> indices_;
  std::vector<glm::vec2> uvs_;
  TimeSteps steps_;
  InstanceMotion instance_;
  DiscreteDistribution areaDistribution_;  // empty unless samplable
  bool samplable_;
  float area_ = 0.0f;
};

}  // namespace camsim
