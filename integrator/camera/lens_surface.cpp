#include "integrator/camera/lens_surface.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace camsim {

bool LensSurface::aspheric() const {
  if (conic != 0.0) return true;
  for (const double a : asphere)
    if (a != 0.0) return true;
  return false;
}

SurfaceShape SurfaceShape::from(const LensSurface& s, double vertexZ) {
  SurfaceShape shape;
  shape.vertexZ = vertexZ;
  shape.curvature = s.curvature();
  shape.conic = s.conic;
  shape.asphere = s.asphere;
  shape.clearRadius2 = 0.25 * s.apertureDiameter * s.apertureDiameter;
  shape.aspheric = s.aspheric();
  return shape;
}

bool sagDefined(const SurfaceShape& s, double rSquared) {
  return 1.0 - (1.0 + s.conic) * s.curvature * s.curvature * rSquared > 0.0;
}

double sag(const SurfaceShape& s, double rSquared) {
  const double c = s.curvature;
  const double root = std::sqrt(std::max(0.0, 1.0 - (1.0 + s.conic) * c * c * rSquared));
  double z = c * rSquared / (1.0 + root);
  // Σ a_{2i} r^{2i} = r⁴ (a4 + r² (a6 + r² (…))) by Horner's rule in r².
  double poly = 0.0;
  for (int i = kAsphereTerms - 1; i >= 0; --i) poly = poly * rSquared + s.asphere[i];
  return z + poly * rSquared * rSquared;
}

double sagSlopeOverR(const SurfaceShape& s, double rSquared) {
  const double c = s.curvature;
  const double root = std::sqrt(std::max(0.0, 1.0 - (1.0 + s.conic) * c * c * rSquared));
  // d/dr of the conic term is c r / √(…); of a_{2i} r^{2i} it is 2i a_{2i} r^{2i−1}.
  const double slope = root > 0.0 ? c / root : 0.0;  // root > 0 where sagDefined
  double poly = 0.0;
  for (int i = kAsphereTerms - 1; i >= 0; --i)
    poly = poly * rSquared + 2.0 * (i + 2) * s.asphere[i];
  return slope + poly * rSquared;  // Σ 2i a_{2i} r^{2i−2} = r² Σ 2(j+2) a r^{2j}
}

glm::dvec3 surfaceNormal(const SurfaceShape& s, const glm::dvec3& p) {
  const double k = sagSlopeOverR(s, p.x * p.x + p.y * p.y);
  return glm::normalize(glm::dvec3(k * p.x, k * p.y, 1.0));
}

namespace {

// The base sphere's (or plane's) root on the vertex's hemisphere, first ahead; -1 if none.
// With w = z − vertexZ the sphere is c (x² + y² + w²) + 2w = 0: A t² + B t + C = 0.
double baseRoot(const SurfaceShape& s, const glm::dvec3& o, const glm::dvec3& d) {
  const double c = s.curvature, ow = o.z - s.vertexZ;
  const double a = c * glm::dot(d, d);
  const double b = 2.0 * (c * (o.x * d.x + o.y * d.y + ow * d.z) + d.z);
  const double cc = c * (o.x * o.x + o.y * o.y + ow * ow) + 2.0 * ow;
  if (a == 0.0) {  // a plane
    if (b == 0.0) return -1.0;
    const double t = -cc / b;
    return t > 0.0 && std::isfinite(t) ? t : -1.0;
  }
  const double disc = b * b - 4.0 * a * cc;
  if (!(disc >= 0.0)) return -1.0;
  // The two roots without cancellation: q = −(b + sign(b)√disc)/2, t = q/a and c/q.
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  double t0 = q / a, t1 = q != 0.0 ? cc / q : t0;
  if (t0 > t1) std::swap(t0, t1);
  for (const double t : {t0, t1}) {
    const double w = ow + t * d.z;
    if (t > 0.0 && std::isfinite(t) && 1.0 + c * w > 0.0) return t;
  }
  return -1.0;
}

}  // namespace

std::optional<double> intersectSurface(const SurfaceShape& s, const glm::dvec3& o,
                                       const glm::dvec3& d) {
  double t = baseRoot(s, o, d);
  if (!s.aspheric) {
    if (t > 0.0) return t;
    return std::nullopt;
  }
  if (!(t > 0.0)) {  // the base sphere missed: start from the vertex plane
    if (d.z == 0.0) return std::nullopt;
    t = (s.vertexZ - o.z) / d.z;
  }
  // Newton on g(t) = vertexZ − sag(r²(t)) − z(t); g'(t) = −(sag'/r)(x dx + y dy) − dz.
  for (int iteration = 0; iteration < 40; ++iteration) {
    const glm::dvec3 p = o + t * d;
    const double r2 = p.x * p.x + p.y * p.y;
    if (!sagDefined(s, r2)) return std::nullopt;
    const double g = s.vertexZ - sag(s, r2) - p.z;
    const double dg = -sagSlopeOverR(s, r2) * (p.x * d.x + p.y * d.y) - d.z;
    if (!(std::abs(dg) > 1e-300)) return std::nullopt;
    const double step = g / dg;
    t -= step;
    if (!std::isfinite(t)) return std::nullopt;
    if (std::abs(step) < 1e-14) {
      if (t > 0.0) return t;
      return std::nullopt;
    }
  }
  return std::nullopt;
}

bool refract(glm::dvec3& d, glm::dvec3 n, double etaFrom, double etaTo) {
  double cosI = -glm::dot(n, d);
  if (cosI < 0.0) {  // face the normal against the incoming ray
    n = -n;
    cosI = -cosI;
  }
  const double eta = etaFrom / etaTo;
  const double k = 1.0 - eta * eta * (1.0 - cosI * cosI);
  if (k < 0.0) return false;  // total internal reflection
  d = eta * d + (eta * cosI - std::sqrt(k)) * n;
  return true;
}

}  // namespace camsim
