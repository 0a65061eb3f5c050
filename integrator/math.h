// Small geometric helpers shared by the integrator: frames, sampling warps, and the
// floating-point error bounds used to offset ray origins (pbrt-v4, §6.8):
//   γ(n) = n·ε / (1 − n·ε),  ε = 2⁻²⁴ (float unit roundoff).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace camsim {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;

inline constexpr float gammaBound(int n) {
  constexpr float eps = std::numeric_limits<float>::epsilon() * 0.5f;
  return (static_cast<float>(n) * eps) / (1.0f - static_cast<float>(n) * eps);
}

inline float nextFloatUp(float v) {
  if (std::isinf(v) && v > 0.0f) return v;
  if (v == -0.0f) v = 0.0f;
  std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
  bits = v >= 0.0f ? bits + 1 : bits - 1;
  return std::bit_cast<float>(bits);
}

inline float nextFloatDown(float v) {
  if (std::isinf(v) && v < 0.0f) return v;
  if (v == 0.0f) v = -0.0f;
  std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
  bits = v > 0.0f ? bits - 1 : bits + 1;
  return std::bit_cast<float>(bits);
}

// |v| per component. glm::abs is written as x >= 0 ? x : −x, which GCC compiles to a
// branch per component; std::abs on a float is one mask.
inline glm::vec3 absComponents(const glm::vec3& v) { return {std::abs(v.x), std::abs(v.y), std::abs(v.z)}; }

// Moves p off its surface (normal n, absolute error bound pError) to the side of w, far
// enough that a ray leaving from it cannot re-hit the surface it started on.
inline glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& pError, const glm::vec3& n,
                                 const glm::vec3& w) {
  const float d = glm::dot(absComponents(n), pError);
  glm::vec3 offset = d * n;
  if (glm::dot(w, n) < 0.0f) offset = -offset;
  glm::vec3 po = p + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0.0f) po[i] = nextFloatUp(po[i]);
    else if (offset[i] < 0.0f) po[i] = nextFloatDown(po[i]);
  }
  return po;
}

// Orthonormal basis around a unit vector (Duff et al. 2017).
struct Frame {
  glm::vec3 s, t, n;

  static Frame fromZ(const glm::vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
  }
  glm::vec3 toLocal(const glm::vec3& v) const { return {glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)}; }
  glm::vec3 toWorld(const glm::vec3& v) const { return v.x * s + v.y * t + v.z * n; }
};

inline float safeSqrt(float x) { return std::sqrt(std::max(0.0f, x)); }

inline float lengthSquared(const glm::vec3& v) { return glm::dot(v, v); }

// Concentric map of the unit square to the unit disk (Shirley & Chiu).
inline glm::vec2 sampleUniformDiskConcentric(glm::vec2 u) {
  const glm::vec2 o = 2.0f * u - 1.0f;
  if (o.x == 0.0f && o.y == 0.0f) return {0.0f, 0.0f};
  float r, theta;
  if (std::abs(o.x) > std::abs(o.y)) {
    r = o.x;
    theta = (kPi / 4.0f) * (o.y / o.x);
  } else {
    r = o.y;
    theta = kPi / 2.0f - (kPi / 4.0f) * (o.x / o.y);
  }
  return r * glm::vec2(std::cos(theta), std::sin(theta));
}

// Cosine-weighted direction on the +z hemisphere; pdf = cosθ/π.
inline glm::vec3 sampleCosineHemisphere(glm::vec2 u) {
  const glm::vec2 d = sampleUniformDiskConcentric(u);
  return {d.x, d.y, safeSqrt(1.0f - d.x * d.x - d.y * d.y)};
}

// Uniform barycentrics on a triangle (b0, b1); b2 = 1 − b0 − b1.
inline glm::vec2 sampleUniformTriangle(glm::vec2 u) {
  const float su = std::sqrt(u.x);
  return {1.0f - su, u.y * su};
}

inline float powerHeuristic(float fPdf, float gPdf) {
  const float f = fPdf * fPdf, g = gPdf * gPdf;
  if (std::isinf(f)) return 1.0f;
  return f + g > 0.0f ? f / (f + g) : 0.0f;
}

}  // namespace camsim
