// TriangleMesh: indexed triangles in world space (m), possibly moving: a moving mesh stores
// one pose, the reference of its instance motion (Shape), and places it at time t with the
// instance transform interpolated linearly between the K uniform time steps, exactly the
// transform Embree traces it with. Optional per-vertex normals give
// the shading normal. Points are sampled uniformly by area: a triangle is chosen with
// probability ∝ its area at rest, then a uniform point on it at the sample's time.
//   p = b0·p0 + b1·p1 + b2·p2,  error bound γ(7)·(|b0 p0| + |b1 p1| + |b2 p2|), for a
//   moving mesh plus γ(3)·(|p0| + |p1| + |p2|) (time lerp) and the instance term (Shape)
//   geometric normal n = normalize((p1 − p0) × (p2 − p0))  (counter-clockwise front)
//   pdf_area(p on triangle k at t) = P(k) / area_k(t)
//   texture coordinates uv = b0·uv0 + b1·uv1 + b2·uv2 with per-vertex uvs; a mesh without
//   them uses (0,0), (1,0), (1,1) at each triangle's corners: uv = (b1 + b2, b2) (pbrt)
//
// Tangent frame (normal maps, tangentFrame()): with per-vertex tangents (xyz along ∂p/∂u,
// w = ±1, glTF's TANGENT) tangent = Σ bᵢ tᵢ.xyz, bitangent = sign(Σ bᵢ tᵢ.w) · ns × tangent;
// without them ∂p/∂u and ∂p/∂v of the triangle from its uvs (pbrt):
//   [∂p/∂u ∂p/∂v] = [p0 − p2, p1 − p2] · [uv0 − uv2, uv1 − uv2]⁻¹
// (none where the uvs are degenerate, |det| ≤ 1e-12 or not finite). A moving mesh turns
// both by its instance transform at the hit's time.
//
// Memory and speed: Embree traces the mesh's own position and index arrays (shared, see
// EmbreeScene), so they are allocated with one spare element for Embree's 16-byte loads.
// A static mesh also stores each triangle's unit normal (12 bytes/triangle): every hit
// and light sample needs it, and computing it (cross product, sqrt, divide) was a long
// latency chain in the path loop. Moving meshes compute it at the sample's time.
// Only a mesh that a light samples (an emitter) keeps the per-triangle area distribution
// and, if it is static, planar and one-sided, its FrontPlane (shape.h).
// A static mesh (one time step) skips the time interpolation, and its area pdf is 1/area:
// P(k)/area_k with P(k) = area_k/area. Two triangles of nearly equal area on a diagonal (a
// rectangle light; not an instanced one: MeshInstance) are sampled by parallelogramPoint,
// P(k) = ½: a better spread of the points, no search, no root.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "integrator/geometry/shape.h"
#include "integrator/sampling/distribution.h"

namespace camsim {

// A point on a mesh chosen by area, as MeshInstance and TriangleMesh (but for the
// parallelogram below) sample their lights:
// the triangle by u.x (∝ area), u.x rescaled to its share of the triangle, and the point by
// that remapped pair, so the pixel's stratified 2D points spread over the whole emitter (a
// quad's two triangles each get their half of them; picking by a separate number gave each
// triangle a random half of the points, plain Monte Carlo; Cycles reuses its number so too).
struct TrianglePoint {
  size_t tri = 0;
  float b1 = 0.0f, b2 = 0.0f;  // barycentrics of vertices 1 and 2
};
inline TrianglePoint pickTrianglePoint(const DiscreteDistribution& areas, glm::vec2 u) {
  const size_t tri = areas.sample(u.x, &u.x);
  const glm::vec2 b = sampleUniformTriangle(u);
  return {tri, b.y, 1.0f - b.x - b.y};
}
// Two triangles of (nearly) equal area on one diagonal, (p0, p1, p2) and (p0, p2, p3) (a
// rectangle light's): u.y ≤ u.x is triangle 0 at barycentrics (u.x − u.y, u.y), else triangle
// 1 at (u.x, u.y − u.x). Each half of the square maps linearly (Jacobian 1) onto its triangle
// and the two agree on the diagonal, so the density is ½ / area_k (1/area for equal areas,
// as pickTrianglePoint's), and for a
// parallelogram u is the point p0 + u.x·(p1 − p0) + u.y·(p2 − p1): the pixel's 2D points
// stay one stratified net over the emitter (the triangle choice and the square-root warp
// bend it), for no search and no root.
inline TrianglePoint parallelogramPoint(glm::vec2 u) {
  if (u.y <= u.x) return {0, u.x - u.y, u.y};
  return {1, u.x, u.y - u.x};
}

class TriangleMesh final : public Shape {
 public:
  // positions / normals: the stored pose (normals may be empty). indices: 3 per triangle.
  // uvs: empty or one per vertex (they do not move). Zero-area triangles are kept for
  // intersection (Embree never hits them) and are never sampled. samplable: false for a
  // mesh no light samples (sample() and pdf() must then not be called). instance: for a
  // moving mesh (steps.count > 1) one transform per step from the stored pose (Shape).
  // tangents: empty or one per vertex, in the stored pose (MeshData::tangents).
  TriangleMesh(std::vector<glm::vec3> positions, std::vector<glm::vec3> normals,
               std::vector<std::uint32_t> indices, TimeSteps steps, std::vector<glm::vec2> uvs = {},
               bool samplable = true, InstanceMotion instance = {},
               std::vector<glm::vec4> tangents = {});

