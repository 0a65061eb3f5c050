// MirrorMaterial: a perfect specular reflector, the same on both sides of the surface.
//
// | parameter   | unit          | default |
// |-------------|---------------|---------|
// | reflectance | dimensionless | 0.5     |  k(λ) in [0, 1], may be a texture
//
//   wi = (−wo.x, −wo.y, wo.z)   (mirror image about the shading normal)
//   delta lobe: sample() returns f = k(λ)/|cos θi| and pdf = 1 (the lobe's probability),
//   so the path weight f |cos θi| / pdf is exactly k(λ): reflected radiance = k(λ) Lₑ.
//   f() and pdf() are 0 for every pair of directions (a delta is only sampled).
#pragma once

#include <memory>

#include "integrator/materials/material.h"
#include "integrator/textures/texture.h"

namespace camsim {

class MirrorMaterial final : public Material {
 public:
  explicit MirrorMaterial(std::unique_ptr<SpectrumTexture> reflectance);
  explicit MirrorMaterial(Spectrum reflectance);

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
