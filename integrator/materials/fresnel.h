// Fresnel reflectance of smooth interfaces (unpolarised light), in the local frame.
//
//   dielectric   η = index of the inside (−z) over the outside (+z); cosθi < 0 means the
//                light arrives from the inside: the function then swaps the media (η → 1/η).
//                R = (r∥² + r⊥²)/2,  r∥ = (η cosθi − cosθt)/(η cosθi + cosθt),
//                r⊥ = (cosθi − η cosθt)/(cosθi + η cosθt);  R = 1 beyond the critical angle
//   conductor    complex index η̃ = η + i k: the same formulas with complex arithmetic
//   Schlick      R = R0 + (1 − R0)(1 − cosθ)⁵
#pragma once

#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "sensor/base/enum_names.h"
#include "sensor/spectra/sampled_spectrum.h"

namespace camsim {

enum class FresnelModel { kExact, kSchlick };
// The scene's material `fresnel` names (sensor/base/enum_names.h).
template <>
struct EnumNames<FresnelModel> {
  static constexpr EnumName<FresnelModel> kTable[] = {{FresnelModel::kExact, "exact"},
                                                      {FresnelModel::kSchlick, "schlick"}};
};

float fresnelDielectric(float cosThetaI, float eta);
float fresnelConductor(float cosThetaI, float eta, float k);
SampledSpectrum fresnelConductor(float cosThetaI, const SampledSpectrum& eta,
                                 const SampledSpectrum& k);
SampledSpectrum fresnelSchlick(float cosThetaI, const SampledSpectrum& r0);

inline glm::vec3 reflect(const glm::vec3& wo, const glm::vec3& n) {
  return -wo + 2.0f * glm::dot(wo, n) * n;
}

// Refracts wi (pointing away from the surface) through the interface with normal n and
// relative index eta (n's side is the outside). Returns the transmitted direction and the
// relative index actually crossed (eta or 1/eta); nothing on total internal reflection.
struct Refraction {
  glm::vec3 wt;
  float etap;
};
std::optional<Refraction> refract(const glm::vec3& wi, glm::vec3 n, float eta);

}  // namespace camsim