  // Embree may load 16 bytes from the last vertex (float3) and the last index triple, so
  // the arrays it shares keep this many spare elements of capacity past their end.
  // TriangleMesh reserves them itself; a caller that allocates them up front saves a copy.
  static constexpr size_t kSpareVertices = 1;
  static constexpr size_t kSpareIndices = 3;

  // The stored pose (m): the mesh at rest, or the reference pose of a moving mesh.
  const std::vector<glm::vec3>& positions() const { return positions_; }
  const std::vector<std::uint32_t>& indices() const { return indices_; }
  const std::vector<glm::vec3>& normals() const { return normals_; }  // empty: none
  const std::vector<glm::vec2>& uvs() const { return uvs_; }          // empty: none
  // Static meshes: each triangle's unit normal as interaction() computes it (+z for a
  // degenerate one); empty for a moving mesh.
  const std::vector<glm::vec3>& faceNormals() const { return faceNormals_; }
  size_t triangleCount() const { return indices_.size() / 3; }
  // The texture coordinates interaction() gives triangle tri at barycentrics
  // (1 − b1 − b2, b1, b2) (Embree's u = b1, v = b2), by the same operations.
  glm::vec2 uvAt(size_t tri, float b1, float b2) const {
    if (uvs_.empty()) return {b1 + b2, b2};
    const float b0 = 1.0f - b1 - b2;
    return b0 * uvs_[indices_[3 * tri]] + b1 * uvs_[indices_[3 * tri + 1]] +
           b2 * uvs_[indices_[3 * tri + 2]];
  }
  const TimeSteps& timeSteps() const override { return steps_; }
  const InstanceMotion& instanceMotion() const override { return instance_; }

  float area() const override { return area_; }
  SurfaceInteraction interaction(const Hit& hit, const Ray& ray) const override;
  std::optional<SurfaceTangents> tangentFrame(const Hit& hit,
                                              const SurfaceInteraction& si) const override;
  std::optional<ShapeSample> sample(const glm::vec3& ref, float u1, glm::vec2 u2,
                                    double time) const override;
  float pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const override;
  std::optional<FrontPlane> frontPlane() const override { return frontPlane_; }

 private:
  static std::optional<FrontPlane> findFrontPlane(const std::vector<glm::vec3>& positions,
                                                  const std::vector<glm::vec3>& normals,
                                                  const std::vector<std::uint32_t>& indices,
                                                  const std::vector<double>& areas);

  glm::mat4 transformAt(double time) const;
  // The point of triangle tri at barycentrics (1 − b1 − b2, b1, b2) and `time`, into si
  // (every field but `shape`, which the caller keeps). area: if given and the mesh moves, receives the triangle's area at
  // `time` (m², computed anyway; a static mesh's area pdf does not need it).
  void pointOn(size_t tri, float b1, float b2, double time, float* area,
               SurfaceInteraction& si) const;
  void pointOnMoving(size_t tri, float b1, float b2, double time, float* area,
                     SurfaceInteraction& si) const;
  void finish(SurfaceInteraction& si, const glm::vec3& n, size_t tri, std::uint32_t i0,
              std::uint32_t i1, std::uint32_t i2, float b0, float b1, float b2, double time,
              const glm::mat4* m) const;
  float triangleArea(size_t tri, double time) const;
  float areaPdf(size_t tri, float area) const;

  std::vector<glm::vec3> positions_;  // the stored pose; shared with Embree
  std::vector<glm::vec3> normals_;
  std::vector<std::uint32_t> indices_;
  std::vector<glm::vec2> uvs_;
  std::vector<glm::vec4> tangents_;     // empty, or one per vertex (tangentFrame)
  std::vector<glm::vec3> faceNormals_;  // static meshes: unit normal per triangle (pointOn)
  TimeSteps steps_;
  InstanceMotion instance_;
  DiscreteDistribution areaDistribution_;  // empty unless samplable
  bool samplable_;
  float area_ = 0.0f;
  std::optional<FrontPlane> frontPlane_;  // static planar meshes only
  bool parallelogram_ = false;            // samplable, sampled by parallelogramPoint
  std::array<float, 2> restAreas_{};      // its two triangles' areas at rest (m², areaPdf)
};

}  // namespace camsim
