#include "integrator/materials/mirror_material.h"

#include <cmath>

#include "sensor/base/check.h"

namespace camsim {

MirrorMaterial::MirrorMaterial(std::unique_ptr<SpectrumTexture> reflectance)
    : reflectance_(std::move(reflectance)) {
  CAMSIM_CHECK(reflectance_ != nullptr);
  traits_.reflects = reflectance_->maxValue() > 0.0;
  traits_.nonSpecular = false;
}

MirrorMaterial::MirrorMaterial(Spectrum reflectance)
    : MirrorMaterial(std::make_unique<ConstantSpectrumTexture>(std::move(reflectance))) {}

SampledSpectrum MirrorMaterial::f(const glm::vec3& /*wo*/, const glm::vec3& /*wi*/,
                                  const SampledWavelengths& /*lambda*/,
                                  const BsdfContext& /*ctx*/) const {
  return SampledSpectrum(0.0f);
}

std::optional<BsdfSample> MirrorMaterial::sample(const glm::vec3& wo, float /*uc*/, glm::vec2 /*u*/,
                                                 const SampledWavelengths& lambda,
                                                 const BsdfContext& ctx) const {
  const float cosTheta = std::abs(wo.z);
  if (!(cosTheta > 0.0f)) return std::nullopt;
  BsdfSample s;
  s.wi = glm::vec3(-wo.x, -wo.y, wo.z);
  s.f = ctx.lookup(*reflectance_, lambda) / cosTheta;
  if (!s.f.isFinite()) return std::nullopt;  // cos θ below ~1e-38: nothing usable
  s.pdf = 1.0f;
  s.specular = true;
  return s;
}

float MirrorMaterial::pdf(const glm::vec3& /*wo*/, const glm::vec3& /*wi*/,
                          const SampledWavelengths& /*lambda*/, const BsdfContext& /*ctx*/) const {
  return 0.0f;
}

SurfaceAov MirrorMaterial::aov(const SampledWavelengths& lambda, const BsdfContext& ctx) const {
  return {ctx.lookup(*reflectance_, lambda), 0.0f};
}

}  // namespace camsim
