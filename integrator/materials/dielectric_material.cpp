#include "integrator/materials/dielectric_material.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "integrator/materials/fresnel.h"
#include "sensor/base/check.h"

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

// Fresnel transmittance 1 − R of a refraction pair from both cosines (c1 on the incident
// side, c2 on the other, etap = n2/n1): T = (t∥ + t⊥)/2 with t = 1 − r² written as
//   t∥ = 4 η' c1 c2 / (η' c1 + c2)²,   t⊥ = 4 η' c1 c2 / (c1 + η' c2)².
// Symmetric in the two sides and free of the cancellation in 1 − R and in
// cosθt = √(1 − sin²θi/η'²) near the critical angle, so the BTDF stays reciprocal there.
float transmittance(float c1, float c2, float etap) {
  c1 = std::abs(c1);
  c2 = std::abs(c2);
  const float a = etap * c1 + c2, b = c1 + etap * c2;
  return std::min(1.0f, 2.0f * etap * c1 * c2 * (1.0f / (a * a) + 1.0f / (b * b)));
}

// The rough BSDF and the density of sample() for one pair of directions (see the header).
// The lobe-choice probability is F(wo·wm) as in sample(); the BTDF uses the accurate
// two-sided transmittance.
struct RoughValue {
  float f, pdf;
};

std::optional<RoughValue> evaluateRough(const glm::vec3& wo, const glm::vec3& wi, float eta,
                                        const MicrofacetModel& m) {
  const std::optional<HalfVector> h = halfVector(wo, wi, eta);
  if (!h) return std::nullopt;
  const float cosOM = glm::dot(wo, h->wm), cosIM = glm::dot(wi, h->wm);
  const float R = fresnelDielectric(cosOM, eta);
  const float dg = m.D(h->wm) * m.G(wo, wi, h->wm);
  const float pdfWm = m.pdf(wo, h->wm);
  RoughValue v;
  if (h->reflection) {
    v.f = dg * R / (4.0f * std::abs(wi.z * wo.z));
    v.pdf = pdfWm / (4.0f * std::abs(cosOM)) * R;
  } else {
    const float denom = sqr(cosIM + cosOM / h->etap);
    const float T = transmittance(cosOM, cosIM, h->etap);
    v.f = dg * T * std::abs(cosIM * cosOM / (denom * wi.z * wo.z)) / sqr(h->etap);
    v.pdf = pdfWm * (std::abs(cosIM) / denom) * (1.0f - R);
  }
  if (!std::isfinite(v.f) || !std::isfinite(v.pdf)) return std::nullopt;
  return v;
}

}  // namespace

DielectricMaterial::DielectricMaterial(Spectrum eta, std::unique_ptr<FloatTexture> roughness,
                                       float anisotropy, MicrofacetDistribution distribution,
                                       MaskingModel masking)
    : eta_(std::move(eta)),
      roughness_(std::move(roughness)),
      anisotropy_(anisotropy),
      distribution_(distribution),
      masking_(masking) {
  traits_.dispersive = eta_.maxValue() != eta_.minValue();
  CAMSIM_CHECK(roughness_ != nullptr);
  CAMSIM_CHECK(eta_.minValue() > 0.0);
  CAMSIM_CHECK(anisotropy_ > -1.0f && anisotropy_ < 1.0f);
  // A constant roughness tells up front whether every lobe is a delta (then light sampling
  // is skipped); a varying one may be rough somewhere.
  if (dynamic_cast<const ConstantFloatTexture*>(roughness_.get()) != nullptr) {
    const bool indexMatched = !traits_.dispersive && eta_.maxValue() == 1.0;
    traits_.nonSpecular = !indexMatched && !microfacet(BsdfContext{}).effectivelySmooth();
  }
}

DielectricMaterial::DielectricMaterial(Spectrum eta, float roughness, float anisotropy,
                                       MicrofacetDistribution distribution, MaskingModel masking)
    : DielectricMaterial(std::move(eta), std::make_unique<ConstantFloatTexture>(roughness),
                         anisotropy, distribution, masking) {}

MicrofacetModel DielectricMaterial::microfacet(const BsdfContext& ctx) const {
  return MicrofacetModel::fromRoughness(distribution_, masking_, roughness_->evaluate(ctx.uv),
                                        anisotropy_);
}

SampledSpectrum DielectricMaterial::f(const glm::vec3& wo, const glm::vec3& wi,
                                      const SampledWavelengths& lambda,
                                      const BsdfContext& ctx) const {
  const float eta = etaAt(lambda);
  const MicrofacetModel m = microfacet(ctx);
  if (smooth(m, eta)) return SampledSpectrum(0.0f);
  const std::optional<RoughValue> v = evaluateRough(wo, wi, eta, m);
  return SampledSpectrum(v ? v->f : 0.0f);
}

float DielectricMaterial::pdf(const glm::vec3& wo, const glm::vec3& wi,
                              const SampledWavelengths& lambda, const BsdfContext& ctx) const {
  const float eta = etaAt(lambda);
  const MicrofacetModel m = microfacet(ctx);
  if (smooth(m, eta)) return 0.0f;
  const std::optional<RoughValue> v = evaluateRough(wo, wi, eta, m);
  return v ? v->pdf : 0.0f;
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
  const std::optional<Refraction> r = refract(wo, glm::vec3(0.0f, 0.0f, 1.0f), eta);
  if (!r) return std::nullopt;
  s.wi = r->wt;
  if (s.wi.z * wo.z >= 0.0f) return std::nullopt;
  s.f = SampledSpectrum(T / (std::abs(s.wi.z) * sqr(r->etap)));
  s.pdf = T;
  s.transmission = true;
  s.etap = r->etap;
  if (!finitePositive(s.pdf) || !s.f.isFinite()) return std::nullopt;
  return s;
}

std::optional<BsdfSample> DielectricMaterial::sampleRough(const glm::vec3& wo, float uc,
                                                          glm::vec2 u, float eta,
                                                          const MicrofacetModel& m) const {
  const glm::vec3 wm = m.sampleWm(wo, u);
  const float cosOM = glm::dot(wo, wm);
  if (cosOM * wo.z <= 0.0f) return std::nullopt;  // a back-facing facet (rounding at grazing wo)
  BsdfSample s;
  if (uc < fresnelDielectric(cosOM, eta)) {
    s.wi = glm::normalize(reflect(wo, wm));
    if (s.wi.z * wo.z <= 0.0f) return std::nullopt;
  } else {
    const std::optional<Refraction> r = refract(wo, wm, eta);
    if (!r) return std::nullopt;
    s.wi = glm::normalize(r->wt);
    if (s.wi.z * wo.z >= 0.0f) return std::nullopt;
    s.transmission = true;
    s.etap = r->etap;
  }
  // f and pdf from (wo, wi) exactly as f() and pdf() compute them, so the three agree to
  // the last bit (MIS relies on it), also where they are ill-conditioned (V-groove G at
  // near-vertical facets, Fresnel near the critical angle).
  const std::optional<RoughValue> v = evaluateRough(wo, s.wi, eta, m);
  if (!v || !finitePositive(v->pdf) || !std::isfinite(v->f)) return std::nullopt;
  s.f = SampledSpectrum(v->f);
  s.pdf = v->pdf;
  return s;
}

SurfaceAov DielectricMaterial::aov(const SampledWavelengths&, const BsdfContext& ctx) const {
  return {SampledSpectrum(1.0f), roughness_->evaluate(ctx.uv)};
}

}  // namespace camsim
