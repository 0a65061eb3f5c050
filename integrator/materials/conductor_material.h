// ConductorMaterial: rough (or smooth) metal, microfacet reflection only, two-sided.
//
// | parameter    | unit          | default | meaning                                        |
// |--------------|---------------|---------|------------------------------------------------|
// | roughness    | dimensionless | 0       | α, may be a texture; α < 1e-4 is a smooth mirror |
// | anisotropy   | dimensionless | 0       | a ∈ (−1, 1): αx = α (1 + a), αy = α (1 − a)     |
// | distribution | —             | ggx     | ggx or beckmann (microfacet.h)                 |
// | masking      | —             | smith   | smith (height-correlated) or v-groove          |
// | fresnel      | —             | exact   | exact (η, k) or schlick (R0)                   |
// | eta, k       | dimensionless | 1.5, 0  | complex index η(λ) + i k(λ) (exact Fresnel)    |
// | reflectance  | dimensionless | 0.5     | R0(λ), normal-incidence reflectance (Schlick)  |
//
//   f(wo, wi) = D(wm) G(wo, wi, wm) F(|wo·wm|) / (4 |cos θo| |cos θi|),  wm = (wo + wi)/|wo + wi|
//   only when wo and wi are on the same side; wo.z < 0 is mirrored to +z (both sides alike)
//   sampling: wm ~ MicrofacetModel::sampleWm(wo), wi = reflect(wo, wm),
//             pdf = pdf(wo, wm) / (4 |wo·wm|)
//   smooth (max(αx, αy) < kSmoothAlpha): delta mirror, weight F(|cos θo|), f = F/|cos θi|, pdf 1
#pragma once

#include <memory>

#include "integrator/materials/fresnel.h"
#include "integrator/materials/material.h"
#include "integrator/materials/microfacet.h"
#include "integrator/textures/texture.h"

namespace camsim {

struct ConductorParameters {
  std::unique_ptr<FloatTexture> roughness;
  float anisotropy = 0.0f;
  MicrofacetDistribution distribution = MicrofacetDistribution::kGgx;
  MaskingModel masking = MaskingModel::kSmith;
  FresnelModel fresnel = FresnelModel::kExact;
  Spectrum eta = Spectrum::constant(1.5);
  Spectrum k = Spectrum::constant(0.0);
  std::unique_ptr<SpectrumTexture> r0;  // Schlick only; may be null for exact Fresnel
};

class ConductorMaterial final : public Material {
 public:
  explicit ConductorMaterial(ConductorParameters p);

  SampledSpectrum f(const glm::vec3& wo, const glm::vec3& wi, const SampledWavelengths& lambda,
                    const BsdfContext& ctx) const override;
  std::optional<BsdfSample> sample(const glm::vec3& wo, float uc, glm::vec2 u,
                                   const SampledWavelengths& lambda,
                                   const BsdfContext& ctx) const override;
  float pdf(const glm::vec3& wo, const glm::vec3& wi, const SampledWavelengths& lambda,
            const BsdfContext& ctx) const override;
  SurfaceAov aov(const SampledWavelengths& lambda, const BsdfContext& ctx) const override;

 private:
  MicrofacetModel model(const BsdfContext& ctx) const;
  SampledSpectrum fresnel(float cosTheta, const SampledWavelengths& lambda,
                          const BsdfContext& ctx) const;

  ConductorParameters p_;
};

}  // namespace camsim
