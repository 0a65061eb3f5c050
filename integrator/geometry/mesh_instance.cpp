#include "integrator/geometry/mesh_instance.h"

#include <algorithm>
#include <cmath>

#include "integrator/geometry/math.h"
#include "sensor/base/check.h"

namespace camsim {
namespace {

// |m| per element times |v| per component: a bound on the magnitudes summed in m·v.
glm::vec3 absTimes(const glm::mat3& m, const glm::vec3& v) {
  const glm::vec3 a = absComponents(v);
  return absComponents(m[0]) * a.x + absComponents(m[1]) * a.y + absComponents(m[2]) * a.z;
}

// Largest absolute row sum (the ∞-norm).
template <typename M>
double infinityNorm(const M& m) {
  double norm = 0.0;
  for (int row = 0; row < 3; ++row)
    norm = std::max(norm, std::abs(static_cast<double>(m[0][row])) +
                              std::abs(static_cast<double>(m[1][row])) +
                              std::abs(static_cast<double>(m[2][row])));
  return norm;
}

// Columns a1 × a2, a2 × a0, a0 × a1: det(A)·A⁻ᵀ, so that cof·(u × v) = (A u) × (A v).
template <typename M>
M cofactor(const M& a) {
  return M(glm::cross(a[1], a[2]), glm::cross(a[2], a[0]), glm::cross(a[0], a[1]));
}

// ‖A‖∞·‖A⁻¹‖∞ of the linear part (≥ 1); CAMSIM_CHECK: invertible and finite.
double conditionOf(const glm::dmat4& pose) {
  const glm::dmat3 a(pose);
  const double det = glm::determinant(a);
  CAMSIM_CHECK(det != 0.0 && std::isfinite(det));
  const glm::dmat3 inverse = glm::transpose(cofactor(a)) / det;
  return std::max(1.0, infinityNorm(a) * infinityNorm(inverse));
}

}  // namespace

MeshInstance::Affine MeshInstance::affineOf(const glm::mat4& m) {
  Affine f;
  f.a = glm::mat3(m);
  f.t = glm::vec3(m[3]);
  f.cof = cofactor(f.a);
  f.sign = glm::determinant(f.a) < 0.0f ? -1.0f : 1.0f;
  return f;
}

MeshInstance::MeshInstance(std::shared_ptr<const TriangleMesh> mesh,
                           const std::vector<glm::dmat4>& poses, TimeSteps steps, bool samplable)
    : mesh_(std::move(mesh)), steps_(steps), samplable_(samplable) {
  CAMSIM_CHECK(mesh_ && mesh_->timeSteps().count == 1);
  CAMSIM_CHECK(poses.size() == static_cast<size_t>(steps_.count));
  placement_ = glm::mat4(poses.front());
  rest_ = affineOf(placement_);
  // The static instance's normal and area matrix in double, then rounded once.
  rest_.cof = glm::mat3(cofactor(glm::dmat3(poses.front())));
  rest_.sign = glm::determinant(glm::dmat3(poses.front())) < 0.0 ? -1.0f : 1.0f;
  double kappa = 1.0;
  for (const glm::dmat4& pose : poses) {
    kappa = std::max(kappa, conditionOf(pose));
    for (int axis = 0; axis < 3; ++axis)
      motion_.translation =
          std::max(motion_.translation, static_cast<float>(std::abs(pose[3][axis])));
  }
  kappa_ = static_cast<float>(kappa);
  // Conformal: AᵀA = s²·I within float rounding, at every step.
  for (const glm::dmat4& pose : poses) {
    const glm::dmat3 a(pose);
    const glm::dmat3 ata = glm::transpose(a) * a;
    const double s2 = (ata[0][0] + ata[1][1] + ata[2][2]) / 3.0;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r)
        conformal_ = conformal_ && std::abs(ata[c][r] - (c == r ? s2 : 0.0)) <= 1e-7 * s2;
  }
  if (steps_.count > 1)
    for (const glm::dmat4& pose : poses) motion_.steps.emplace_back(pose);
  if (!samplable_) return;
  // Render-space areas at rest, in double from the object's triangles.
  const glm::dmat3 cof = cofactor(glm::dmat3(poses.front()));
  const std::vector<glm::vec3>& p = mesh_->positions();
  const std::vector<std::uint32_t>& idx = mesh_->indices();
  std::vector<double> areas(mesh_->triangleCount());
  double total = 0.0;
  for (size_t k = 0; k < areas.size(); ++k) {
    const glm::dvec3 p0(p[idx[3 * k]]), p1(p[idx[3 * k + 1]]), p2(p[idx[3 * k + 2]]);
    areas[k] = 0.5 * glm::length(cof * glm::cross(p1 - p0, p2 - p0));
    total += areas[k];
  }
  area_ = static_cast<float>(total);
  if (total > 0.0) areaDistribution_ = DiscreteDistribution(areas);
}

float MeshInstance::area() const {
  if (samplable_) return area_;
  double total = 0.0;
  for (size_t k = 0; k < mesh_->triangleCount(); ++k)
    total += static_cast<double>(triangleArea(k, rest_.cof));
  return static_cast<float>(total);
}

MeshInstance::Affine MeshInstance::affineAt(double time) const {
  if (motion_.empty()) return rest_;
  int step;
  float f;
  steps_.locate(time, step, f);
  return affineOf(motion_.at(step, f));
}

float MeshInstance::triangleArea(size_t tri, const glm::mat3& cof) const {
  const std::vector<glm::vec3>& p = mesh_->positions();
  const std::vector<std::uint32_t>& idx = mesh_->indices();
  const glm::vec3 p0 = p[idx[3 * tri]], p1 = p[idx[3 * tri + 1]], p2 = p[idx[3 * tri + 2]];
  return 0.5f * glm::length(cof * glm::cross(p1 - p0, p2 - p0));
}

