// LensSystem: real rays (both ways), focus, the traced focal length and the chief ray.
//
// A ray meets each surface in turn (lens_surface.h: closed form, or Newton for an
// asphere), is lost outside the surface's clear aperture or the stop's shape, and
// refracts by Snell's law (lost at total internal reflection) when the indices on the
// two sides differ. Nothing is allocated: the indices at the wavelength are on the stack.
//
// Focus (focusSensorDistance):
//   kParaxial: s = −(A d + B)/(C d + D) at λ (lens_system.h), BFL at infinity.
//   kBestRms:  256 real meridional rays from the axial object point (parallel at infinity)
//     through rings of the front surface's clear aperture (weight: the ring's radius, for
//     the area), traced in; those that pass cross a plane z = −s at x_k = p_k + s q_k, and
//     the RMS radius Σ w_k x_k² / Σ w_k is least at s = −Σ w p q / Σ w q². With fewer
//     than 8 rays through it falls back to kParaxial.
#include <cmath>

#include <glm/geometric.hpp>

#include "integrator/camera/lens_system.h"
#include "integrator/camera/secant.h"

namespace camsim {

std::optional<LensRay> LensSystem::traceBack(const LensRay& ray, const Indices& n, int first,
                                             bool apertures) const {
  glm::dvec3 o = ray.origin, d = ray.direction;
  for (int i = surfaceCount() - 1; i >= first; --i) {
    const SurfaceShape& s = shapes_[static_cast<size_t>(i)];
    const std::optional<double> t = intersectSurface(s, o, d);
    if (!t) return std::nullopt;
    o += *t * d;
    if (i == lens_.stopIndex) {
      if (apertures && !insideStop(o.x, o.y)) return std::nullopt;
      continue;
    }
    if (apertures && o.x * o.x + o.y * o.y > s.clearRadius2) return std::nullopt;
    const double from = n.after[static_cast<size_t>(i)];
    const double to = i > 0 ? n.after[static_cast<size_t>(i - 1)] : 1.0;
    if (from != to && !refract(d, surfaceNormal(s, o), from, to)) return std::nullopt;
  }
  return LensRay{o, d};
}

std::optional<LensRay> LensSystem::traceFromFilm(const LensRay& ray, const Indices& n) const {
  return traceBack(ray, n, 0, true);
}

std::optional<LensRay> LensSystem::traceFromObject(const LensRay& ray, const Indices& n) const {
  glm::dvec3 o = ray.origin, d = ray.direction;
  for (int i = 0; i < surfaceCount(); ++i) {
    const SurfaceShape& s = shapes_[static_cast<size_t>(i)];
    const std::optional<double> t = intersectSurface(s, o, d);
    if (!t) return std::nullopt;
    o += *t * d;
    if (i == lens_.stopIndex) {
      if (!insideStop(o.x, o.y)) return std::nullopt;
      continue;
    }
    if (o.x * o.x + o.y * o.y > s.clearRadius2) return std::nullopt;
    const double from = i > 0 ? n.after[static_cast<size_t>(i - 1)] : 1.0;
    const double to = n.after[static_cast<size_t>(i)];
    if (from != to && !refract(d, surfaceNormal(s, o), from, to)) return std::nullopt;
  }
  return LensRay{o, d};
}

double LensSystem::focusSensorDistance(double objectDistance, double lambdaNm,
                                       FocusMethod method) const {
  const Indices n = indicesAt(lambdaNm);
  const Matrix m = matrix(0, surfaceCount() - 1, n);
  const bool infinite = std::isinf(objectDistance);
  const double paraxialS =
      infinite ? -m.a / m.c : -(m.a * objectDistance + m.b) / (m.c * objectDistance + m.d);
  if (method == FocusMethod::kParaxial) return paraxialS;

  constexpr int kRings = 256;
  const double front = frontVertexZ();
  const double frontRadius = std::sqrt(shapes_.front().clearRadius2);
  double swpq = 0.0, swqq = 0.0;
  int through = 0;
  for (int k = 0; k < kRings; ++k) {
    const double h = (k + 0.5) / kRings * frontRadius;
    LensRay ray;
    if (infinite) {  // start in front of any bulge of the front surface
      ray.origin = {h, 0.0, front + 2.0 * frontRadius};
      ray.direction = {0.0, 0.0, -1.0};
    } else {
      ray.origin = {0.0, 0.0, front + objectDistance};
      ray.direction = glm::normalize(glm::dvec3(h, 0.0, front) - ray.origin);
    }
    const std::optional<LensRay> out = traceFromObject(ray, n);
    if (!out || !(out->direction.z < 0.0)) continue;
    // x on the plane z = −s: o.x + (−s − o.z) d.x/d.z = p + s q.
    const double q = -out->direction.x / out->direction.z;
    const double p = out->origin.x - out->origin.z * out->direction.x / out->direction.z;
    swpq += h * p * q;
    swqq += h * q * q;
    ++through;
  }
  const double best = -swpq / swqq;
  if (through < 8 || !std::isfinite(best)) return paraxialS;
  return best;
}

std::optional<double> LensSystem::tracedFocalLength(double height, double lambdaNm) const {
  LensRay ray;
  ray.origin = {height, 0.0, frontVertexZ() + 2.0 * std::sqrt(shapes_.front().clearRadius2)};
  ray.direction = {0.0, 0.0, -1.0};
  const std::optional<LensRay> out = traceFromObject(ray, lambdaNm);
  if (!out || out->direction.x == 0.0 || !(out->direction.z < 0.0)) return std::nullopt;
  // The slope towards the image, dx/dz' with z' = −z; f = −h / slope.
  return -height / (out->direction.x / -out->direction.z);
}

std::optional<double> LensSystem::chiefRayAngle(double filmHeight, double sensorDistance,
                                                double lambdaNm) const {
  const Indices n = indicesAt(lambdaNm);
  const glm::dvec3 film(filmHeight, 0.0, -sensorDistance);
  // The ray from the film point through (x, 0, 0) crosses the stop's plane at height g(x);
  // the chief ray has g = 0, found by the secant method (no apertures while aiming).
  const auto stopHeight = [&](double x) -> std::optional<double> {
    const LensRay ray{film, glm::normalize(glm::dvec3(x, 0.0, 0.0) - film)};
    const std::optional<LensRay> atStop = traceBack(ray, n, lens_.stopIndex, false);
    if (!atStop) return std::nullopt;
    return atStop->origin.x;
  };
  const std::optional<double> x1 =
      secantRoot(stopHeight, 0.0, -0.1 * rearClearRadius() * (filmHeight >= 0.0 ? 1.0 : -1.0));
  if (!x1) return std::nullopt;
  const LensRay chief{film, glm::normalize(glm::dvec3(*x1, 0.0, 0.0) - film)};
  const std::optional<LensRay> out = traceBack(chief, n, 0, false);
  if (!out) return std::nullopt;
  return std::atan2(std::hypot(out->direction.x, out->direction.y), out->direction.z);
}

}  // namespace camsim
