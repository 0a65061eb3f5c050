// Small geometric helpers shared by the integrator: frames, sampling warps, and the
// floating-point error bounds used to offset ray origins (pbrt-v4, §6.8):
//   γ(n) = n·ε / (1 − n·ε),  ε = 2⁻²⁴ (float unit roundoff).
#pragma once

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sensor/base/float_math.h"

namespace camsim {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;

inline constexpr float gammaBound(int n) {
  constexpr float eps = std::numeric_limits<float>::epsilon() * 0.5f;
  return (static_cast<float>(n) * eps) / (1.0f - static_cast<float>(n) * eps);
}

// |v| per component. glm::abs is written as x >= 0 ? x : −x, which GCC compiles to a
// branch per component; std::abs on a float is one mask.
inline glm::vec3 absComponents(const glm::vec3& v) {
  return {std::abs(v.x), std::abs(v.y), std::abs(v.z)};
}

// Moves p off its surface (normal n, absolute error bound pError) to the side of w, far
// enough that a ray leaving from it cannot re-hit the surface it started on: along n by
// the error box's extent d = |n|·pError plus a margin for the rounding of p + offset. Each
// coordinate of the sum rounds by at most 2⁻²⁴ of its magnitude, which moves the point
// along the unit n by at most √3·2⁻²⁴·max|pᵢ + offsetᵢ|; the margin, 2⁻²¹·(max|pᵢ| + d),
// is more than twice that. (pbrt-v4, §6.8.6, instead steps each coordinate one ulp away
// from p: three times the instructions for three origins per bounce.)
inline glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& pError, const glm::vec3& n,
                                 const glm::vec3& w) {
  const glm::vec3 a = absComponents(p);
  float d = glm::dot(absComponents(n), pError);
  d += (std::max(std::max(a.x, a.y), a.z) + d) * 0x1p-21f;
  return p + (glm::dot(w, n) < 0.0f ? -d : d) * n;
}

// Orthonormal basis around a unit vector (Duff et al. 2017).
struct Frame {
  glm::vec3 s, t, n;

  static Frame fromZ(const glm::vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {
        {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
  }
  glm::vec3 toLocal(const glm::vec3& v) const {
    return {glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)};
  }
  glm::vec3 toWorld(const glm::vec3& v) const { return v.x * s + v.y * t + v.z * n; }
};

inline float safeSqrt(float x) {
  return std::sqrt(std::max(0.0f, x));
}

inline float lengthSquared(const glm::vec3& v) {
  return glm::dot(v, v);
}

// Concentric map of the unit square to the unit disk (Shirley & Chiu). *radius, if given,
// gets the point's distance from the centre, max(|2u − 1|), known before the sine and
// cosine are.
inline glm::vec2 sampleUniformDiskConcentric(glm::vec2 u, float* radius = nullptr) {
  const glm::vec2 o = 2.0f * u - 1.0f;
  if (radius) *radius = std::max(std::abs(o.x), std::abs(o.y));
  if (o.x == 0.0f && o.y == 0.0f) return {0.0f, 0.0f};
  // Selects rather than an if/else: which wedge a random point falls in is a coin toss.
  const bool xMajor = std::abs(o.x) > std::abs(o.y);
  const float r = xMajor ? o.x : o.y;
  const float ratio = (xMajor ? o.y : o.x) / r;
  // θ = (π/4)·ratio (x major) or π/2 − (π/4)·ratio (y major): sin and cos of (π/4)·ratio,
  // swapped for the y-major wedges.
  const SinCos sc = sinCosQuarterPi((kPi / 4.0f) * ratio);
  return r * (xMajor ? glm::vec2(sc.cos, sc.sin) : glm::vec2(sc.sin, sc.cos));
}

// Cosine-weighted direction on the +z hemisphere; pdf = cosθ/π. z = √(1 − r²) from the disk
// radius rather than from the point (equal up to rounding), so that it is computed
// alongside the sine and cosine instead of after them.
inline glm::vec3 sampleCosineHemisphere(glm::vec2 u) {
  float r;
  const glm::vec2 d = sampleUniformDiskConcentric(u, &r);
  return {d.x, d.y, safeSqrt(1.0f - r * r)};
}

// Uniform barycentrics on a triangle (b0, b1); b2 = 1 − b0 − b1.
inline glm::vec2 sampleUniformTriangle(glm::vec2 u) {
  const float su = std::sqrt(u.x);
  return {1.0f - su, u.y * su};
}

// erf⁻¹(x) for x in (−1, 1), ±∞ at ±1: M. Giles, "Approximating the erfinv function" (GPU Computing
// Gems, 2011), single-precision polynomials in w = −ln(1 − x²); relative error ≈ 1e-7 (the
// tests check erf(erfInv(x)) = x).
inline float erfInv(float x) {
  if (std::abs(x) >= 1.0f) return std::copysign(std::numeric_limits<float>::infinity(), x);
  float w = -std::log((1.0f - x) * (1.0f + x));
  float p;
  if (w < 5.0f) {
    w -= 2.5f;
    p = 2.81022636e-08f;
    p = 3.43273939e-07f + p * w;
    p = -3.5233877e-06f + p * w;
    p = -4.39150654e-06f + p * w;
    p = 0.00021858087f + p * w;
    p = -0.00125372503f + p * w;
    p = -0.00417768164f + p * w;
    p = 0.246640727f + p * w;
    p = 1.50140941f + p * w;
  } else {
    w = std::sqrt(w) - 3.0f;
    p = -0.000200214257f;
    p = 0.000100950558f + p * w;
    p = 0.00134934322f + p * w;
    p = -0.00367342844f + p * w;
    p = 0.00573950773f + p * w;
    p = -0.0076224613f + p * w;
    p = 0.00943887047f + p * w;
    p = 1.00167406f + p * w;
    p = 2.83297682f + p * w;
  }
  return p * x;
}

inline float powerHeuristic(float fPdf, float gPdf) {
  const float f = fPdf * fPdf, g = gPdf * gPdf;
  if (std::isinf(f)) return 1.0f;
  return f + g > 0.0f ? f / (f + g) : 0.0f;
}

}  // namespace camsim