float MeshInstance::areaPdf(size_t tri, float area) const {
  if (motion_.empty()) return 1.0f / area_;
  return area > 0.0f ? areaDistribution_.pmf(tri) / area : 0.0f;
}

void MeshInstance::pointOn(size_t tri, float b1, float b2, double time, float* area,
                           SurfaceInteraction& si) const {
  // The mesh's own point in object space (p, its error, ns, uv), then placed.
  Hit hit;
  hit.prim = static_cast<int>(tri);
  hit.u = b1;
  hit.v = b2;
  const SurfaceInteraction o = mesh_->interaction(hit, Ray{});
  const Affine m = affineAt(time);
  si.p = m.a * o.p + m.t;
  const glm::vec3 magnitude = absTimes(m.a, o.p) + absComponents(m.t);
  const float rounding = gammaBound(motion_.empty() ? 4 : 6);
  const glm::vec3 a = absComponents(si.p);
  const float embree =
      gammaBound(8) * kappa_ * (std::max(a.x, std::max(a.y, a.z)) + motion_.translation);
  si.pError = absTimes(m.a, o.pError) + rounding * magnitude + glm::vec3(embree);
  // Geometric normal: the placed triangle's, from the object's stored one.
  glm::vec3 n = m.cof * mesh_->faceNormals()[tri];
  const float nLen = std::sqrt(glm::dot(n, n));
  n = nLen > 0.0f && std::isfinite(nLen) ? n * (1.0f / nLen) : glm::vec3(0.0f, 0.0f, 1.0f);
  si.n = n;
  si.ns = n;
  if (!mesh_->normals().empty()) {
    // |det A|·A⁻ᵀ·n has the direction of A⁻ᵀ·n. A conformal A keeps the vertex normals'
    // lengths equal, so the object's interpolated normal, placed, is the placed normals'
    // interpolation; otherwise they are placed and normalised one by one first, as a
    // baked copy stores them.
    glm::vec3 ns;
    if (conformal_) {
      ns = m.sign * (m.cof * o.ns);
    } else {
      const std::vector<glm::vec3>& normals = mesh_->normals();
      const std::vector<std::uint32_t>& idx = mesh_->indices();
      const glm::mat3 normalMatrix = m.sign * m.cof;
      const auto placed = [&](std::uint32_t i) {
        const glm::vec3 v = normalMatrix * normals[i];
        const float len = std::sqrt(glm::dot(v, v));
        return len > 0.0f ? v * (1.0f / len) : v;
      };
      ns = (1.0f - b1 - b2) * placed(idx[3 * tri]) + b1 * placed(idx[3 * tri + 1]) +
           b2 * placed(idx[3 * tri + 2]);
    }
    const float nsLen = std::sqrt(glm::dot(ns, ns));
    if (nsLen > 0.0f && std::isfinite(nsLen)) {
      si.ns = ns / nsLen;
      if (glm::dot(si.n, si.ns) < 0.0f) si.n = -si.n;  // as TriangleMesh: n on ns's side
    }
  }
  si.uv = o.uv;
  si.prim = static_cast<int>(tri);
  si.time = time;
  if (area) *area = triangleArea(tri, m.cof);
}

SurfaceInteraction MeshInstance::interaction(const Hit& hit, const Ray& ray) const {
  SurfaceInteraction si;
  pointOn(static_cast<size_t>(hit.prim), hit.u, hit.v, ray.time, nullptr, si);
  return si;
}

std::optional<SurfaceTangents> MeshInstance::tangentFrame(const Hit& hit,
                                                          const SurfaceInteraction& si) const {
  const Affine a = affineAt(si.time);
  SurfaceInteraction object = si;  // the shading normal in object space: Aᵀ·n (∝ A⁻¹ᵀ⁻¹)
  const glm::vec3 n = glm::transpose(a.a) * si.ns;
  const float len = glm::length(n);
  if (!(len > 0.0f)) return std::nullopt;
  object.ns = n / len;
  const std::optional<SurfaceTangents> f = mesh_->tangentFrame(hit, object);
  if (!f) return std::nullopt;
  return SurfaceTangents{a.a * f->tangent, a.a * f->bitangent};
}

std::optional<ShapeSample> MeshInstance::sample(const glm::vec3& ref, float /*u1*/, glm::vec2 u2,
                                                double time) const {
  CAMSIM_CHECK(samplable_);
  std::optional<ShapeSample> out;
  if (area_ <= 0.0f) return out;
  const TrianglePoint t = pickTrianglePoint(areaDistribution_, u2);
  ShapeSample& s = out.emplace();
  float area = 0.0f;
  pointOn(t.tri, t.b1, t.b2, time, motion_.empty() ? nullptr : &area, s.point);
  const float pdfArea = areaPdf(t.tri, area);
  completeAreaSample(out, ref, pdfArea);
  return out;
}

float MeshInstance::pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const {
  CAMSIM_CHECK(samplable_);
  if (area_ <= 0.0f || onShape.prim < 0) return 0.0f;
  const auto tri = static_cast<size_t>(onShape.prim);
  const float area = motion_.empty() ? area_ : triangleArea(tri, affineAt(onShape.time).cof);
  const float pdfArea = areaPdf(tri, area);
  if (!(pdfArea > 0.0f)) return 0.0f;
  return areaToSolidAnglePdf(pdfArea, ref, onShape);
}

}  // namespace camsim
