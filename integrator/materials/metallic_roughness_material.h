// MetallicRoughnessMaterial: the glTF 2.0 metallic-roughness BRDF (glTF 2.0 specification,
// Appendix B), reflection only, two-sided.
//
// | parameter | unit          | default | meaning                                            |
// |-----------|---------------|---------|----------------------------------------------------|
// | baseColor | dimensionless | 0.5     | c(λ), may be a texture: the dielectric's diffuse   |
// |           |               |         | albedo and the metal's F0; clamped to [0, 1]       |
// | metallic  | dimensionless | 0       | m ∈ [0, 1], may be a texture (clamped)             |
// | roughness | dimensionless | 0       | perceptual r ∈ [0, 1], may be a texture (clamped); |
// |           |               |         | α = r²; α < 1e-4 (r < 0.01) is smooth              |
//
//   f = (1 − m) · dielectric_brdf + m · metal_brdf                          (same side only)
//   metal_brdf      = S · (c + (1 − c)(1 − |wo·h|)⁵)                        (Schlick, F0 = c)
//   dielectric_brdf = c/π · (1 − E(μo))(1 − E(μi)) / (1 − E_avg)  +  F_d · S
//                     F_d = 0.04 + 0.96 (1 − |wo·h|)⁵ (ior 1.5: F0 = ((1 − 1.5)/(1 + 1.5))²)
//   E(μ), E_avg: the specular layer's directional albedo and its cosine-weighted mean
//                     (dielectric_specular_albedo.h), μ = cos θ
//   S = D(h) G(wo, wi) / (4 |cos θo| |cos θi|)   the specular_brdf, h = normalize(wo + wi)
//   D: GGX (Trowbridge–Reitz) with α = r²; G: Smith height-correlated,
//      G = 1 / (1 + Λ(wo) + Λ(wi)) — the form the specification writes as V_GGX (its
//      "height-correlated" visibility), and microfacet.h's kSmith: masking and shadowing
//      are correlated through the microsurface's height, which the separable product
//      G1(wo) G1(wi) ignores (it over-darkens at grazing angles, Heitz 2014).
//   Where camsim departs from Appendix B: its fresnel_mix weighs the diffuse lobe by
//   1 − F_d(wo·h), which is not energy conserving (the specification says so, B.3.5): a
//   white dielectric reflected 1.535 at cos θo = 0.1, r = 0.1, and 1.84 at cos θo = 0.02,
//   r = 0.02. camsim dims the diffuse lobe by what the specular layer reflects, in the
//   reciprocal form of Kelly & Kulla (2017): the diffuse albedo is c (1 − E(μo)), so a white
//   dielectric reflects E + (1 − E) = 1 (up to the table's 9·10⁻⁴) and any c ≤ 1 at most 1.
//   The specular and metal lobes are the specification's. Single scattering: the rough
//   specular lobe loses the energy of multiple bounces between microfacets, as the spec's
//   model does (a rough white metal reflects less than 1). f is reciprocal.
//
// Sampling: the diffuse lobe (cosine-weighted) with probability pd, else the specular lobe
//   (GGX visible normals, microfacet.h sampleWm, reflected). pd weighs the lobes as they
//   are in wo's mirror direction (h = n): with s = (1 − cos θo)⁵, cmax the largest c over
//   the path's wavelengths,
//     w_diffuse = (1 − m)(1 − E(μo)) cmax,
//     w_specular = (1 − m) E(μo) + m (cmax + (1 − cmax) s),
//     pd = w_diffuse / (w_diffuse + w_specular)       (0 when both are 0)
//   pdf = pd |cos θi|/π + (1 − pd) pdf_spec(wo, wi)
// Smooth (α < kSmoothAlpha): the specular lobe is a delta mirror chosen with probability
//   1 − pd, weight (1 − m) F_d(cos θo) + m (c + (1 − c)(1 − cos θo)⁵), f = weight/|cos θi|;
//   f() and pdf() hold only the diffuse part; E = F_d exactly and E_avg = 0.04 + 0.96/21.
// wo below the surface is mirrored to +z (both sides alike).
//
// AOV: albedo = c (the dielectric's diffuse albedo and the metal's F0 alike), roughness = α.
#pragma once

#include <memory>

#include "integrator/materials/material.h"
#include "integrator/materials/microfacet.h"
#include "integrator/textures/texture.h"

namespace camsim {

struct MetallicRoughnessParameters {
  std::unique_ptr<SpectrumTexture> baseColor;
  std::unique_ptr<FloatTexture> metallic;
  std::unique_ptr<FloatTexture> roughness;  // perceptual r (α = r²)
};

class MetallicRoughnessMaterial final : public Material {
 public:
  explicit MetallicRoughnessMaterial(MetallicRoughnessParameters p);

  SampledSpectrum f(const glm::vec3& wo, const glm::vec3& wi, const SampledWavelengths& lambda,
                    const BsdfContext& ctx) const override;
  std::optional<BsdfSample> sample(const glm::vec3& wo, float uc, glm::vec2 u,
                                   const SampledWavelengths& lambda,
                                   const BsdfContext& ctx) const override;
  float pdf(const glm::vec3& wo, const glm::vec3& wi, const SampledWavelengths& lambda,
            const BsdfContext& ctx) const override;
  SurfaceAov aov(const SampledWavelengths& lambda, const BsdfContext& ctx) const override;

 private:
  struct Lobes {                // everything that depends on the surface point, λ and wo
    SampledSpectrum baseColor;  // c(λ), clamped to [0, 1]
    float metallic = 0.0f;      // m
    float pDiffuse = 0.0f;      // pd
    MicrofacetModel model;
    float roughness = 0.0f;     // r
    float albedoOut = 0.0f;     // E(cos θo, r)
    float diffuseScale = 0.0f;  // (1 − m)(1 − E(cos θo)) / (π (1 − E_avg))
  };
  // E(cos θ, r), exactly the Fresnel factor for a smooth surface.
  static float specularAlbedo(const Lobes& l, float cosTheta);
  struct Eval {
    SampledSpectrum f;
    float pdf = 0.0f;
  };
  Lobes lobes(const glm::vec3& wo, const SampledWavelengths& lambda, const BsdfContext& ctx) const;
  // f and pdf for wo, wi on the +z side with half vector (or sampled normal) wm.
  Eval evaluate(const Lobes& l, const glm::vec3& wo, const glm::vec3& wi,
                const glm::vec3& wm) const;
  float alpha(const BsdfContext& ctx) const;

  MetallicRoughnessParameters p_;
};

}  // namespace camsim
