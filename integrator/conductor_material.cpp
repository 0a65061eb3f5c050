#include "integrator/conductor_material.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "sensor/check.h"

namespace camsim {
namespace {

// Mirrors a direction below the surface to +z (the material is the same on both sides).
glm::vec3 upper(const glm::vec3& w) {
  return {w.x, w.y, std::abs(w.z)};
}

}  // namespace

ConductorMaterial::ConductorMaterial(ConductorParameters p) : p_(std::move(p)) {
  CAMSIM_CHECK(p_.roughness != nullptr);
  CAMSIM_CHECK(p_.fresnel == FresnelModel::kExact || p_.r0 != nullptr);
  // A constant roughness below the smooth threshold makes the material a pure mirror.
  if (dynamic_cast<const ConstantFloatTexture*>(p_.roughness.get()) != nullptr)
    hasNonSpecular_ = !model(BsdfContext{}).effectivelySmooth();
}

MicrofacetModel ConductorMaterial::model(const BsdfContext& ctx) const {
  const float alpha = std::max(0.0f, p_.roughness->evaluate(ctx.uv));
  return MicrofacetModel(p_.distribution, p_.masking, alpha * (1.0f + p_.anisotropy),
                         alpha * (1.0f - p_.anisotropy));
}

SampledSpectrum ConductorMaterial::fresnel(float cosTheta, const SampledWavelengths& lambda,
                                           const BsdfContext& ctx) const {
  if (p_.fresnel == FresnelModel::kSchlick)
    return fresnelSchlick(cosTheta, p_.r0->evaluate(ctx.uv, lambda));
  return fresnelConductor(cosTheta, sampleSpectrum(p_.eta, lambda), sampleSpectrum(p_.k, lambda));
}

// f and pdf for wo, wi on the +z side and their half vector wm.
ConductorMaterial::Eval ConductorMaterial::evaluate(const MicrofacetModel& m, const glm::vec3& wo,
                                                    const glm::vec3& wi, const glm::vec3& wm,
                                                    const SampledWavelengths& lambda,
                                                    const BsdfContext& ctx) const {
  const float woDotWm = glm::dot(wo, wm);
  if (!(woDotWm > 0.0f) || !(wm.z > 0.0f)) return {};
  const float d = m.D(wm);
  if (d == 0.0f) return {};
  const float value = d * m.G(wo, wi, wm) / (4.0f * wo.z * wi.z);
  const float pdf = m.pdf(wo, wm) / (4.0f * woDotWm);
  if (!std::isfinite(value) || !std::isfinite(pdf)) return {};
  return {fresnel(woDotWm, lambda, ctx) * value, pdf};
}

std::optional<glm::vec3> ConductorMaterial::halfVector(const glm::vec3& wo, const glm::vec3& wi) {
  const glm::vec3 h = wo + wi;
  const float len2 = glm::dot(h, h);
  if (!(len2 > 0.0f)) return std::nullopt;
  return h / std::sqrt(len2);
}

SampledSpectrum ConductorMaterial::f(const glm::vec3& woIn, const glm::vec3& wiIn,
                                     const SampledWavelengths& lambda,
                                     const BsdfContext& ctx) const {
  if (!(woIn.z * wiIn.z > 0.0f)) return SampledSpectrum(0.0f);
  const MicrofacetModel m = model(ctx);
  if (m.effectivelySmooth()) return SampledSpectrum(0.0f);
  const glm::vec3 wo = upper(woIn), wi = upper(wiIn);
  const std::optional<glm::vec3> wm = halfVector(wo, wi);
  return wm ? evaluate(m, wo, wi, *wm, lambda, ctx).f : SampledSpectrum(0.0f);
}

float ConductorMaterial::pdf(const glm::vec3& woIn, const glm::vec3& wiIn,
                             const SampledWavelengths& lambda, const BsdfContext& ctx) const {
  if (!(woIn.z * wiIn.z > 0.0f)) return 0.0f;
  const MicrofacetModel m = model(ctx);
  if (m.effectivelySmooth()) return 0.0f;
  const glm::vec3 wo = upper(woIn), wi = upper(wiIn);
  const std::optional<glm::vec3> wm = halfVector(wo, wi);
  return wm ? evaluate(m, wo, wi, *wm, lambda, ctx).pdf : 0.0f;
}

std::optional<BsdfSample> ConductorMaterial::sample(const glm::vec3& woIn, float /*uc*/,
                                                    glm::vec2 u, const SampledWavelengths& lambda,
                                                    const BsdfContext& ctx) const {
  if (woIn.z == 0.0f) return std::nullopt;
  const float side = woIn.z > 0.0f ? 1.0f : -1.0f;
  const glm::vec3 wo = upper(woIn);
  const MicrofacetModel m = model(ctx);
  BsdfSample s;
  if (m.effectivelySmooth()) {
    s.wi = glm::vec3(-woIn.x, -woIn.y, woIn.z);
    s.f = fresnel(wo.z, lambda, ctx) / wo.z;
    s.pdf = 1.0f;
    s.specular = true;
    return s;
  }
  const glm::vec3 wm = m.sampleWm(wo, u);
  const glm::vec3 wi = glm::normalize(reflect(wo, wm));
  if (!(wi.z > 0.0f)) return std::nullopt;
  // f and pdf with the sampled wm: at grazing wo and tiny α the half vector rebuilt from
  // (wo, wi) in single precision would be off by more than the lobe is wide.
  const Eval e = evaluate(m, wo, wi, wm, lambda, ctx);
  if (!(e.pdf > 0.0f)) return std::nullopt;
  s.wi = glm::vec3(wi.x, wi.y, side * wi.z);
  s.f = e.f;
  s.pdf = e.pdf;
  return s;
}

}  // namespace camsim
