// PlasticMaterial: a diffuse base under an ideal colourless specular layer, two-sided.
//
// | parameter      | unit          | default | meaning                                      |
// |----------------|---------------|---------|----------------------------------------------|
// | reflectance    | dimensionless | 0.5     | ρ(λ), diffuse reflectance, may be a texture  |
// | specularWeight | dimensionless | 0.1     | ks; the diffuse weight is kd = 1 − ks        |
// | roughness      | dimensionless | 0       | α of the specular lobe; < 1e-4 = smooth      |
// | anisotropy     | dimensionless | 0       | αx = α (1 + a), αy = α (1 − a)               |
// | distribution   | —             | ggx     | ggx or beckmann (microfacet.h)               |
// | masking        | —             | smith   | smith or v-groove                            |
//
//   f(wo, wi) = kd ρ(λ)/π + ks D(wm) G(wo, wi, wm) / (4 |cos θo| |cos θi|)   (same side only)
//   The specular layer is ideal and colourless: F = 1 (the scene's η is not used). Each lobe
//   conserves energy on its own, so the albedo is at most kd ρ + ks ≤ 1.
//   sampling: the diffuse lobe with probability pd = kd ρmax / (kd ρmax + ks) (ρmax: largest
//   ρ over the path's wavelengths), else the specular lobe (microfacet.h sampleWm + reflect);
//   pdf = pd |cos θi|/π + (1 − pd) pdf_spec.  Smooth (α < kSmoothAlpha): the specular lobe is a
//   delta mirror chosen with probability 1 − pd, f = ks/|cos θi|, pdf() holds the diffuse part.
//   wo below the surface is mirrored to +z (like DiffuseMaterial, both sides are alike).
#pragma once

#include <memory>

#include "integrator/materials/material.h"
#include "integrator/materials/microfacet.h"
#include "integrator/textures/texture.h"

namespace camsim {

struct PlasticParameters {
  std::unique_ptr<SpectrumTexture> reflectance;
  std::unique_ptr<FloatTexture> roughness;
  float specularWeight = 0.1f;
  float anisotropy = 0.0f;
  MicrofacetDistribution distribution = MicrofacetDistribution::kGgx;
  MaskingModel masking = MaskingModel::kSmith;
};

class PlasticMaterial final : public Material {
 public:
  explicit PlasticMaterial(PlasticParameters p);

  SampledSpectrum f(const glm::vec3& wo, const glm::vec3& wi, const SampledWavelengths& lambda,
                    const BsdfContext& ctx) const override;
  std::optional<BsdfSample> sample(const glm::vec3& wo, float uc, glm::vec2 u,
                                   const SampledWavelengths& lambda,
                                   const BsdfContext& ctx) const override;
  float pdf(const glm::vec3& wo, const glm::vec3& wi, const SampledWavelengths& lambda,
            const BsdfContext& ctx) const override;
  SurfaceAov aov(const SampledWavelengths& lambda, const BsdfContext& ctx) const override;

 private:
  struct Lobes {              // everything that depends on the surface point and wavelengths
    SampledSpectrum diffuse;  // kd ρ(λ)/π
    float pDiffuse = 0.0f;    // probability of sampling the diffuse lobe
    MicrofacetModel model;
  };
  struct Eval {
    SampledSpectrum f;
    float pdf = 0.0f;
  };
  Lobes lobes(const SampledWavelengths& lambda, const BsdfContext& ctx) const;
  // f and pdf for wo, wi on the +z side, wm their half vector (specular part).
  Eval evaluate(const Lobes& l, const glm::vec3& wo, const glm::vec3& wi,
                const glm::vec3& wm) const;

  PlasticParameters p_;
};

}  // namespace camsim
