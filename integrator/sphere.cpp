#include "integrator/sphere.h"

#include "integrator/math.h"
#include "sensor/check.h"

namespace camsim {

Sphere::Sphere(glm::vec3 centre, float radius) : centre_(centre), radius_(radius) {
  CAMSIM_CHECK(radius > 0.0f);
}

float Sphere::area() const { return 4.0f * kPi * radius_ * radius_; }

SurfaceInteraction Sphere::surfacePoint(const glm::vec3& direction) const {
  SurfaceInteraction si;
  si.n = glm::normalize(direction);
  si.ns = si.n;
  si.p = centre_ + radius_ * si.n;
  si.pError = gammaBound(5) * (glm::abs(si.p) + glm::abs(centre_));
  return si;
}

bool Sphere::inside(const glm::vec3& ref) const {
  return lengthSquared(ref - centre_) <= radius_ * radius_ * (1.0f + 1e-4f);
}

SurfaceInteraction Sphere::interaction(const Hit& hit, const Ray& ray) const {
  SurfaceInteraction si = surfacePoint(ray.at(hit.t) - centre_);
  si.time = ray.time;
  return si;
}

std::optional<ShapeSample> Sphere::sample(const glm::vec3& ref, float u1, glm::vec2 u2) const {
  (void)u1;
  ShapeSample s;
  if (inside(ref)) {
    const float z = 1.0f - 2.0f * u2.x;
    const float r = safeSqrt(1.0f - z * z);
    const float phi = 2.0f * kPi * u2.y;
    s.point = surfacePoint({r * std::cos(phi), r * std::sin(phi), z});
    s.pdf = areaToSolidAnglePdf(1.0f / area(), ref, s.point);
  } else {
    const glm::vec3 toCentre = centre_ - ref;
    const float dc = glm::length(toCentre);
    const float sin2Max = radius_ * radius_ / (dc * dc);
    const float cosMax = safeSqrt(1.0f - sin2Max);
    const float oneMinusCosMax = sin2Max / (1.0f + cosMax);  // 1 − cosθmax without cancellation
    // Uniform cone direction, then the point where it meets the sphere (nearest hit).
    const float cosTheta = 1.0f - u2.x * oneMinusCosMax;
    const float sinTheta = safeSqrt(1.0f - cosTheta * cosTheta);
    const float phi = 2.0f * kPi * u2.y;
    const Frame frame = Frame::fromZ(toCentre / dc);
    const glm::vec3 w = frame.toWorld({sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta});
    // |ref + t w − c|² = r²: t = dc cosθ − √(r² − dc² sin²θ)
    const float t = dc * cosTheta - safeSqrt(radius_ * radius_ - dc * dc * sinTheta * sinTheta);
    s.point = surfacePoint(ref + t * w - centre_);
    s.pdf = 1.0f / (2.0f * kPi * oneMinusCosMax);
  }
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return std::nullopt;
  return s;
}

float Sphere::pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const {
  if (inside(ref)) return areaToSolidAnglePdf(1.0f / area(), ref, onShape);
  const float dc2 = lengthSquared(centre_ - ref);
  const float sin2Max = radius_ * radius_ / dc2;
  const float cosMax = safeSqrt(1.0f - sin2Max);
  return 1.0f / (2.0f * kPi * (sin2Max / (1.0f + cosMax)));
}

}  // namespace camsim
