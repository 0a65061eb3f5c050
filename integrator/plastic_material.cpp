#include "integrator/plastic_material.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "integrator/fresnel.h"
#include "integrator/math.h"
#include "sensor/check.h"

namespace camsim {
namespace {

glm::vec3 upper(const glm::vec3& w) {
  return {w.x, w.y, std::abs(w.z)};
}

glm::vec3 halfVector(const glm::vec3& wo, const glm::vec3& wi) {
  const glm::vec3 h = wo + wi;
  const float len2 = glm::dot(h, h);
  return len2 > 0.0f ? h / std::sqrt(len2) : glm::vec3(0.0f, 0.0f, 1.0f);
}

}  // namespace

PlasticMaterial::PlasticMaterial(PlasticParameters p) : p_(std::move(p)) {
  CAMSIM_CHECK(p_.reflectance != nullptr && p_.roughness != nullptr);
  CAMSIM_CHECK(p_.specularWeight >= 0.0f && p_.specularWeight <= 1.0f);
  reflects_ = p_.specularWeight > 0.0f || p_.reflectance->maxValue() > 0.0;
}

PlasticMaterial::Lobes PlasticMaterial::lobes(const SampledWavelengths& lambda,
                                              const BsdfContext& ctx) const {
  const float ks = p_.specularWeight, kd = 1.0f - ks;
  const SampledSpectrum rho = p_.reflectance->evaluate(ctx.uv, lambda);
  const float diffuseWeight = kd * std::max(0.0f, rho.maxComponent());
  const float total = diffuseWeight + ks;
  const float alpha = std::max(0.0f, p_.roughness->evaluate(ctx.uv));
  return {rho * (kd * kInvPi), total > 0.0f ? diffuseWeight / total : 0.0f,
          MicrofacetModel(p_.distribution, p_.masking, alpha * (1.0f + p_.anisotropy),
                          alpha * (1.0f - p_.anisotropy))};
}

PlasticMaterial::Eval PlasticMaterial::evaluate(const Lobes& l, const glm::vec3& wo,
                                                const glm::vec3& wi, const glm::vec3& wm) const {
  Eval e{l.diffuse, l.pDiffuse * wi.z * kInvPi};
  if (l.model.effectivelySmooth() || p_.specularWeight == 0.0f) return e;
  const float woDotWm = glm::dot(wo, wm);
  if (!(woDotWm > 0.0f) || !(wm.z > 0.0f)) return e;
  const float spec =
      p_.specularWeight * l.model.D(wm) * l.model.G(wo, wi, wm) / (4.0f * wo.z * wi.z);
  const float specPdf = l.model.pdf(wo, wm) / (4.0f * woDotWm);
  if (std::isfinite(spec) && std::isfinite(specPdf)) {
    e.f += SampledSpectrum(spec);
    e.pdf += (1.0f - l.pDiffuse) * specPdf;
  }
  return e;
}

SampledSpectrum PlasticMaterial::f(const glm::vec3& woIn, const glm::vec3& wiIn,
                                   const SampledWavelengths& lambda, const BsdfContext& ctx) const {
  if (!(woIn.z * wiIn.z > 0.0f)) return SampledSpectrum(0.0f);
  const glm::vec3 wo = upper(woIn), wi = upper(wiIn);
  return evaluate(lobes(lambda, ctx), wo, wi, halfVector(wo, wi)).f;
}

float PlasticMaterial::pdf(const glm::vec3& woIn, const glm::vec3& wiIn,
                           const SampledWavelengths& lambda, const BsdfContext& ctx) const {
  if (!(woIn.z * wiIn.z > 0.0f)) return 0.0f;
  const glm::vec3 wo = upper(woIn), wi = upper(wiIn);
  return evaluate(lobes(lambda, ctx), wo, wi, halfVector(wo, wi)).pdf;
}

std::optional<BsdfSample> PlasticMaterial::sample(const glm::vec3& woIn, float uc, glm::vec2 u,
                                                  const SampledWavelengths& lambda,
                                                  const BsdfContext& ctx) const {
  if (woIn.z == 0.0f) return std::nullopt;
  const float side = woIn.z > 0.0f ? 1.0f : -1.0f;
  const glm::vec3 wo = upper(woIn);
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
    // The sampled wm (not one rebuilt from wo + wi) keeps grazing, tiny-α samples exact.
    wm = l.model.sampleWm(wo, u);
    wi = glm::normalize(reflect(wo, wm));
  }
  if (!(wi.z > 0.0f)) return std::nullopt;
  const Eval e = evaluate(l, wo, wi, wm);
  if (!(e.pdf > 0.0f)) return std::nullopt;
  s.wi = glm::vec3(wi.x, wi.y, side * wi.z);
  s.f = e.f;
  s.pdf = e.pdf;
  return s;
}

}  // namespace camsim
