// DiffuseMaterial: Lambertian reflection, the same on both sides of the surface.
//
// | parameter   | unit          | default |
// |-------------|---------------|---------|
// | reflectance | dimensionless | 0.5     |  ρ(λ) in [0, 1], may be a texture
//
//   f = ρ(λ)/π  when wo and wi are on the same side, else 0
//   sampling: cosine-weighted on wo's side, pdf = |cos θi| / π
#pragma once

#include <memory>

#include "integrator/materials/material.h"
#include "integrator/textures/texture.h"

namespace camsim {

class DiffuseMaterial final : public Material {
 public:
  explicit DiffuseMaterial(std::unique_ptr<SpectrumTexture> reflectance);
  explicit DiffuseMaterial(Spectrum reflectance);

  SampledSpectrum f(const glm::vec3& wo, const glm::vec3& wi, const SampledWavelengths& lambda,
                    const BsdfContext& ctx) const override;
  std::optional<BsdfSample> sample(const glm::vec3& wo, float uc, glm::vec2 u,
                                   const SampledWavelengths& lambda,
                                   const BsdfContext& ctx) const override;
  float pdf(const glm::vec3& wo, const glm::vec3& wi, const SampledWavelengths& lambda,
            const BsdfContext& ctx) const override;
  SurfaceAov aov(const SampledWavelengths& lambda, const BsdfContext& ctx) const override;

 private:
  std::unique_ptr<SpectrumTexture> reflectance_;
};

}  // namespace camsim
