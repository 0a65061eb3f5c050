// DielectricMaterial: glass, an interface between the outside (+z, index 1) and the inside
// (−z, index η), smooth or rough, reflecting and refracting.
//
// | parameter    | unit          | default | meaning                                       |
// |--------------|---------------|---------|-----------------------------------------------|
// | eta          | dimensionless | 1.5     | η(λ) = index inside / outside, > 0 (spectrum) |
// | roughness    | dimensionless | 0       | microfacet α ≥ 0 (texture); < kSmoothAlpha:   |
// |              |               |         | smooth                                        |
// | anisotropy   | dimensionless | 0       | a in (−1, 1): αx = α (1 + a), αy = α (1 − a)  |
// | distribution | —             | ggx     | microfacet D: ggx or beckmann (microfacet.h)  |
// | masking      | —             | smith   | shadowing–masking G: smith or v-groove        |
//
// Notation: cosθ = ω·z; η' = the relative index actually crossed from wo's side to the
// other side: η' = η when wo is outside, 1/η when wo is inside. F(cos, η) is the exact
// unpolarised Fresnel reflectance (fresnel.h; negative cos = from the inside).
//
// Smooth (α < kSmoothAlpha, or η = 1: an index-matched interface only transmits), two
// delta lobes chosen with the Fresnel probabilities R = F(cosθo, η), T = 1 − R:
//   reflection  wi = (−wo.x, −wo.y, wo.z),       f = R / |cosθi|,       pdf = R
//   refraction  η' sinθi = sinθo (Snell),          f = T / (|cosθi| η'²), pdf = T
//   so f |cosθi| / pdf = 1 (reflection) and 1/η'² (refraction: radiance L/n² is invariant).
//   Beyond the critical angle (from the inside) R = 1: total internal reflection.
//
// Rough (Walter et al. 2007), generalised half vector with η' the index of wi's side over
// wo's side (η' = 1 for reflection):
//   wm = ±normalize(η' wi + wo), oriented to +z; facets seen from behind by wo or wi give 0.
//   reflection    f = D(wm) G(wo, wi) F / (4 |cosθi cosθo|)
//   transmission  f = D(wm) G(wo, wi) (1 − F) |wi·wm| |wo·wm|
//                     / (|cosθi cosθo| (wi·wm + wo·wm/η')² η'²)
//   with F = F(wo·wm, η); in the BTDF, 1 − F is the two-sided transmittance
//   T = 2 η' c1 c2 (1/(η' c1 + c2)² + 1/(c1 + η' c2)²), c1 = |wo·wm|, c2 = |wi·wm| (equal to
//   1 − F in exact arithmetic, but accurate near the critical angle). The transmission f obeys the
//   generalised reciprocity f(wo, wi) / η_o² = f(wi, wo) / η_i²  (η_o, η_i the indices of wo's and
//   wi's sides).
// Sampling: wm ~ MicrofacetModel::sampleWm(wo, u), which from the inside samples the visible
// normals of −wo (the facets seen from below); reflection with probability F(wo·wm),
// else refraction through wm; the density of wi is the density of wm times the Jacobian
//   reflection    dwm/dwi = 1 / (4 |wo·wm|)
//   transmission  dwm/dwi = |wi·wm| / (wi·wm + wo·wm/η')²
//   pdf(wo, wi) = pdf_m(wo, wm) · dwm/dwi · (F or 1 − F).
// Samples that leave the sampled lobe's hemisphere (or hit a back-facing facet) are
// rejected, so the pdf integrates to the probability that sample() succeeds (≤ 1).
//
// Total internal reflection: F(wo·wm, η) = 1 beyond the critical angle of the facet, so
// the refraction branch is never chosen there; the smooth case reflects with pdf 1.
// Grazing and extreme roughness: every quotient is checked; a non-finite f or pdf gives
// 0 (f, pdf) or no sample, never NaN. hasNonSpecular() is false only when the roughness
// is a constant below kSmoothAlpha or η is the constant 1 (then light sampling is skipped).
//
// Dispersion: when η(λ) is not constant, dispersive() is true; the integrator then
// terminates the secondary wavelengths and η is evaluated at the hero wavelength lambda[0]
// only (it is always evaluated there).
#pragma once

#include <memory>

#include "integrator/materials/material.h"
#include "integrator/materials/microfacet.h"
#include "integrator/textures/texture.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

class DielectricMaterial final : public Material {
 public:
  DielectricMaterial(Spectrum eta, std::unique_ptr<FloatTexture> roughness, float anisotropy = 0.0f,
                     MicrofacetDistribution distribution = MicrofacetDistribution::kGgx,
                     MaskingModel masking = MaskingModel::kSmith);
  // Constant roughness α (0 = smooth glass).
  DielectricMaterial(Spectrum eta, float roughness, float anisotropy = 0.0f,
                     MicrofacetDistribution distribution = MicrofacetDistribution::kGgx,
                     MaskingModel masking = MaskingModel::kSmith);

  SampledSpectrum f(const glm::vec3& wo, const glm::vec3& wi, const SampledWavelengths& lambda,
                    const BsdfContext& ctx) const override;
  std::optional<BsdfSample> sample(const glm::vec3& wo, float uc, glm::vec2 u,
                                   const SampledWavelengths& lambda,
                                   const BsdfContext& ctx) const override;
  float pdf(const glm::vec3& wo, const glm::vec3& wi, const SampledWavelengths& lambda,
            const BsdfContext& ctx) const override;
  SurfaceAov aov(const SampledWavelengths& lambda, const BsdfContext& ctx) const override;

  // η at the hero wavelength lambda[0].
  float etaAt(const SampledWavelengths& lambda) const { return eta_(lambda[0]); }

 private:
  MicrofacetModel microfacet(const BsdfContext& ctx) const;
  // True when the interface at ctx is a pair of delta lobes.
  bool smooth(const MicrofacetModel& m, float eta) const {
    return eta == 1.0f || m.effectivelySmooth();
  }
  std::optional<BsdfSample> sampleSmooth(const glm::vec3& wo, float uc, float eta) const;
  std::optional<BsdfSample> sampleRough(const glm::vec3& wo, float uc, glm::vec2 u, float eta,
                                        const MicrofacetModel& m) const;

  Spectrum eta_;
  std::unique_ptr<FloatTexture> roughness_;
  float anisotropy_;
  MicrofacetDistribution distribution_;
  MaskingModel masking_;
};

}  // namespace camsim
