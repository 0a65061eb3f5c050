// The glTF 2.0 metallic-roughness BRDF (see metallic_roughness_material.h for the equations).
#include "integrator/materials/metallic_roughness_material.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "integrator/geometry/math.h"
#include "integrator/materials/dielectric_specular_albedo.h"
#include "integrator/materials/fresnel.h"
#include "sensor/base/check.h"

namespace camsim {
namespace {

constexpr float kDielectricF0 = 0.04f;  // ((1 − 1.5)/(1 + 1.5))², glTF's ior 1.5
// E_avg of a smooth dielectric: 2 ∫ F_d(μ) μ dμ = 0.04 + 0.96 · 2 B(2, 6) = 0.04 + 0.96/21.
constexpr float kSmoothAverage = kDielectricF0 + (1.0f - kDielectricF0) / 21.0f;

// x clamped to [0, 1]; NaN → 0.
float unit(float x) {
  return x > 0.0f ? std::min(x, 1.0f) : 0.0f;
}

// (1 − cos)⁵, Schlick's weight, for cos clamped to [0, 1].
float schlickWeight(float cosTheta) {
  const float x = 1.0f - unit(cosTheta);
  const float x2 = x * x;
  return x2 * x2 * x;
}

}  // namespace

MetallicRoughnessMaterial::MetallicRoughnessMaterial(MetallicRoughnessParameters p)
    : p_(std::move(p)) {
  CAMSIM_CHECK(p_.baseColor != nullptr && p_.metallic != nullptr && p_.roughness != nullptr);
  DielectricSpecularAlbedo::get();  // built now (once), not inside a render
  // A smooth metal everywhere has only its delta lobe: light sampling can be skipped.
  const auto* r = dynamic_cast<const ConstantFloatTexture*>(p_.roughness.get());
  const auto* m = dynamic_cast<const ConstantFloatTexture*>(p_.metallic.get());
  if (r && m)
    traits_.nonSpecular = !(unit(m->evaluate({})) == 1.0f &&
                            MicrofacetModel::fromRoughness(MicrofacetDistribution::kGgx,
                                                           MaskingModel::kSmith, alpha({}), 0.0f)
                                .effectivelySmooth());
}

float MetallicRoughnessMaterial::alpha(const BsdfContext& ctx) const {
  const float r = unit(p_.roughness->evaluate(ctx.uv));
  return r * r;
}

MetallicRoughnessMaterial::Lobes MetallicRoughnessMaterial::lobes(const glm::vec3& wo,
                                                                  const SampledWavelengths& lambda,
                                                                  const BsdfContext& ctx) const {
  const float r = unit(p_.roughness->evaluate(ctx.uv));
  Lobes l{ctx.lookup(*p_.baseColor, lambda), unit(p_.metallic->evaluate(ctx.uv)), 0.0f,
          MicrofacetModel::fromRoughness(MicrofacetDistribution::kGgx, MaskingModel::kSmith, r * r,
                                         0.0f),
          r};
  for (int i = 0; i < kWavelengthSamples; ++i) l.baseColor[i] = unit(l.baseColor[i]);
  const float s = schlickWeight(wo.z), m = l.metallic;
  l.albedoOut = specularAlbedo(l, wo.z);
  const float average =
      l.model.effectivelySmooth() ? kSmoothAverage : DielectricSpecularAlbedo::get().average(r);
  l.diffuseScale = (1.0f - m) * (1.0f - l.albedoOut) * kInvPi / (1.0f - average);
  const float cmax = l.baseColor.maxComponent();
  const float wDiffuse = (1.0f - m) * (1.0f - l.albedoOut) * cmax;
  const float wSpecular = (1.0f - m) * l.albedoOut + m * (cmax + (1.0f - cmax) * s);
  const float total = wDiffuse + wSpecular;
  l.pDiffuse = total > 0.0f ? wDiffuse / total : 0.0f;
  return l;
}

float MetallicRoughnessMaterial::specularAlbedo(const Lobes& l, float cosTheta) {
  return l.model.effectivelySmooth()
             ? DielectricSpecularAlbedo::fresnel(cosTheta)
             : DielectricSpecularAlbedo::get().albedo(cosTheta, l.roughness);
}

MetallicRoughnessMaterial::Eval MetallicRoughnessMaterial::evaluate(const Lobes& l,
                                                                    const glm::vec3& wo,
                                                                    const glm::vec3& wi,
                                                                    const glm::vec3& wm) const {
  const float s = schlickWeight(std::abs(glm::dot(wo, wm)));
  const float fd = kDielectricF0 + (1.0f - kDielectricF0) * s, m = l.metallic;
  Eval e{l.baseColor * (l.diffuseScale * (1.0f - specularAlbedo(l, wi.z))),
         l.pDiffuse * wi.z * kInvPi};
  if (l.model.effectivelySmooth()) return e;
  const MicrofacetModel::Reflection r = l.model.reflection(wo, wi, wm);
  if (r.f > 0.0f) {
    // (1 − m) F_d + m (c + (1 − c) s), per wavelength
    const SampledSpectrum fresnel =
        SampledSpectrum((1.0f - m) * fd + m * s) + l.baseColor * (m * (1.0f - s));
    e.f += fresnel * r.f;
  }
  e.pdf += (1.0f - l.pDiffuse) * r.pdf;
  return e;
}

SampledSpectrum MetallicRoughnessMaterial::f(const glm::vec3& woIn, const glm::vec3& wiIn,
                                             const SampledWavelengths& lambda,
                                             const BsdfContext& ctx) const {
  if (!(woIn.z * wiIn.z > 0.0f)) return SampledSpectrum(0.0f);
  const glm::vec3 wo = upperHemisphere(woIn), wi = upperHemisphere(wiIn);
  return evaluate(lobes(wo, lambda, ctx), wo, wi, halfVector(wo, wi)).f;
}

float MetallicRoughnessMaterial::pdf(const glm::vec3& woIn, const glm::vec3& wiIn,
                                     const SampledWavelengths& lambda,
                                     const BsdfContext& ctx) const {
  if (!(woIn.z * wiIn.z > 0.0f)) return 0.0f;
  const glm::vec3 wo = upperHemisphere(woIn), wi = upperHemisphere(wiIn);
  return evaluate(lobes(wo, lambda, ctx), wo, wi, halfVector(wo, wi)).pdf;
}

std::optional<BsdfSample> MetallicRoughnessMaterial::sample(const glm::vec3& woIn, float uc,
                                                            glm::vec2 u,
                                                            const SampledWavelengths& lambda,
                                                            const BsdfContext& ctx) const {
  if (!(std::abs(woIn.z) > 0.0f)) return std::nullopt;  // in the plane, or NaN
  const float side = woIn.z > 0.0f ? 1.0f : -1.0f;
  const glm::vec3 wo = upperHemisphere(woIn);
  const Lobes l = lobes(wo, lambda, ctx);
  BsdfSample s;
  glm::vec3 wi, wm;
  if (uc < l.pDiffuse) {
    wi = sampleCosineHemisphere(u);
    wm = halfVector(wo, wi);
  } else if (l.model.effectivelySmooth()) {
    // The delta mirror: wm = the normal, wo·wm = cos θo.
    const float sw = schlickWeight(wo.z), m = l.metallic;
    const float fd = kDielectricF0 + (1.0f - kDielectricF0) * sw;
    s.wi = glm::vec3(-woIn.x, -woIn.y, woIn.z);
    s.f = (SampledSpectrum((1.0f - m) * fd + m * sw) + l.baseColor * (m * (1.0f - sw))) *
          (1.0f / wo.z);
    s.pdf = 1.0f - l.pDiffuse;
    s.specular = true;
    return s.f.isFinite() && s.pdf > 0.0f ? std::optional<BsdfSample>(s) : std::nullopt;
  } else {
    const std::optional<MicrofacetModel::ReflectionSample> h = l.model.sampleReflection(wo, u);
    if (!h) return std::nullopt;
    wi = h->wi;
    wm = h->wm;
  }
  if (!(wi.z > 0.0f)) return std::nullopt;
  const Eval e = evaluate(l, wo, wi, wm);
  if (!(e.pdf > 0.0f) || !e.f.isFinite()) return std::nullopt;
  s.wi = glm::vec3(wi.x, wi.y, side * wi.z);
  s.f = e.f;
  s.pdf = e.pdf;
  return s;
}

SurfaceAov MetallicRoughnessMaterial::aov(const SampledWavelengths& lambda,
                                          const BsdfContext& ctx) const {
  SampledSpectrum c = ctx.lookup(*p_.baseColor, lambda);
  for (int i = 0; i < kWavelengthSamples; ++i) c[i] = unit(c[i]);
  return {c, alpha(ctx)};
}

}  // namespace camsim
