#include "integrator/triangle_mesh.h"

#include "integrator/math.h"
#include "sensor/check.h"

namespace camsim {

TriangleMesh::TriangleMesh(std::vector<glm::vec3> positions, std::vector<glm::vec3> normals,
                           std::vector<std::uint32_t> indices)
    : positions_(std::move(positions)), normals_(std::move(normals)), indices_(std::move(indices)) {
  CAMSIM_CHECK(indices_.size() % 3 == 0 && !indices_.empty());
  CAMSIM_CHECK(normals_.empty() || normals_.size() == positions_.size());
  std::vector<double> areas(triangleCount());
  double total = 0.0;
  for (size_t t = 0; t < triangleCount(); ++t) {
    const glm::dvec3 p0 = positions_[indices_[3 * t]], p1 = positions_[indices_[3 * t + 1]],
                     p2 = positions_[indices_[3 * t + 2]];
    areas[t] = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
    total += areas[t];
  }
  area_ = static_cast<float>(total);
  if (total > 0.0) areaDistribution_ = DiscreteDistribution(areas);
}

SurfaceInteraction TriangleMesh::pointOn(size_t tri, float b1, float b2) const {
  const std::uint32_t i0 = indices_[3 * tri], i1 = indices_[3 * tri + 1], i2 = indices_[3 * tri + 2];
  const glm::vec3 &p0 = positions_[i0], &p1 = positions_[i1], &p2 = positions_[i2];
  const float b0 = 1.0f - b1 - b2;
  SurfaceInteraction si;
  si.p = b0 * p0 + b1 * p1 + b2 * p2;
  si.pError = gammaBound(7) * (glm::abs(b0 * p0) + glm::abs(b1 * p1) + glm::abs(b2 * p2));
  const glm::vec3 cross = glm::cross(p1 - p0, p2 - p0);
  const float len = glm::length(cross);
  si.n = len > 0.0f ? cross / len : glm::vec3(0.0f, 0.0f, 1.0f);
  si.ns = si.n;
  if (!normals_.empty()) {
    const glm::vec3 ns = b0 * normals_[i0] + b1 * normals_[i1] + b2 * normals_[i2];
    const float nsLen = glm::length(ns);
    if (nsLen > 0.0f && std::isfinite(nsLen)) {
      si.ns = ns / nsLen;
      // Keep the geometric normal on the side the mesh's normals point to.
      if (glm::dot(si.n, si.ns) < 0.0f) si.n = -si.n;
    }
  }
  return si;
}

SurfaceInteraction TriangleMesh::interaction(const Hit& hit, const Ray& ray) const {
  SurfaceInteraction si = pointOn(static_cast<size_t>(hit.prim), hit.u, hit.v);
  si.time = ray.time;
  return si;
}

std::optional<ShapeSample> TriangleMesh::sample(const glm::vec3& ref, float u1, glm::vec2 u2) const {
  if (area_ <= 0.0f) return std::nullopt;
  const size_t tri = areaDistribution_.sample(u1);
  const glm::vec2 b = sampleUniformTriangle(u2);
  ShapeSample s;
  s.point = pointOn(tri, b.y, 1.0f - b.x - b.y);
  s.pdf = areaToSolidAnglePdf(1.0f / area_, ref, s.point);
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return std::nullopt;
  return s;
}

float TriangleMesh::pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const {
  if (area_ <= 0.0f) return 0.0f;
  return areaToSolidAnglePdf(1.0f / area_, ref, onShape);
}

}  // namespace camsim
