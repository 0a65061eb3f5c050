#include "integrator/materials/diffuse_material.h"

#include <cmath>

#include "integrator/geometry/math.h"

namespace camsim {

DiffuseMaterial::DiffuseMaterial(std::unique_ptr<SpectrumTexture> reflectance)
    : reflectance_(std::move(reflectance)) {
  traits_.reflects = reflectance_->maxValue() > 0.0;
  traits_.lambertianReflectance = reflectance_.get();
}

DiffuseMaterial::DiffuseMaterial(Spectrum reflectance)
    : DiffuseMaterial(std::make_unique<ConstantSpectrumTexture>(std::move(reflectance))) {}

SampledSpectrum DiffuseMaterial::f(const glm::vec3& wo, const glm::vec3& wi,
                                   const SampledWavelengths& lambda, const BsdfContext& ctx) const {
  if (wo.z * wi.z <= 0.0f) return SampledSpectrum(0.0f);
  return ctx.lookup(*reflectance_, lambda) * kInvPi;
}

std::optional<BsdfSample> DiffuseMaterial::sample(const glm::vec3& wo, float /*uc*/, glm::vec2 u,
                                                  const SampledWavelengths& lambda,
                                                  const BsdfContext& ctx) const {
  if (wo.z == 0.0f) return std::nullopt;
  glm::vec3 wi = sampleCosineHemisphere(u);
  wi.z = std::copysign(wi.z, wo.z);  // wo's side (wi.z ≥ 0 here); no branch on a random sign
  const float pdfValue = std::abs(wi.z) * kInvPi;
  if (pdfValue == 0.0f) return std::nullopt;
  BsdfSample s;
  s.f = ctx.lookup(*reflectance_, lambda) * kInvPi;
  s.wi = wi;
  s.pdf = pdfValue;
  return s;
}

float DiffuseMaterial::pdf(const glm::vec3& wo, const glm::vec3& wi,
                           const SampledWavelengths& /*lambda*/, const BsdfContext& /*ctx*/) const {
  if (wo.z * wi.z <= 0.0f) return 0.0f;
  return std::abs(wi.z) * kInvPi;
}

SurfaceAov DiffuseMaterial::aov(const SampledWavelengths& lambda, const BsdfContext& ctx) const {
  return {ctx.lookup(*reflectance_, lambda), 1.0f};
}

}  // namespace camsim
