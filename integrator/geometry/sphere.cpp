// Sphere (see sphere.h). Texture coordinates of a point with unit normal n (from the
// centre; docs/scene-format.md): u = φ/2π in [0, 1) with φ = atan2(n.x, n.z) about +y (from
// +z towards +x), v = 1 − θ/π with θ = acos(n.y) from +y (v = 1 at the top pole, 0 at the
// bottom). The axes are the world's (a sphere has no orientation of its own). Hits get
// them; light samples do not (no light reads them).
#include "integrator/geometry/sphere.h"

#include <algorithm>
#include <cmath>

#include "integrator/geometry/math.h"
#include "sensor/base/check.h"

namespace camsim {

Sphere::Sphere(std::vector<glm::vec3> centres, std::vector<float> radii, TimeSteps steps)
    : centres_(std::move(centres)), radii_(std::move(radii)), steps_(steps) {
  CAMSIM_CHECK(!centres_.empty() && centres_.size() == radii_.size() &&
               static_cast<int>(centres_.size()) == steps_.count);
  for (float r : radii_) CAMSIM_CHECK(r > 0.0f);
  if (steps_.count == 1) return;
  // Pose k maps the unit sphere to the sphere of step k.
  std::vector<glm::dmat4> poses;
  for (size_t k = 0; k < centres_.size(); ++k) {
    glm::dmat4 m(static_cast<double>(radii_[k]));
    m[3] = glm::dvec4(glm::dvec3(centres_[k]), 1.0);
    poses.push_back(m);
  }
  instance_ = InstanceMotion::fromPoses(poses);
}

Sphere::Pose Sphere::at(double time) const {
  int i;
  float f;
  steps_.locate(time, i, f);
  const size_t k = static_cast<size_t>(i);
  if (f == 0.0f) return {centres_[k], radii_[k]};
  return {glm::mix(centres_[k], centres_[k + 1], f), (1.0f - f) * radii_[k] + f * radii_[k + 1]};
}

float Sphere::area() const {
  return 4.0f * kPi * radii_[0] * radii_[0];
}

SurfaceInteraction Sphere::surfacePoint(const Pose& pose, const glm::vec3& direction,
                                        double time) const {
  SurfaceInteraction si;
  si.n = glm::normalize(direction);
  si.ns = si.n;
  si.p = pose.centre + pose.radius * si.n;
  si.pError = gammaBound(5) * (glm::abs(si.p) + glm::abs(pose.centre));
  if (!instance_.empty()) si.pError += instance_.error(si.p);
  si.time = time;
  return si;
}

// World up is +y: u = φ/2π about +y (φ from +z towards +x), v = 1 − θ/π (θ from +y), so an
// image's top row (v = 1) maps to the top pole and the picture is not mirrored when seen
// from a camera looking along +z.
glm::vec2 Sphere::uvOf(const glm::vec3& n) {
  float u = std::atan2(n.x, n.z) / (2.0f * kPi);
  if (u < 0.0f) u += 1.0f;
  return {u < 1.0f ? u : 0.0f, 1.0f - std::acos(std::clamp(n.y, -1.0f, 1.0f)) / kPi};
}

bool Sphere::inside(const Pose& pose, const glm::vec3& ref) {
  return lengthSquared(ref - pose.centre) <= pose.radius * pose.radius * (1.0f + 1e-4f);
}

SurfaceInteraction Sphere::interaction(const Hit& hit, const Ray& ray) const {
  const Pose pose = at(ray.time);
  SurfaceInteraction si = surfacePoint(pose, ray.at(hit.t) - pose.centre, ray.time);
  si.uv = uvOf(si.n);
  return si;
}

// n = (sinθ sinφ, cosθ, sinθ cosφ): ∂n/∂φ = (n.z, 0, −n.x); v = 1 − θ/π grows towards +y,
// along −∂n/∂θ ∝ (−n.x n.y, 1 − n.y², −n.y n.z) (both scaled by sinθ; only directions count).
std::optional<SurfaceTangents> Sphere::tangentFrame(const Hit& /*hit*/,
                                                    const SurfaceInteraction& si) const {
  const glm::vec3& n = si.n;
  return SurfaceTangents{{n.z, 0.0f, -n.x}, {-n.x * n.y, 1.0f - n.y * n.y, -n.y * n.z}};
}

std::optional<ShapeSample> Sphere::sample(const glm::vec3& ref, float /*u1*/, glm::vec2 u2,
                                          double time) const {
  const Pose pose = at(time);
  ShapeSample s;
  const bool insideSphere = inside(pose, ref);
  if (insideSphere) {
    const float z = 1.0f - 2.0f * u2.x;
    const float r = safeSqrt(1.0f - z * z);
    const float phi = 2.0f * kPi * u2.y;
    s.point = surfacePoint(pose, {r * std::cos(phi), r * std::sin(phi), z}, time);
    s.pdf = 1.0f / (4.0f * kPi * pose.radius * pose.radius);  // by area (m⁻²), for now
  } else {
    const glm::vec3 toCentre = pose.centre - ref;
    const float dc = glm::length(toCentre);
    const float sin2Max = pose.radius * pose.radius / (dc * dc);
    const float cosMax = safeSqrt(1.0f - sin2Max);
    const float oneMinusCosMax = sin2Max / (1.0f + cosMax);  // 1 − cosθmax without cancellation
    if (!(sin2Max > 0.0f)) return std::nullopt;              // subtends no solid angle in float
    // Uniform cone direction, then the point where it meets the sphere (nearest hit).
    // The point is placed from the centre, by the angle α at the centre between the
    // direction back to ref and the surface normal there: sin²θ = u sin²θmax (1 − cosθ
    // without cancellation), cos α = sin²θ/sinθmax + cosθ √(1 − sin²θ/sin²θmax). Placing it
    // from ref instead (ref + t w − c) cancels to nothing when the radius is below the
    // rounding of ref's coordinates (a 1e-7 m bulb 2 m away).
    const float oneMinusCosTheta = u2.x * oneMinusCosMax;
    const float cosTheta = 1.0f - oneMinusCosTheta;
    const float sin2Theta = oneMinusCosTheta * (1.0f + cosTheta);
    const float cosAlpha = sin2Theta / std::sqrt(sin2Max) +
                           cosTheta * safeSqrt(1.0f - std::min(1.0f, sin2Theta / sin2Max));
    const float sinAlpha = safeSqrt(1.0f - cosAlpha * cosAlpha);
    const float phi = 2.0f * kPi * u2.y;
    const Frame frame = Frame::fromZ(-toCentre / dc);  // z: from the centre towards ref
    const glm::vec3 n =
        frame.toWorld({sinAlpha * std::cos(phi), sinAlpha * std::sin(phi), cosAlpha});
    s.point = surfacePoint(pose, n, time);
    s.pdf = 1.0f / (2.0f * kPi * oneMinusCosMax);
  }
  const std::optional<Towards> t = towards(ref, s.point.p);
  if (!t) return std::nullopt;
  if (insideSphere) s.pdf = solidAnglePdf(s.pdf, *t, s.point.n);
  s.wi = t->wi;
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return std::nullopt;
  return s;
}

float Sphere::pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const {
  const Pose pose = at(onShape.time);
  if (inside(pose, ref))
    return areaToSolidAnglePdf(1.0f / (4.0f * kPi * pose.radius * pose.radius), ref, onShape);
  const float dc2 = lengthSquared(pose.centre - ref);
  const float sin2Max = pose.radius * pose.radius / dc2;
  const float cosMax = safeSqrt(1.0f - sin2Max);
  return 1.0f / (2.0f * kPi * (sin2Max / (1.0f + cosMax)));
}

}  // namespace camsim
