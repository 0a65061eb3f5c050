#include "integrator/triangle_mesh.h"

#include "integrator/math.h"
#include "sensor/check.h"

namespace camsim {

TriangleMesh::TriangleMesh(std::vector<std::vector<glm::vec3>> positions,
                           std::vector<std::vector<glm::vec3>> normals,
                           std::vector<std::uint32_t> indices, TimeSteps steps,
                           std::vector<glm::vec2> uvs)
    : positions_(std::move(positions)),
      normals_(std::move(normals)),
      indices_(std::move(indices)),
      uvs_(std::move(uvs)),
      steps_(steps) {
  CAMSIM_CHECK(indices_.size() % 3 == 0 && !indices_.empty());
  CAMSIM_CHECK(static_cast<int>(positions_.size()) == steps_.count);
  CAMSIM_CHECK(normals_.empty() || normals_.size() == positions_.size());
  CAMSIM_CHECK(uvs_.empty() || uvs_.size() == positions_[0].size());
  std::vector<double> areas(triangleCount());
  double total = 0.0;
  for (size_t t = 0; t < triangleCount(); ++t) {
    const glm::dvec3 p0 = positions_[0][indices_[3 * t]], p1 = positions_[0][indices_[3 * t + 1]],
                     p2 = positions_[0][indices_[3 * t + 2]];
    areas[t] = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
    total += areas[t];
  }
  area_ = static_cast<float>(total);
  if (total > 0.0) areaDistribution_ = DiscreteDistribution(areas);
}

glm::vec3 TriangleMesh::vertex(std::uint32_t index, int step, float f) const {
  const glm::vec3& a = positions_[static_cast<size_t>(step)][index];
  if (f == 0.0f) return a;
  return (1.0f - f) * a + f * positions_[static_cast<size_t>(step) + 1][index];
}

float TriangleMesh::triangleArea(size_t tri, float time) const {
  int step;
  float f;
  steps_.locate(time, step, f);
  const glm::vec3 p0 = vertex(indices_[3 * tri], step, f),
                  p1 = vertex(indices_[3 * tri + 1], step, f),
                  p2 = vertex(indices_[3 * tri + 2], step, f);
  return 0.5f * glm::length(glm::cross(p1 - p0, p2 - p0));
}

SurfaceInteraction TriangleMesh::pointOn(size_t tri, float b1, float b2, float time) const {
  int step;
  float f;
  steps_.locate(time, step, f);
  const std::uint32_t i0 = indices_[3 * tri], i1 = indices_[3 * tri + 1],
                      i2 = indices_[3 * tri + 2];
  const glm::vec3 p0 = vertex(i0, step, f), p1 = vertex(i1, step, f), p2 = vertex(i2, step, f);
  const float b0 = 1.0f - b1 - b2;
  SurfaceInteraction si;
  si.p = b0 * p0 + b1 * p1 + b2 * p2;
  si.pError = gammaBound(7) * (glm::abs(b0 * p0) + glm::abs(b1 * p1) + glm::abs(b2 * p2));
  if (f != 0.0f)
    si.pError += gammaBound(3) * (glm::abs(p0) + glm::abs(p1) + glm::abs(p2));  // time lerp
  const glm::vec3 cross = glm::cross(p1 - p0, p2 - p0);
  const float len = glm::length(cross);
  si.n = len > 0.0f ? cross / len : glm::vec3(0.0f, 0.0f, 1.0f);
  si.ns = si.n;
  if (!normals_.empty()) {
    const auto& n0 = normals_[static_cast<size_t>(step)];
    const auto& n1 = normals_[static_cast<size_t>(f == 0.0f ? step : step + 1)];
    const glm::vec3 ns = b0 * glm::mix(n0[i0], n1[i0], f) + b1 * glm::mix(n0[i1], n1[i1], f) +
                         b2 * glm::mix(n0[i2], n1[i2], f);
    const float nsLen = glm::length(ns);
    if (nsLen > 0.0f && std::isfinite(nsLen)) {
      si.ns = ns / nsLen;
      // Keep the geometric normal on the side the mesh's normals point to.
      if (glm::dot(si.n, si.ns) < 0.0f) si.n = -si.n;
    }
  }
  si.uv = uvs_.empty() ? glm::vec2(b1 + b2, b2) : b0 * uvs_[i0] + b1 * uvs_[i1] + b2 * uvs_[i2];
  si.prim = static_cast<int>(tri);
  si.time = time;
  return si;
}

SurfaceInteraction TriangleMesh::interaction(const Hit& hit, const Ray& ray) const {
  return pointOn(static_cast<size_t>(hit.prim), hit.u, hit.v, ray.time);
}

std::optional<ShapeSample> TriangleMesh::sample(const glm::vec3& ref, float u1, glm::vec2 u2,
                                                float time) const {
  if (area_ <= 0.0f) return std::nullopt;
  const size_t tri = areaDistribution_.sample(u1);
  const glm::vec2 b = sampleUniformTriangle(u2);
  ShapeSample s;
  s.point = pointOn(tri, b.y, 1.0f - b.x - b.y, time);
  const float area = triangleArea(tri, time);
  if (!(area > 0.0f)) return std::nullopt;
  s.pdf = areaToSolidAnglePdf(areaDistribution_.pmf(tri) / area, ref, s.point);
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return std::nullopt;
  return s;
}

float TriangleMesh::pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const {
  if (area_ <= 0.0f || onShape.prim < 0) return 0.0f;
  const size_t tri = static_cast<size_t>(onShape.prim);
  const float area = triangleArea(tri, onShape.time);
  if (!(area > 0.0f)) return 0.0f;
  return areaToSolidAnglePdf(areaDistribution_.pmf(tri) / area, ref, onShape);
}

}  // namespace camsim
