// Microfacet distributions and shadowing–masking, in the local shading frame (z = normal).
//
// | parameter    | unit          | default | meaning                                        |
// |--------------|---------------|---------|------------------------------------------------|
// | distribution | —             | ggx     | D: ggx (Trowbridge–Reitz) or beckmann          |
// | masking      | —             | smith   | G: smith (height-correlated) or v-groove       |
// | alpha_x/y    | dimensionless | —       | α, width of the slope distribution (≈ RMS slope·√2 for Beckmann); 0 = smooth |
//
//   GGX       D(m) = 1 / (π αx αy cos⁴θm (1 + tan²θm (cos²φ/αx² + sin²φ/αy²))²)
//             Λ(ω) = (−1 + √(1 + α(φ)² tan²θ)) / 2
//   Beckmann  D(m) = exp(−tan²θm (cos²φ/αx² + sin²φ/αy²)) / (π αx αy cos⁴θm)
//             Λ(ω) = (erfc(a) ... ) exact: (e^{−a²}/(a√π) − erfc(a)) / 2,  a = 1/(α(φ) tanθ)
//   Smith, height-correlated   G(ωo, ωi) = 1 / (1 + Λ(ωo) + Λ(ωi))
//   V-groove (Cook–Torrance)   G(ωo, ωi) = min(1, 2 cosθm cosθo / (ωo·m), 2 cosθm cosθi / (ωi·m))
//   Visible normals (Heitz 2018)   D_ω(m) = G1(ω) max(0, ω·m) D(m) / cosθ
//
// Sampling: visible normals, exactly, pdf(ω, m) = D_ω(m): GGX by Heitz 2018, Beckmann by
// inverting the CDF of its visible slopes (Heitz & d'Eon 2014). Every sampled normal faces
// ω, and with Smith masking a reflection's weight f cosθi / pdf = G(ωo, ωi)/G1(ωo) ≤ 1.
// Valid for either masking model (the pdf does not depend on G).
// A direction w below the surface (w.z < 0) is sampled as −w: the lobe seen from the other side.
//
// Reflection off the microfacets (conductor, plastic's specular lobe), Fresnel left out:
//   f = D(m) G(ωo, ωi, m) / (4 cosθo cosθi),   pdf(ωi) = pdf(ωo, m) / (4 ωo·m),   m = half vector
#pragma once

#include <cmath>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sensor/base/enum_names.h"

namespace camsim {

enum class MicrofacetDistribution { kGgx, kBeckmann };
enum class MaskingModel { kSmith, kVGroove };
// The scene's material `distribution` and `masking` names (sensor/base/enum_names.h).
template <>
struct EnumNames<MicrofacetDistribution> {
  static constexpr EnumName<MicrofacetDistribution> kTable[] = {
      {MicrofacetDistribution::kGgx, "ggx"}, {MicrofacetDistribution::kBeckmann, "beckmann"}};
};
template <>
struct EnumNames<MaskingModel> {
  static constexpr EnumName<MaskingModel> kTable[] = {{MaskingModel::kSmith, "smith"},
                                                      {MaskingModel::kVGroove, "v-groove"}};
};

class MicrofacetModel {
 public:
  MicrofacetModel(MicrofacetDistribution distribution, MaskingModel masking, float alphaX,
                  float alphaY);
  // From a roughness α (negative → 0) and an anisotropy a ∈ (−1, 1): αx = α (1 + a), αy = α (1 − a).
  static MicrofacetModel fromRoughness(MicrofacetDistribution distribution, MaskingModel masking,
                                       float alpha, float anisotropy);

  // Below this α the surface is treated as perfectly smooth (a delta lobe): D would
  // overflow single precision and no sampler could find the peak.
  static constexpr float kSmoothAlpha = 1e-4f;
  bool effectivelySmooth() const;

  float D(const glm::vec3& wm) const;
  float lambda(const glm::vec3& w) const;
  float G1(const glm::vec3& w) const;
  // Joint shadowing–masking of the selected model for the half-vector wm.
  float G(const glm::vec3& wo, const glm::vec3& wi, const glm::vec3& wm) const;
  // Draws a microfacet normal (in the +z hemisphere) for the direction w (either side:
  // w below the surface is taken as −w).
  glm::vec3 sampleWm(const glm::vec3& w, glm::vec2 u) const;
  // Density of sampleWm producing wm, sr⁻¹.
  float pdf(const glm::vec3& w, const glm::vec3& wm) const;

  // Reflection for wo, wi on the +z side and their half vector (or the sampled normal) wm:
  // f without Fresnel and the pdf of sampleReflection; both 0 if invalid or not finite.
  struct Reflection {
    float f = 0.0f;    // sr⁻¹
    float pdf = 0.0f;  // sr⁻¹
  };
  Reflection reflection(const glm::vec3& wo, const glm::vec3& wi, const glm::vec3& wm) const;
  // wo (z > 0) reflected about a sampled normal wm; nothing if wi falls below the surface.
  // Callers evaluate with this wm, not one rebuilt from wo + wi: at grazing wo and tiny α the
  // rebuilt half vector is off, in single precision, by more than the lobe is wide.
  struct ReflectionSample {
    glm::vec3 wi, wm;
  };
  std::optional<ReflectionSample> sampleReflection(const glm::vec3& wo, glm::vec2 u) const;

 private:
  MicrofacetDistribution distribution_;
  MaskingModel masking_;
  float alphaX_, alphaY_;
};

// The material is the same on both sides: a direction below the surface mirrored to +z.
inline glm::vec3 upperHemisphere(const glm::vec3& w) {
  return {w.x, w.y, std::abs(w.z)};
}
// Half vector of two directions on the +z side (their sum is never 0 there).
inline glm::vec3 halfVector(const glm::vec3& wo, const glm::vec3& wi) {
  return glm::normalize(wo + wi);
}

}  // namespace camsim
