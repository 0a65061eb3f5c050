#include "integrator/geometry/triangle_mesh.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>

#include "integrator/geometry/math.h"
#include "sensor/base/check.h"

namespace camsim {

namespace {

// Room for `spare` elements past the end, which Embree may read (see the header); a
// caller that built the vector with that capacity already pays no copy.
template <typename T>
void reserveSpare(std::vector<T>& v, size_t spare) {
  if (v.capacity() < v.size() + spare) v.reserve(v.size() + spare);
}

// The unit normal (p1 − p0) × (p2 − p0) / |…| in float, and |…| (twice the area); +z for a
// degenerate triangle. One function for pointOn and the static meshes' stored normals,
// so both give the same bits.
glm::vec3 faceNormal(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                     float* crossLength = nullptr) {
  const glm::vec3 cross = glm::cross(p1 - p0, p2 - p0);
  const float len = std::sqrt(glm::dot(cross, cross));
  if (crossLength) *crossLength = len;
  return len > 0.0f ? cross * (1.0f / len) : glm::vec3(0.0f, 0.0f, 1.0f);
}

}  // namespace

TriangleMesh::TriangleMesh(std::vector<glm::vec3> positions, std::vector<glm::vec3> normals,
                           std::vector<std::uint32_t> indices, TimeSteps steps,
                           std::vector<glm::vec2> uvs, bool samplable, InstanceMotion instance,
                           std::vector<glm::vec4> tangents)
    : positions_(std::move(positions)),
      normals_(std::move(normals)),
      indices_(std::move(indices)),
      uvs_(std::move(uvs)),
      tangents_(std::move(tangents)),
      steps_(steps),
      instance_(std::move(instance)),
      samplable_(samplable) {
  CAMSIM_CHECK(indices_.size() % 3 == 0 && !indices_.empty());
  CAMSIM_CHECK(normals_.empty() || normals_.size() == positions_.size());
  CAMSIM_CHECK(uvs_.empty() || uvs_.size() == positions_.size());
  CAMSIM_CHECK(tangents_.empty() || tangents_.size() == positions_.size());
  CAMSIM_CHECK(steps_.count == 1 ? instance_.empty()
                                 : instance_.steps.size() == static_cast<size_t>(steps_.count));
  reserveSpare(positions_, kSpareVertices);
  reserveSpare(indices_, kSpareIndices);
  // Areas at rest: at the first time step.
  const glm::dmat4 rest = instance_.empty() ? glm::dmat4(1.0) : glm::dmat4(instance_.steps[0]);
  const auto restVertex = [&](std::uint32_t i) {
    return glm::dvec3(rest * glm::dvec4(glm::dvec3(positions_[i]), 1.0));
  };
  std::vector<double> areas(samplable_ ? triangleCount() : 0);
  // Stored normals for the meshes pointOn takes its static path for (no instance).
  faceNormals_.resize(instance_.empty() ? triangleCount() : 0);
  double total = 0.0;
  for (size_t t = 0; t < triangleCount(); ++t) {
    const std::uint32_t i0 = indices_[3 * t], i1 = indices_[3 * t + 1], i2 = indices_[3 * t + 2];
    const glm::dvec3 p0 = restVertex(i0), p1 = restVertex(i1), p2 = restVertex(i2);
    const double area = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
    if (samplable_) areas[t] = area;
    total += area;
    if (!faceNormals_.empty())
      faceNormals_[t] = faceNormal(positions_[i0], positions_[i1], positions_[i2]);
  }
  area_ = static_cast<float>(total);
  if (samplable_ && total > 0.0) areaDistribution_ = DiscreteDistribution(areas);
  // Two triangles (p0, p1, p2), (p0, p2, p3) of nearly equal area at rest (within 1e-3 of
  // the total: a rectangle's float corners even far from the camera). Their density is
  // exactly ½ / area_k (areaPdf), so "nearly" costs no bias, only variance.
  parallelogram_ = samplable_ && triangleCount() == 2 && indices_[3] == indices_[0] &&
                   indices_[4] == indices_[2] && areas[0] > 0.0 && areas[1] > 0.0 &&
                   std::abs(areas[0] - areas[1]) <= 1e-3 * total;
  if (parallelogram_) restAreas_ = {static_cast<float>(areas[0]), static_cast<float>(areas[1])};
  if (samplable_ && steps_.count == 1)
    frontPlane_ = findFrontPlane(positions_, normals_, indices_, areas);
}

// The plane of a static mesh's triangles, if they all lie in one with the same front. Each
// triangle that can be sampled (areas[k] > 0, as the area distribution has it) must have a normal as pointOn computes it (float
// cross product) within ≈ 1e-3 rad of the first one's, and every vertex normal clearly on
// its front side (so pointOn never flips n). The bounds are measured in double over the vertices.
std::optional<FrontPlane> TriangleMesh::findFrontPlane(const std::vector<glm::vec3>& positions,
                                                       const std::vector<glm::vec3>& normals,
                                                       const std::vector<std::uint32_t>& indices,
                                                       const std::vector<double>& areas) {
  std::optional<glm::dvec3> planeNormal;
  double maxChord = 0.0;
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (size_t k = 0; k < indices.size(); k += 3) {
    const std::uint32_t i[3] = {indices[k], indices[k + 1], indices[k + 2]};
    if (!(areas[k / 3] > 0.0)) continue;  // never sampled
    const glm::vec3 cross =
        glm::cross(positions[i[1]] - positions[i[0]], positions[i[2]] - positions[i[0]]);
    if (!(glm::dot(cross, cross) > 0.0f)) return std::nullopt;  // pointOn would use +z
    const glm::dvec3 n = glm::normalize(glm::dvec3(cross));
    if (!planeNormal) planeNormal = n;
    const double chord = glm::length(n - *planeNormal);
    if (!(chord <= 1e-3)) return std::nullopt;  // also NaN (an overflowing cross product)
    maxChord = std::max(maxChord, chord);
    for (const std::uint32_t v : i) {
      // Vertex normals clearly on the front (cos > 1e-3): pointOn's float n and interpolated
      // ns (barycentrics a rounding off [0, 1]) then never disagree in sign.
      if (!normals.empty()) {
        const glm::dvec3 nv(normals[v]);
        if (!(glm::dot(nv, n) > 1e-3 * glm::length(nv))) return std::nullopt;
      }
      lo = glm::min(lo, glm::dvec3(positions[v]));
      hi = glm::max(hi, glm::dvec3(positions[v]));
    }
  }
  if (!planeNormal) return std::nullopt;
  const glm::dvec3 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  const double offset = glm::dot(*planeNormal, centre);
  double spread = 0.0;
  for (size_t k = 0; k < indices.size(); ++k) {
    const glm::dvec3 p(positions[indices[k]]);
    spread = std::max(spread, std::abs(glm::dot(*planeNormal, p) - offset));
  }
  FrontPlane plane;
  plane.n = glm::vec3(*planeNormal);
  plane.offset = static_cast<float>(offset);
  plane.centre = glm::vec3(centre);
  plane.radius = static_cast<float>(glm::length(half)) * (1.0f + 1e-6f);
  plane.spread = static_cast<float>(spread) * (1.0f + 1e-6f);
  // Twice the measured chord, plus float normalisation and the float plane normal.
  plane.tilt = static_cast<float>(2.0 * maxChord + 1e-6);
  return plane;
}

// Moving mesh: the instance transform at `time`.
glm::mat4 TriangleMesh::transformAt(double time) const {
  int step;
  float f;
  steps_.locate(time, step, f);
  return instance_.at(step, f);
}

float TriangleMesh::triangleArea(size_t tri, double time) const {
  const glm::mat4 m = transformAt(time);
  const std::uint32_t i0 = indices_[3 * tri], i1 = indices_[3 * tri + 1],
                      i2 = indices_[3 * tri + 2];
  const auto vertex = [&](std::uint32_t i) {
    return glm::vec3(m * glm::vec4(positions_[i], 1.0f));
  };
  const glm::vec3 p0 = vertex(i0), p1 = vertex(i1), p2 = vertex(i2);
  return 0.5f * glm::length(glm::cross(p1 - p0, p2 - p0));
}

// Density by area of sample() producing a point of triangle tri whose area at that time
// is `area` (m²; a static mesh's density does not depend on it). parallelogramPoint draws
// each of its two triangles with probability ½.
float TriangleMesh::areaPdf(size_t tri, float area) const {
  if (parallelogram_) {
    const float a = steps_.count == 1 ? restAreas_[tri] : area;
    return a > 0.0f ? 0.5f / a : 0.0f;
  }
  if (steps_.count == 1) return 1.0f / area_;
  return area > 0.0f ? areaDistribution_.pmf(tri) / area : 0.0f;
}

namespace {

// The point b0·p0 + b1·p1 + b2·p2 and the bound on its rounding error, with the three
// coordinates in Float4 lanes (the fourth is 0): the same operations in the same order as
// on glm::vec3, so the same bits, in a third of the instructions. Sets si.p and si.pError.
[[gnu::always_inline]] inline void interpolate(SurfaceInteraction& si, Float4 p0, Float4 p1,
                                               Float4 p2, float b0, float b1, float b2) {
  const Float4 t0 = b0 * p0, t1 = b1 * p1, t2 = b2 * p2;
  const Float4 p = t0 + t1 + t2;
  const Int4 noSign = Int4{} + 0x7fffffff;
  const auto abs = [&](Float4 v) { return std::bit_cast<Float4>(std::bit_cast<Int4>(v) & noSign); };
  const Float4 error = gammaBound(7) * (abs(t0) + abs(t1) + abs(t2));
  si.p = {p[0], p[1], p[2]};
  si.pError = {error[0], error[1], error[2]};
}

Float4 lanesOf(const glm::vec3& v) {
  return Float4{v.x, v.y, v.z, 0.0f};
}

}  // namespace

// Normals, texture coordinates, triangle and time of a point whose p and pError are set.
// n: the geometric normal; m: the instance transform of a moving mesh (else null).
// i0, i1, i2: the triangle's vertex indices (the caller has loaded them already).
[[gnu::always_inline]] inline void TriangleMesh::finish(SurfaceInteraction& si, const glm::vec3& n,
                                                        size_t tri, std::uint32_t i0,
                                                        std::uint32_t i1, std::uint32_t i2,
                                                        float b0, float b1, float b2, double time,
                                                        const glm::mat4* m) const {
  // n stays in a register: copying si.n into si.ns through memory right after the three
  // scalar stores stalled on store forwarding (seen with perf).
  si.n = n;
  si.ns = n;
  if (!normals_.empty()) {
    glm::vec3 ns = b0 * normals_[i0] + b1 * normals_[i1] + b2 * normals_[i2];
    if (m) ns = glm::mat3(*m) * ns;  // uniform scale: renormalised below
    const float nsLen = std::sqrt(glm::dot(ns, ns));
    if (nsLen > 0.0f && std::isfinite(nsLen)) {
      si.ns = ns / nsLen;
      // Keep the geometric normal on the side the mesh's normals point to.
      if (glm::dot(si.n, si.ns) < 0.0f) si.n = -si.n;
    }
  }
  si.uv = uvs_.empty() ? glm::vec2(b1 + b2, b2) : b0 * uvs_[i0] + b1 * uvs_[i1] + b2 * uvs_[i2];
  si.prim = static_cast<int>(tri);
  si.time = time;
}

// Hot: every hit and every light sample on a mesh comes through here. A static mesh has a
// path of its own: no time lookup, no transform, the stored normal, and few enough live
// values that none is spilled to the stack (one function for both spilled them all).
// It writes into the caller's point: returned by value, the point was copied into the
// light sample in 16-byte loads of fields just stored in 4 bytes (stalled store
// forwarding).
void TriangleMesh::pointOn(size_t tri, float b1, float b2, double time, float* area,
                           SurfaceInteraction& si) const {
  if (!instance_.empty()) return pointOnMoving(tri, b1, b2, time, area, si);
  const std::uint32_t i0 = indices_[3 * tri], i1 = indices_[3 * tri + 1],
                      i2 = indices_[3 * tri + 2];
  // Each vertex in one 16-byte load, the fourth lane (the next vertex's x, or the spare
  // element Embree's loads also need; see kSpareVertices) cleared.
  const auto vertex = [this](std::uint32_t i) {
    Float4 v;
    std::memcpy(&v, positions_.data() + i, sizeof v);
    return std::bit_cast<Float4>(std::bit_cast<Int4>(v) & Int4{-1, -1, -1, 0});
  };
  const float b0 = 1.0f - b1 - b2;
  interpolate(si, vertex(i0), vertex(i1), vertex(i2), b0, b1, b2);
  finish(si, faceNormals_[tri], tri, i0, i1, i2, b0, b1, b2, time, nullptr);
}

void TriangleMesh::pointOnMoving(size_t tri, float b1, float b2, double time, float* area,
                                 SurfaceInteraction& si) const {
  const glm::mat4 m = transformAt(time);
  const std::uint32_t i0 = indices_[3 * tri], i1 = indices_[3 * tri + 1],
                      i2 = indices_[3 * tri + 2];
  const auto vertex = [&](std::uint32_t i) {
    return glm::vec3(m * glm::vec4(positions_[i], 1.0f));
  };
  const glm::vec3 p0 = vertex(i0), p1 = vertex(i1), p2 = vertex(i2);
  const float b0 = 1.0f - b1 - b2;
  interpolate(si, lanesOf(p0), lanesOf(p1), lanesOf(p2), b0, b1, b2);
  // The transform's rounding here and in Embree (Shape).
  si.pError += gammaBound(3) * (absComponents(p0) + absComponents(p1) + absComponents(p2)) +
               instance_.error(si.p);
  float len;
  const glm::vec3 n = faceNormal(p0, p1, p2, &len);
  if (area) *area = 0.5f * len;  // the triangle's area at `time` (sample() needs it)
  finish(si, n, tri, i0, i1, i2, b0, b1, b2, time, &m);
}

SurfaceInteraction TriangleMesh::interaction(const Hit& hit, const Ray& ray) const {
  SurfaceInteraction si;
  pointOn(static_cast<size_t>(hit.prim), hit.u, hit.v, ray.time, nullptr, si);
  return si;
}

std::optional<SurfaceTangents> TriangleMesh::tangentFrame(const Hit& hit,
                                                          const SurfaceInteraction& si) const {
  const auto tri = static_cast<size_t>(hit.prim);
  const std::uint32_t i0 = indices_[3 * tri], i1 = indices_[3 * tri + 1],
                      i2 = indices_[3 * tri + 2];
  const float b1 = hit.u, b2 = hit.v, b0 = 1.0f - b1 - b2;
  const glm::mat3 turn = instance_.empty() ? glm::mat3(1.0f) : glm::mat3(transformAt(si.time));
  if (!tangents_.empty()) {
    const glm::vec4 t = b0 * tangents_[i0] + b1 * tangents_[i1] + b2 * tangents_[i2];
    const glm::vec3 tangent = turn * glm::vec3(t);
    return SurfaceTangents{tangent, (t.w < 0.0f ? -1.0f : 1.0f) * glm::cross(si.ns, tangent)};
  }
  const glm::vec2 uv0 = uvs_.empty() ? glm::vec2(0.0f) : uvs_[i0];
  const glm::vec2 uv1 = uvs_.empty() ? glm::vec2(1.0f, 0.0f) : uvs_[i1];
  const glm::vec2 uv2 = uvs_.empty() ? glm::vec2(1.0f) : uvs_[i2];
  const glm::vec2 d02 = uv0 - uv2, d12 = uv1 - uv2;
  const float det = d02.x * d12.y - d02.y * d12.x;
  if (!(std::abs(det) > 1e-12f) || !std::isfinite(det)) return std::nullopt;
  const glm::vec3 p02 = turn * (positions_[i0] - positions_[i2]);
  const glm::vec3 p12 = turn * (positions_[i1] - positions_[i2]);
  const float inv = 1.0f / det;
  return SurfaceTangents{(d12.y * p02 - d02.y * p12) * inv, (d02.x * p12 - d12.x * p02) * inv};
}

std::optional<ShapeSample> TriangleMesh::sample(const glm::vec3& ref, float /*u1*/, glm::vec2 u2,
                                                double time) const {
  CAMSIM_CHECK(samplable_);
  // Every return returns `out`, so the sample is built in the caller's slot. Built in a
  // local and returned, it was copied out in 16-byte loads of fields just stored in 4 and 8
  // bytes: stalled store forwarding, a third of this function's time (pointOn likewise).
  std::optional<ShapeSample> out;
  if (area_ <= 0.0f) return out;
  const TrianglePoint t =
      parallelogram_ ? parallelogramPoint(u2) : pickTrianglePoint(areaDistribution_, u2);
  ShapeSample& s = out.emplace();
  float area = 0.0f;
  pointOn(t.tri, t.b1, t.b2, time, &area, s.point);
  const float pdfArea = areaPdf(t.tri, area);
  completeAreaSample(out, ref, pdfArea);
  return out;
}

float TriangleMesh::pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const {
  CAMSIM_CHECK(samplable_);
  if (area_ <= 0.0f || onShape.prim < 0) return 0.0f;
  const auto tri = static_cast<size_t>(onShape.prim);
  const float pdfArea = areaPdf(tri, steps_.count == 1 ? area_ : triangleArea(tri, onShape.time));
  if (!(pdfArea > 0.0f)) return 0.0f;
  return areaToSolidAnglePdf(pdfArea, ref, onShape);
}

}  // namespace camsim
