// The omnidirectional models: Mei's unified model, the double sphere and the
// equirectangular panorama. For a unit direction d = (X, Y, Z) at field angle θ:
//
// | parameter | unit | default | model |
// |-----------|------|---------|-------|
// | xi (ξ)    | —    | 0       | unified: ≥ 0 (0 is the pinhole, 1 the stereographic parabola); double sphere: [−1, 1] |
// | alpha (α) | —    | 0.5     | double sphere: [0, 1] |
// | k1 k2 p1 p2 | —  | 0       | unified: OpenCV omnidir's radial and tangential distortion |
//
// Unified (C. Mei & P. Rives, ICRA 2007; OpenCV omnidir, "Omnidirectional Camera
// Calibration"): the point on the unit sphere is projected from (0, 0, −ξ) onto the plane
// one unit in front of that centre,
//   m = (X, Y) / (Z + ξ),   ρ(θ) = sin θ / (cos θ + ξ),   dρ/dθ = (1 + ξ cos θ) / (cos θ + ξ)²,
// then distorted as OpenCV's pinhole with k1 k2 p1 p2 only (projection.cpp). Valid for
// cos θ > −min(ξ, 1/ξ) (the projection centre's horizon, or for ξ > 1 where ρ(θ) turns
// back). Inverse: t = (ξ + √(1 + (1 − ξ²) ρ²)) / (ρ² + 1), the sphere point (t·m, t − ξ).
//
// Double sphere (V. Usenko, N. Demmel, D. Cremers, "The Double Sphere Camera Model",
// 3DV 2018): d₂ = √(X² + Y² + (ξ + Z)²) = √(1 + 2ξ cos θ + ξ²),
//   m = (X, Y) / (α d₂ + (1 − α)(ξ + Z)),
// valid for Z > −w₂ with w₁ = α/(1−α) (α ≤ ½) or (1−α)/α (α > ½),
// w₂ = (w₁ + ξ)/√(2w₁ξ + ξ² + 1). Closed-form inverse, for r² = |m|² ≤ 1/(2α − 1) when α > ½:
//   m_z = (1 − α² r²) / (α √(1 − (2α − 1) r²) + 1 − α),
//   d ∝ (m_z ξ + √(m_z² + (1 − ξ²) r²)) / (m_z² + r²) · (m_x, m_y, m_z) − (0, 0, ξ).
// ξ = 0, α = ½ is the stereographic projection; α = 0 is the unified model.
//
// Equirectangular: longitude λ = atan2(X, Z) ∈ [−π, π], latitude φ = asin(Y) ∈ [−π/2, π/2]
// (positive down, as y); u = cx + fx λ, v = cy + fy φ. A full panorama of W×H pixels has
// fx = W/(2π), fy = H/π, cx = W/2 − ½, cy = H/2 − ½. dΩ = cos φ dλ dφ, so
// dΩ/dA = cos φ / (fx fy). maxFieldAngle does not apply.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "integrator/camera/projection_detail.h"

namespace camsim::projection_detail {

Radius unifiedRadius(double xi, double theta) {
  const double c = std::cos(theta), w = c + xi;
  return {std::sin(theta) / w, (1.0 + xi * c) / (w * w)};
}

double unifiedLimit(double xi) {
  const double w = xi <= 1.0 ? xi : 1.0 / xi;
  return std::acos(-std::clamp(w, 0.0, 1.0));
}

std::optional<double> unifiedFieldAngle(double xi, double rho) {
  const double r2 = rho * rho, disc = 1.0 + (1.0 - xi * xi) * r2;
  if (!(disc >= 0.0)) return std::nullopt;
  const double t = (xi + std::sqrt(disc)) / (r2 + 1.0);
  return std::atan2(t * rho, t - xi);
}

Radius doubleSphereRadius(double xi, double alpha, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  const double d2 = std::sqrt(1.0 + 2.0 * xi * c + xi * xi);
  const double den = alpha * d2 + (1.0 - alpha) * (xi + c);
  const double dden = -alpha * xi * s / d2 - (1.0 - alpha) * s;
  return {s / den, (c * den - s * dden) / (den * den)};
}

double doubleSphereLimit(double xi, double alpha) {
  const double w1 = alpha <= 0.5 ? alpha / (1.0 - alpha) : (1.0 - alpha) / alpha;
  const double w2 = (w1 + xi) / std::sqrt(2.0 * w1 * xi + xi * xi + 1.0);
  return std::acos(-std::clamp(w2, -1.0, 1.0));
}

std::optional<double> doubleSphereFieldAngle(double xi, double alpha, double rho) {
  const double r2 = rho * rho;
  const double inner = 1.0 - (2.0 * alpha - 1.0) * r2;
  if (!(inner >= 0.0)) return std::nullopt;
  const double mz = (1.0 - alpha * alpha * r2) / (alpha * std::sqrt(inner) + 1.0 - alpha);
  const double disc = mz * mz + (1.0 - xi * xi) * r2;
  if (!(disc >= 0.0)) return std::nullopt;
  const double t = (mz * xi + std::sqrt(disc)) / (mz * mz + r2);
  return std::atan2(t * rho, t * mz - xi);
}

std::optional<glm::dvec2> projectEquirectangular(const Projection& p, glm::dvec3 d) {
  const double lon = std::atan2(d.x, d.z), lat = std::atan2(d.y, std::hypot(d.x, d.z));
  return glm::dvec2(p.cx + p.fx * lon, p.cy + p.fy * lat);
}

std::optional<glm::dvec3> unprojectEquirectangular(const Projection& p, glm::dvec2 pixel) {
  const double lon = (pixel.x - p.cx) / p.fx, lat = (pixel.y - p.cy) / p.fy;
  if (!(std::abs(lon) <= std::numbers::pi && std::abs(lat) <= 0.5 * std::numbers::pi))
    return std::nullopt;
  const double c = std::cos(lat);
  return glm::dvec3(c * std::sin(lon), std::sin(lat), c * std::cos(lon));
}

double equirectangularDensity(const Projection& p, glm::dvec2 pixel) {
  const double lon = (pixel.x - p.cx) / p.fx, lat = (pixel.y - p.cy) / p.fy;
  if (!(std::abs(lon) <= std::numbers::pi && std::abs(lat) <= 0.5 * std::numbers::pi)) return 0.0;
  return std::cos(lat) / (p.fx * p.fy);
}

}  // namespace camsim::projection_detail
