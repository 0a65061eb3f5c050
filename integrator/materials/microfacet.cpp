// Microfacet distributions, Smith and V-groove shadowing–masking, normal sampling.
//
// | parameter    | unit          | default | meaning                                        |
// |--------------|---------------|---------|------------------------------------------------|
// | distribution | —             | ggx     | ggx (Trowbridge–Reitz) or beckmann             |
// | masking      | —             | smith   | smith (height-correlated) or v-groove          |
// | alpha_x/y    | dimensionless | —       | slope widths; clamped below at kMinAlpha       |
//
// Everything is written with the components of unit vectors instead of θ and φ, which
// keeps it finite at cos θ → 0 and at the pole (no tan θ, no division by sin θ):
//   GGX       D(m) = 1 / (π αx αy (mx²/αx² + my²/αy² + mz²)²)          (mz > 0, else 0)
//             α(φ)² tan²θ = (αx² wx² + αy² wy²) / wz²,   Λ = t / (2 (1 + √(1 + t))),  t = α(φ)²
//             tan²θ G1/|cos θ| = 2 / (|wz| + √(wz² + αx² wx² + αy² wy²))     (finite at wz = 0)
//   Beckmann  D(m) = exp(−(mx²/αx² + my²/αy²)/mz²) / (π αx αy mz⁴)
//             Λ = (e^{−a²}/(a√π) − erfc(a)) / 2,  a = |wz| / √(αx² wx² + αy² wy²)  (double)
//   Sampling  visible normals, pdf = G1(w) max(0, w·m) D(m) / |cos θ|, both distributions:
//             GGX by Heitz 2018 (the projected hemisphere of the stretched configuration);
//             Beckmann by its visible slopes (Heitz & d'Eon 2014): stretched to α = 1 and
//             seen at incidence θ, the slope x̃ along the azimuth of w has the CDF
//               F(x̃) = (1 + erf x̃ + tanθ e^{−x̃²}/√π) / N,  N = 1 + erf(cotθ) + tanθ e^{−cot²θ}/√π
//             on x̃ ≤ cotθ (the facets w can see), and ỹ across it is Gaussian (σ² = ½).
//             Beckmann's G1/|cos θ| = 1/(|cos θ| (1 + Λ)), Λ as above
#include "integrator/materials/microfacet.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "integrator/geometry/math.h"
#include "integrator/materials/fresnel.h"

