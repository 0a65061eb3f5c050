// Fresnel reflectance of smooth interfaces and Snell refraction.
//
// | parameter | unit          | default | meaning                                          |
// |-----------|---------------|---------|--------------------------------------------------|
// | cosThetaI | —             | —       | cosine of incidence w.r.t. the +z (outside) normal |
// | eta       | dimensionless | —       | index inside / outside (dielectric), real part η  |
// | k         | dimensionless | 0       | extinction coefficient of a conductor            |
// | r0        | dimensionless | —       | Schlick normal-incidence reflectance             |
//
//   r∥ = (η̃ cos θi − cos θt)/(η̃ cos θi + cos θt),  r⊥ = (cos θi − η̃ cos θt)/(cos θi + η̃ cos θt)
//   cos θt = √(1 − sin²θi / η̃²),  R = (|r∥|² + |r⊥|²)/2   (η̃ = η real, or η + i k)
//   dielectric: R = 1 once sin²θt ≥ 1 (total internal reflection); η = 1: R = 0, wt = −wi exactly
//   refraction: wt = −wi/η + (cos θi/η − cos θt) n
#include "integrator/materials/fresnel.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "integrator/geometry/math.h"

namespace camsim {

float fresnelDielectric(float cosThetaI, float eta) {
  if (eta == 1.0f) return 0.0f;  // no interface (below, 1 − cos² rounds to 1 near grazing: TIR)
  cosThetaI = std::clamp(cosThetaI, -1.0f, 1.0f);
  if (cosThetaI < 0.0f) {  // light arrives from the inside: swap the media
    eta = 1.0f / eta;
    cosThetaI = -cosThetaI;
  }
  const float sin2ThetaI = 1.0f - cosThetaI * cosThetaI;
  const float sin2ThetaT = sin2ThetaI / (eta * eta);
  if (sin2ThetaT >= 1.0f) return 1.0f;
  const float cosThetaT = safeSqrt(1.0f - sin2ThetaT);
  const float parallel = (eta * cosThetaI - cosThetaT) / (eta * cosThetaI + cosThetaT);
  const float perpendicular = (cosThetaI - eta * cosThetaT) / (cosThetaI + eta * cosThetaT);
  const float r = 0.5f * (parallel * parallel + perpendicular * perpendicular);
  return std::isfinite(r) ? r : 1.0f;
}

float fresnelConductor(float cosThetaI, float eta, float k) {
  using Complex = std::complex<float>;
  const float cosI = std::clamp(std::abs(cosThetaI), 0.0f, 1.0f);
  const Complex etaC(eta, k);
  const float sin2ThetaI = 1.0f - cosI * cosI;
  const Complex sin2ThetaT = sin2ThetaI / (etaC * etaC);
  const Complex cosThetaT = std::sqrt(Complex(1.0f) - sin2ThetaT);
  const Complex parallelDen = etaC * cosI + cosThetaT;
  const Complex perpendicularDen = Complex(cosI) + etaC * cosThetaT;
  if (std::norm(parallelDen) == 0.0f || std::norm(perpendicularDen) == 0.0f) return 1.0f;
  const Complex parallel = (etaC * cosI - cosThetaT) / parallelDen;
  const Complex perpendicular = (Complex(cosI) - etaC * cosThetaT) / perpendicularDen;
  const float r = 0.5f * (std::norm(parallel) + std::norm(perpendicular));
  return std::isfinite(r) ? std::min(r, 1.0f) : 1.0f;
}

SampledSpectrum fresnelConductor(float cosThetaI, const SampledSpectrum& eta,
                                 const SampledSpectrum& k) {
  SampledSpectrum r;
  for (int i = 0; i < kWavelengthSamples; ++i) r[i] = fresnelConductor(cosThetaI, eta[i], k[i]);
  return r;
}

SampledSpectrum fresnelSchlick(float cosThetaI, const SampledSpectrum& r0) {
  const float c = 1.0f - std::clamp(std::abs(cosThetaI), 0.0f, 1.0f);
  const float c2 = c * c;
  const float w = c2 * c2 * c;
  return r0 + (SampledSpectrum(1.0f) - r0) * w;
}

std::optional<Refraction> refract(const glm::vec3& wi, glm::vec3 n, float eta) {
  if (eta == 1.0f)
    return Refraction{-wi, 1.0f};  // index-matched: straight through, also at grazing
  float cosThetaI = std::clamp(glm::dot(n, wi), -1.0f, 1.0f);
  if (cosThetaI < 0.0f) {  // wi on the inside: the interface seen from the other side
    eta = 1.0f / eta;
    cosThetaI = -cosThetaI;
    n = -n;
  }
  const float sin2ThetaI = std::max(0.0f, 1.0f - cosThetaI * cosThetaI);
  const float sin2ThetaT = sin2ThetaI / (eta * eta);
  if (sin2ThetaT >= 1.0f) return std::nullopt;
  const float cosThetaT = safeSqrt(1.0f - sin2ThetaT);
  return Refraction{-wi / eta + (cosThetaI / eta - cosThetaT) * n, eta};
}

}  // namespace camsim
