#include "integrator/dielectric_material.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "integrator/fresnel.h"
#include "sensor/check.h"

namespace camsim {

namespace {

float sqr(float x) {
  return x * x;
}

// The generalised half vector of (wo, wi) and the relative index η' of wi's side over
// wo's side (1 for reflection); nothing for degenerate or back-facing configurations.
struct HalfVector {
  glm::vec3 wm;
  float etap;
  bool reflection;
};

std::optional<HalfVector> halfVector(const glm::vec3& wo, const glm::vec3& wi, float eta) {
  const float cosO = wo.z, cosI = wi.z;
  if (cosO == 0.0f || cosI == 0.0f) return std::nullopt;
  const bool reflection = cosO * cosI > 0.0f;
  const float etap = reflection ? 1.0f : (cosO > 0.0f ? eta : 1.0f / eta);
  glm::vec3 wm = wi * etap + wo;
  const float len2 = glm::dot(wm, wm);
  if (!(len2 > 0.0f) || !std::isfinite(len2)) return std::nullopt;
  wm /= std::sqrt(len2);
  if (wm.z < 0.0f) wm = -wm;
  if (!(wm.z > 0.0f)) return std::nullopt;
  // Facets that wo or wi see from behind contribute nothing.
  if (glm::dot(wm, wo) * cosO <= 0.0f || glm::dot(wm, wi) * cosI <= 0.0f) return std::nullopt;
  return HalfVector{wm, etap, reflection};
}

bool finitePositive(float x) {
  return x > 0.0f && std::isfinite(x);
}

}  // namespace

DielectricMaterial::DielectricMaterial(Spectrum eta, std::unique_ptr<FloatTexture> roughness,
                                       float anisotropy, MicrofacetDistribution distribution,
                                       MaskingModel masking)
    : eta_(std::move(eta)),
      roughness_(std::move(roughness)),
      anisotropy_(anisotropy),
      distribution_(distribution),
      masking_(masking),
      dispersive_(eta_.maxValue() != eta_.minValue()),
      hasNonSpecular_(true) {
  CAMSIM_CHECK(roughness_ != nullptr);
  CAMSIM_CHECK(eta_.minValue() > 0.0);
  CAMSIM_CHECK(anisotropy_ > -1.0f && anisotropy_ < 1.0f);
  // A constant roughness tells up front whether every lobe is a delta (then light sampling
  // is skipped); a varying one may be rough somewhere.
  if (dynamic_cast<const ConstantFloatTexture*>(roughness_.get()) != nullptr) {
    const bool indexMatched = !dispersive_ && eta_.maxValue() == 1.0;
    hasNonSpecular_ = !indexMatched && !microfacet(BsdfContext{}).effectivelySmooth();
  }
}

DielectricMaterial::DielectricMaterial(Spectrum eta, float roughness, float anisotropy,
                                       MicrofacetDistribution distribution, MaskingModel masking)
    : DielectricMaterial(std::move(eta), std::make_unique<ConstantFloatTexture>(roughness),
                         anisotropy, distribution, masking) {}

MicrofacetModel DielectricMaterial::microfacet(const BsdfContext& ctx) const {
  const float alpha = std::max(0.0f, roughness_->evaluate(ctx.uv));
  return MicrofacetModel(distribution_, masking_, alpha * (1.0f + anisotropy_),
                         alpha * (1.0f - anisotropy_));
}

SampledSpectrum DielectricMaterial::f(const glm::vec3& wo, const glm::vec3& wi,
                                      const SampledWavelengths& lambda,
                                      const BsdfContext& ctx) const {
  const float eta = etaAt(lambda);
  const MicrofacetModel m = microfacet(ctx);
  if (smooth(m, eta)) return SampledSpectrum(0.0f);
  const std::optional<HalfVector> h = halfVector(wo, wi, eta);
  if (!h) return SampledSpectrum(0.0f);
  const float cosOM = glm::dot(wo, h->wm), cosIM = glm::dot(wi, h->wm);
  const float F = fresnelDielectric(cosOM, eta);
  const float dg = m.D(h->wm) * m.G(wo, wi, h->wm);
  float value;
  if (h->reflection) {
    value = dg * F / (4.0f * std::abs(wi.z * wo.z));
  } else {
    const float denom = sqr(cosIM + cosOM / h->etap) * wi.z * wo.z;
    value = dg * (1.0f - F) * std::abs(cosIM * cosOM / denom) / sqr(h->etap);
  }
  if (!std::isfinite(value)) return SampledSpectrum(0.0f);
  return SampledSpectrum(value);
}

float DielectricMaterial::pdf(const glm::vec3& wo, const glm::vec3& wi,
                              const SampledWavelengths& lambda, const BsdfContext& ctx) const {
  const float eta = etaAt(lambda);
  const MicrofacetModel m = microfacet(ctx);
  if (smooth(m, eta)) return 0.0f;
  const std::optional<HalfVector> h = halfVector(wo, wi, eta);
  if (!h) return 0.0f;
  const float cosOM = glm::dot(wo, h->wm), cosIM = glm::dot(wi, h->wm);
  const float R = fresnelDielectric(cosOM, eta);
  float value;
  if (h->reflection) {
    value = m.pdf(wo, h->wm) / (4.0f * std::abs(cosOM)) * R;
  } else {
    const float dwmDwi = std::abs(cosIM) / sqr(cosIM + cosOM / h->etap);
    value = m.pdf(wo, h->wm) * dwmDwi * (1.0f - R);
  }
  return std::isfinite(value) ? value : 0.0f;
}

std::optional<BsdfSample> DielectricMaterial::sample(const glm::vec3& wo, float uc, glm::vec2 u,
                                                     const SampledWavelengths& lambda,
                                                     const BsdfContext& ctx) const {
  if (wo.z == 0.0f) return std::nullopt;
  const float eta = etaAt(lambda);
  const MicrofacetModel m = microfacet(ctx);
  if (smooth(m, eta)) return sampleSmooth(wo, uc, eta);
  return sampleRough(wo, uc, u, eta, m);
}

std::optional<BsdfSample> DielectricMaterial::sampleSmooth(const glm::vec3& wo, float uc,
                                                           float eta) const {
  const float R = fresnelDielectric(wo.z, eta), T = 1.0f - R;
  BsdfSample s;
  s.specular = true;
  if (uc < R) {
    s.wi = glm::vec3(-wo.x, -wo.y, wo.z);
    s.f = SampledSpectrum(R / std::abs(s.wi.z));
    s.pdf = R;
    return s;
  }
  float etap = 1.0f;
  if (eta == 1.0f) {
    s.wi = -wo;  // index-matched: straight through
  } else {
    const std::optional<Refraction> r = refract(wo, glm::vec3(0.0f, 0.0f, 1.0f), eta);
    if (!r) return std::nullopt;
    s.wi = r->wt;
    etap = r->etap;
  }
  if (s.wi.z * wo.z >= 0.0f) return std::nullopt;
  s.f = SampledSpectrum(T / (std::abs(s.wi.z) * sqr(etap)));
  s.pdf = T;
  s.transmission = true;
  if (!finitePositive(s.pdf) || !s.f.isFinite()) return std::nullopt;
  return s;
}

std::optional<BsdfSample> DielectricMaterial::sampleRough(const glm::vec3& wo, float uc,
                                                          glm::vec2 u, float eta,
                                                          const MicrofacetModel& m) const {
  const glm::vec3 wm = m.sampleWm(wo, u);
  const float cosOM = glm::dot(wo, wm);
  if (cosOM * wo.z <= 0.0f) return std::nullopt;  // a back-facing facet (Beckmann samples D cosθm)
  const float R = fresnelDielectric(cosOM, eta), T = 1.0f - R;
  const float pdfWm = m.pdf(wo, wm);
  BsdfSample s;
  if (uc < R) {
    s.wi = glm::normalize(reflect(wo, wm));
    if (s.wi.z * wo.z <= 0.0f || glm::dot(s.wi, wm) * s.wi.z <= 0.0f) return std::nullopt;
    s.pdf = pdfWm / (4.0f * std::abs(cosOM)) * R;
    s.f = SampledSpectrum(m.D(wm) * m.G(wo, s.wi, wm) * R / (4.0f * std::abs(s.wi.z * wo.z)));
  } else {
    const std::optional<Refraction> r = refract(wo, wm, eta);
    if (!r) return std::nullopt;
    s.wi = glm::normalize(r->wt);
    const float cosIM = glm::dot(s.wi, wm);
    if (s.wi.z * wo.z >= 0.0f || cosIM * s.wi.z <= 0.0f) return std::nullopt;
    const float denom = sqr(cosIM + cosOM / r->etap);
    s.pdf = pdfWm * (std::abs(cosIM) / denom) * T;
    const float ft =
        m.D(wm) * m.G(wo, s.wi, wm) * T * std::abs(cosIM * cosOM / (denom * s.wi.z * wo.z));
    s.f = SampledSpectrum(ft / sqr(r->etap));
    s.transmission = true;
  }
  if (!finitePositive(s.pdf) || !s.f.isFinite()) return std::nullopt;
  return s;
}

}  // namespace camsim