namespace camsim {
namespace {

// Smallest α used in evaluation: D ≤ 1/(π kMinAlpha²) ≈ 3e11 still fits in a float.
constexpr float kMinAlpha = 1e-6f;
constexpr double kSqrtPi = 1.77245385090551602730;

// sampleWm and pdf for w below the surface: the lobe seen from the other side.
glm::vec3 facingUp(const glm::vec3& w) {
  return w.z < 0.0f ? -w : w;
}

// Beckmann's visible slopes (x̃ along the azimuth of w, ỹ across it) in the configuration
// stretched to α = 1, seen at incidence θ (cosθ = wz ≥ 0, sinθ ≥ 0; see the header). F is
// inverted for b = erf x̃ by Newton steps (dF/db = (1 − x̃ tanθ)/N) kept inside a bracket
// that shrinks with each step; the first guess is exact at normal incidence.
glm::vec2 sampleBeckmannSlopes(float cosTheta, float sinTheta, glm::vec2 u) {
  const float u0 = std::clamp(u.x, 1e-6f, 1.0f - 1e-6f);
  const float y = erfInv(2.0f * std::clamp(u.y, 1e-6f, 1.0f - 1e-6f) - 1.0f);
  if (sinTheta < 1e-6f) return {erfInv(2.0f * u0 - 1.0f), y};
  cosTheta = std::max(cosTheta, 1e-6f);
  const float tanTheta = sinTheta / cosTheta, cotTheta = cosTheta / sinTheta;
  const float k = tanTheta * static_cast<float>(1.0 / kSqrtPi);
  const float c = std::erf(cotTheta);
  const float norm = 1.0f + c + k * std::exp(-cotTheta * cotTheta);
  float lo = -1.0f, hi = c;
  float b = u0 * (1.0f + c) - 1.0f;
  float x = erfInv(b);
  for (int i = 0; i < 24; ++i) {
    const float value = (1.0f + b + k * std::exp(-x * x)) / norm - u0;
    if (std::abs(value) < 1e-6f) break;
    (value > 0.0f ? hi : lo) = b;
    const float next = b - value * norm / (1.0f - x * tanTheta);
    b = next > lo && next < hi ? next : 0.5f * (lo + hi);
    x = erfInv(b);
  }
  return {std::min(x, cotTheta), y};
}

}  // namespace

MicrofacetModel::MicrofacetModel(MicrofacetDistribution distribution, MaskingModel masking,
                                 float alphaX, float alphaY)
    : distribution_(distribution),
      masking_(masking),
      alphaX_(std::max(alphaX, kMinAlpha)),
      alphaY_(std::max(alphaY, kMinAlpha)) {}

MicrofacetModel MicrofacetModel::fromRoughness(MicrofacetDistribution distribution,
                                               MaskingModel masking, float alpha,
                                               float anisotropy) {
  alpha = std::max(0.0f, alpha);
  return MicrofacetModel(distribution, masking, alpha * (1.0f + anisotropy),
                         alpha * (1.0f - anisotropy));
}

bool MicrofacetModel::effectivelySmooth() const {
  return std::max(alphaX_, alphaY_) < kSmoothAlpha;
}

float MicrofacetModel::D(const glm::vec3& wm) const {
  if (!(wm.z > 0.0f)) return 0.0f;
  const double ax = static_cast<double>(alphaX_), ay = static_cast<double>(alphaY_);
  const double x = static_cast<double>(wm.x), y = static_cast<double>(wm.y),
               z = static_cast<double>(wm.z);
  const double slope2 = x * x / (ax * ax) + y * y / (ay * ay);  // tan²θ·(…)·cos²θ
  if (distribution_ == MicrofacetDistribution::kGgx) {
    const double d = slope2 + z * z;
    return static_cast<float>(1.0 / (M_PI * ax * ay * d * d));
  }
  const double e = slope2 / (z * z);
  if (e > 700.0) return 0.0f;  // exp underflows (and z⁴ may be 0)
  return static_cast<float>(std::exp(-e) / (M_PI * ax * ay * z * z * z * z));
}

float MicrofacetModel::lambda(const glm::vec3& w) const {
  const double z = std::abs(static_cast<double>(w.z));
  const double x = static_cast<double>(w.x), y = static_cast<double>(w.y);
  const double ax = static_cast<double>(alphaX_), ay = static_cast<double>(alphaY_);
  const double a2s2 = ax * ax * x * x + ay * ay * y * y;  // α(φ)² sin²θ
  if (a2s2 == 0.0) return 0.0f;                           // at the pole: nothing is masked
  if (z == 0.0) return std::numeric_limits<float>::infinity();
  if (distribution_ == MicrofacetDistribution::kGgx) {
    const double t = a2s2 / (z * z);
    if (!std::isfinite(t)) return std::numeric_limits<float>::infinity();
    return static_cast<float>(t / (2.0 * (1.0 + std::sqrt(1.0 + t))));
  }
  const double a = z / std::sqrt(a2s2);
  if (a > 26.0) return 0.0f;  // e^{−a²} underflows; Λ < 1e-296
  return static_cast<float>(0.5 * (std::exp(-a * a) / (a * kSqrtPi) - std::erfc(a)));
}

float MicrofacetModel::G1(const glm::vec3& w) const {
  return 1.0f / (1.0f + lambda(w));
}

float MicrofacetModel::G(const glm::vec3& wo, const glm::vec3& wi, const glm::vec3& wm) const {
  if (masking_ == MaskingModel::kSmith) return 1.0f / (1.0f + lambda(wo) + lambda(wi));
  // V-groove: min(1, 2 |cos θm| |cos θ| / |w·m|) for each direction.
  const auto term = [&](const glm::vec3& w) {
    const float wDotM = std::abs(glm::dot(w, wm));
    if (wDotM <= 0.0f) return 1.0f;
    return std::min(1.0f, 2.0f * std::abs(wm.z) * std::abs(w.z) / wDotM);
  };
  return std::min(term(wo), term(wi));
}

glm::vec3 MicrofacetModel::sampleWm(const glm::vec3& wIn, glm::vec2 u) const {
  const glm::vec3 w = facingUp(wIn);
  const float u0 = std::min(u.x, 1.0f - 0x1p-24f), u1 = u.y;
  // Stretch w to the configuration of α = 1, sample there, unstretch.
  const glm::vec3 wh = glm::normalize(glm::vec3(alphaX_ * w.x, alphaY_ * w.y, w.z));
  const float len2 = wh.x * wh.x + wh.y * wh.y;
  if (distribution_ == MicrofacetDistribution::kBeckmann) {
    const float sinTheta = std::sqrt(len2);
    const glm::vec2 slope = sampleBeckmannSlopes(wh.z, sinTheta, {u0, u1});
    // Rotate from w's azimuth (cos φ, sin φ) = (wh.x, wh.y)/sinθ back to x, y.
    const float cosPhi = sinTheta > 0.0f ? wh.x / sinTheta : 1.0f;
    const float sinPhi = sinTheta > 0.0f ? wh.y / sinTheta : 0.0f;
    const float sx = alphaX_ * (cosPhi * slope.x - sinPhi * slope.y);
    const float sy = alphaY_ * (sinPhi * slope.x + cosPhi * slope.y);
    return glm::normalize(glm::vec3(-sx, -sy, 1.0f));
  }
  // GGX: sample the projected disk of the hemisphere seen from wh.
  const glm::vec3 t1 =
      len2 > 0.0f ? glm::vec3(-wh.y, wh.x, 0.0f) / std::sqrt(len2) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 t2 = glm::cross(wh, t1);
  const float r = std::sqrt(u0), phi = 2.0f * kPi * u1;
  const float p1 = r * std::cos(phi);
  float p2 = r * std::sin(phi);
  const float s = 0.5f * (1.0f + wh.z);
  p2 = (1.0f - s) * safeSqrt(1.0f - p1 * p1) + s * p2;
  const glm::vec3 nh = p1 * t1 + p2 * t2 + safeSqrt(1.0f - p1 * p1 - p2 * p2) * wh;
  return glm::normalize(glm::vec3(alphaX_ * nh.x, alphaY_ * nh.y, std::max(1e-6f, nh.z)));
}

float MicrofacetModel::pdf(const glm::vec3& wIn, const glm::vec3& wm) const {
  const float d = D(wm);
  if (d == 0.0f) return 0.0f;
  const glm::vec3 w = facingUp(wIn);
  const float wDotM = glm::dot(w, wm);
  if (!(wDotM > 0.0f)) return 0.0f;
  // G1(w)/cos θ; GGX's written without the division by cos θ (finite at grazing w).
  const float g1OverCos = distribution_ == MicrofacetDistribution::kGgx
                              ? 2.0f / (w.z + std::sqrt(w.z * w.z + alphaX_ * alphaX_ * w.x * w.x +
                                                        alphaY_ * alphaY_ * w.y * w.y))
                              : 1.0f / (w.z * (1.0f + lambda(w)));
  if (!std::isfinite(g1OverCos)) return 0.0f;
  return g1OverCos * wDotM * d;
}

MicrofacetModel::Reflection MicrofacetModel::reflection(const glm::vec3& wo, const glm::vec3& wi,
                                                        const glm::vec3& wm) const {
  const float woDotWm = glm::dot(wo, wm);
  if (!(woDotWm > 0.0f) || !(wm.z > 0.0f)) return {};
  const float d = D(wm);
  if (d == 0.0f) return {};
  // Λ(wo) once, for Smith's G and for the visible-normal pdf: pdf(wo, wm)/(4 wo·wm) =
  // G1(wo) (wo·wm) D / (cos θo · 4 wo·wm) = D / (4 cos θo (1 + Λ(wo))).
  const float lambdaO = lambda(wo);
  const float g =
      masking_ == MaskingModel::kSmith ? 1.0f / (1.0f + lambdaO + lambda(wi)) : G(wo, wi, wm);
  const float f = d * g / (4.0f * wo.z * wi.z);
  const float p = d / (4.0f * wo.z * (1.0f + lambdaO));
  if (!std::isfinite(f) || !std::isfinite(p)) return {};
  return {f, p};
}

std::optional<MicrofacetModel::ReflectionSample> MicrofacetModel::sampleReflection(
    const glm::vec3& wo, glm::vec2 u) const {
  const glm::vec3 wm = sampleWm(wo, u);
  const glm::vec3 wi = glm::normalize(reflect(wo, wm));
  if (!(wi.z > 0.0f)) return std::nullopt;
  return ReflectionSample{wi, wm};
}

}  // namespace camsim
