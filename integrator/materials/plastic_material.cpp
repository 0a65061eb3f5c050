#include "integrator/materials/plastic_material.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "integrator/geometry/math.h"
#include "sensor/base/check.h"

namespace camsim {

PlasticMaterial::PlasticMaterial(PlasticParameters p) : p_(std::move(p)) {
  CAMSIM_CHECK(p_.reflectance != nullptr && p_.roughness != nullptr);
  CAMSIM_CHECK(p_.specularWeight >= 0.0f && p_.specularWeight <= 1.0f);
  traits_.reflects = p_.specularWeight > 0.0f || p_.reflectance->maxValue() > 0.0;
}

PlasticMaterial::Lobes PlasticMaterial::lobes(const SampledWavelengths& lambda,
                                              const BsdfContext& ctx) const {
  const float ks = p_.specularWeight, kd = 1.0f - ks;
  const SampledSpectrum rho = ctx.lookup(*p_.reflectance, lambda);
  const float diffuseWeight = kd * std::max(0.0f, rho.maxComponent());
  const float total = diffuseWeight + ks;
  return {rho * (kd * kInvPi), total > 0.0f ? diffuseWeight / total : 0.0f,
          MicrofacetModel::fromRoughness(p_.distribution, p_.masking,
                                         p_.roughness->evaluate(ctx.uv), p_.anisotropy)};
}

PlasticMaterial::Eval PlasticMaterial::evaluate(const Lobes& l, const glm::vec3& wo,
                                                const glm::vec3& wi, const glm::vec3& wm) const {
  Eval e{l.diffuse, l.pDiffuse * wi.z * kInvPi};
  if (l.model.effectivelySmooth() || p_.specularWeight == 0.0f) return e;
  const MicrofacetModel::Reflection r = l.model.reflection(wo, wi, wm);
  e.f += SampledSpectrum(p_.specularWeight * r.f);
  e.pdf += (1.0f - l.pDiffuse) * r.pdf;
  return e;
}

SampledSpectrum PlasticMaterial::f(const glm::vec3& woIn, const glm::vec3& wiIn,
                                   const SampledWavelengths& lambda, const BsdfContext& ctx) const {
  if (!(woIn.z * wiIn.z > 0.0f)) return SampledSpectrum(0.0f);
  const glm::vec3 wo = upperHemisphere(woIn), wi = upperHemisphere(wiIn);
  return evaluate(lobes(lambda, ctx), wo, wi, halfVector(wo, wi)).f;
}

float PlasticMaterial::pdf(const glm::vec3& woIn, const glm::vec3& wiIn,
                           const SampledWavelengths& lambda, const BsdfContext& ctx) const {
  if (!(woIn.z * wiIn.z > 0.0f)) return 0.0f;
  const glm::vec3 wo = upperHemisphere(woIn), wi = upperHemisphere(wiIn);
  return evaluate(lobes(lambda, ctx), wo, wi, halfVector(wo, wi)).pdf;
}

std::optional<BsdfSample> PlasticMaterial::sample(const glm::vec3& woIn, float uc, glm::vec2 u,
                                                  const SampledWavelengths& lambda,
                                                  const BsdfContext& ctx) const {
  if (woIn.z == 0.0f) return std::nullopt;
  const float side = woIn.z > 0.0f ? 1.0f : -1.0f;
  const glm::vec3 wo = upperHemisphere(woIn);
  const Lobes l = lobes(lambda, ctx);
  if (l.pDiffuse == 0.0f && p_.specularWeight == 0.0f) return std::nullopt;
  BsdfSample s;
  glm::vec3 wi, wm;
  if (uc < l.pDiffuse) {
    wi = sampleCosineHemisphere(u);
    wm = halfVector(wo, wi);
  } else if (l.model.effectivelySmooth()) {
    s.wi = glm::vec3(-woIn.x, -woIn.y, woIn.z);
    s.f = SampledSpectrum(p_.specularWeight / wo.z);
    s.pdf = 1.0f - l.pDiffuse;
    s.specular = true;
    return s.f.isFinite() ? std::optional<BsdfSample>(s) : std::nullopt;
  } else {
    const std::optional<MicrofacetModel::ReflectionSample> h = l.model.sampleReflection(wo, u);
    if (!h) return std::nullopt;
    wi = h->wi;
    wm = h->wm;
  }
  if (!(wi.z > 0.0f)) return std::nullopt;
  const Eval e = evaluate(l, wo, wi, wm);
  if (!(e.pdf > 0.0f)) return std::nullopt;
  s.wi = glm::vec3(wi.x, wi.y, side * wi.z);
  s.f = e.f;
  s.pdf = e.pdf;
  return s;
}

SurfaceAov PlasticMaterial::aov(const SampledWavelengths& lambda, const BsdfContext& ctx) const {
  return {ctx.lookup(*p_.reflectance, lambda), p_.roughness->evaluate(ctx.uv)};
}

}  // namespace camsim
