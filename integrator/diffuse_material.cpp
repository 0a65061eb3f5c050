#include "integrator/diffuse_material.h"

#include <cmath>

#include "integrator/math.h"

namespace camsim {

DiffuseMaterial::DiffuseMaterial(Spectrum reflectance)
    : reflectance_(reflectance), reflects_(reflectance.maxValue() > 0.0) {}

SampledSpectrum DiffuseMaterial::f(const glm::vec3& wo, const glm::vec3& wi,
                                   const SampledWavelengths& lambda) const {
  if (wo.z * wi.z <= 0.0f) return SampledSpectrum(0.0f);
  return sampleSpectrum(reflectance_, lambda) * kInvPi;
}

std::optional<BsdfSample> DiffuseMaterial::sample(const glm::vec3& wo, float /*uc*/, glm::vec2 u,
                                                  const SampledWavelengths& lambda) const {
  if (wo.z == 0.0f) return std::nullopt;
  glm::vec3 wi = sampleCosineHemisphere(u);
  if (wo.z < 0.0f) wi.z = -wi.z;
  const float pdfValue = std::abs(wi.z) * kInvPi;
  if (pdfValue == 0.0f) return std::nullopt;
  return BsdfSample{sampleSpectrum(reflectance_, lambda) * kInvPi, wi, pdfValue};
}

float DiffuseMaterial::pdf(const glm::vec3& wo, const glm::vec3& wi) const {
  if (wo.z * wi.z <= 0.0f) return 0.0f;
  return std::abs(wi.z) * kInvPi;
}

}  // namespace camsim
