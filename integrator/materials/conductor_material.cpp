#include "integrator/materials/conductor_material.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "sensor/base/check.h"

namespace camsim {

ConductorMaterial::ConductorMaterial(ConductorParameters p) : p_(std::move(p)) {
  CAMSIM_CHECK(p_.roughness != nullptr);
  CAMSIM_CHECK(p_.fresnel == FresnelModel::kExact || p_.r0 != nullptr);
  // A constant roughness below the smooth threshold makes the material a pure mirror.
  if (dynamic_cast<const ConstantFloatTexture*>(p_.roughness.get()) != nullptr)
    traits_.nonSpecular = !model(BsdfContext{}).effectivelySmooth();
}

MicrofacetModel ConductorMaterial::model(const BsdfContext& ctx) const {
  return MicrofacetModel::fromRoughness(p_.distribution, p_.masking, p_.roughness->evaluate(ctx.uv),
                                        p_.anisotropy);
}

SampledSpectrum ConductorMaterial::fresnel(float cosTheta, const SampledWavelengths& lambda,
                                           const BsdfContext& ctx) const {
  if (p_.fresnel == FresnelModel::kSchlick)
    return fresnelSchlick(cosTheta, ctx.lookup(*p_.r0, lambda));
  return fresnelConductor(cosTheta, sampleSpectrum(p_.eta, lambda), sampleSpectrum(p_.k, lambda));
}

SampledSpectrum ConductorMaterial::f(const glm::vec3& woIn, const glm::vec3& wiIn,
                                     const SampledWavelengths& lambda,
                                     const BsdfContext& ctx) const {
  if (!(woIn.z * wiIn.z > 0.0f)) return SampledSpectrum(0.0f);
  const MicrofacetModel m = model(ctx);
  if (m.effectivelySmooth()) return SampledSpectrum(0.0f);
  const glm::vec3 wo = upperHemisphere(woIn), wi = upperHemisphere(wiIn), wm = halfVector(wo, wi);
  const MicrofacetModel::Reflection r = m.reflection(wo, wi, wm);
  return r.f > 0.0f ? fresnel(glm::dot(wo, wm), lambda, ctx) * r.f : SampledSpectrum(0.0f);
}

float ConductorMaterial::pdf(const glm::vec3& woIn, const glm::vec3& wiIn,
                             const SampledWavelengths& /*lambda*/, const BsdfContext& ctx) const {
  if (!(woIn.z * wiIn.z > 0.0f)) return 0.0f;
  const MicrofacetModel m = model(ctx);
  if (m.effectivelySmooth()) return 0.0f;
  const glm::vec3 wo = upperHemisphere(woIn), wi = upperHemisphere(wiIn);
  return m.reflection(wo, wi, halfVector(wo, wi)).pdf;
}

std::optional<BsdfSample> ConductorMaterial::sample(const glm::vec3& woIn, float /*uc*/,
                                                    glm::vec2 u, const SampledWavelengths& lambda,
                                                    const BsdfContext& ctx) const {
  if (woIn.z == 0.0f) return std::nullopt;
  const float side = woIn.z > 0.0f ? 1.0f : -1.0f;
  const glm::vec3 wo = upperHemisphere(woIn);
  const MicrofacetModel m = model(ctx);
  BsdfSample s;
  if (m.effectivelySmooth()) {
    s.wi = glm::vec3(-woIn.x, -woIn.y, woIn.z);
    s.f = fresnel(wo.z, lambda, ctx) / wo.z;
    s.pdf = 1.0f;
    s.specular = true;
    return s;
  }
  const std::optional<MicrofacetModel::ReflectionSample> h = m.sampleReflection(wo, u);
  if (!h) return std::nullopt;
  const MicrofacetModel::Reflection r = m.reflection(wo, h->wi, h->wm);
  if (!(r.pdf > 0.0f)) return std::nullopt;
  s.wi = glm::vec3(h->wi.x, h->wi.y, side * h->wi.z);
  s.f = fresnel(glm::dot(wo, h->wm), lambda, ctx) * r.f;
  s.pdf = r.pdf;
  return s;
}

SurfaceAov ConductorMaterial::aov(const SampledWavelengths& lambda, const BsdfContext& ctx) const {
  return {fresnel(1.0f, lambda, ctx), p_.roughness->evaluate(ctx.uv)};
}

}  // namespace camsim
