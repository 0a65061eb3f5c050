// Material: the BSDF at a surface point, in the local shading frame (z = shading normal,
// pointing to the surface's front, i.e. outside for closed shapes), following Nori's plain
// interface. Directions are unit vectors pointing away from the surface: wo towards the
// viewer, wi towards the light. Transmission means wi and wo on opposite sides (wi.z·wo.z < 0).
//   f(wo, wi, λ, ctx)     BSDF value, sr⁻¹ (0 for delta lobes: they are only sampled)
//   sample(...)           draws wi ∝ (approximately) f·|cos θi|, returns f, pdf
//   pdf(wo, wi, λ, ctx)   density of sample() producing wi (sr⁻¹; 0 for delta lobes)
// Radiance transport: a transmitted path's f carries the 1/η² factor of radiance
// crossing an interface (η = ηt/ηi), so L/n² is invariant along a refracted ray.
//
// Dispersive materials (η depends on λ) scatter each wavelength differently: before
// using them the integrator calls lambda.terminateSecondary(), and the material then
// evaluates η at the hero wavelength lambda[0] only.
#pragma once

#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sensor/spectra/sampled_spectrum.h"

namespace camsim {

// What a material may look up besides the directions: texture coordinates.
struct BsdfContext {
  glm::vec2 uv{0.0f};
};

struct BsdfSample {
  SampledSpectrum f;  // BSDF value, sr⁻¹; for a delta lobe: the lobe's weight / |cos θi|
  glm::vec3 wi{0.0f};
  float pdf = 0.0f;       // sr⁻¹; for a delta lobe: the probability of choosing the lobe
  bool specular = false;  // delta lobe (mirror, smooth glass): no MIS with light sampling
  bool transmission = false;
  // Relative index of refraction η_t/η_i crossed by a transmission (1 for a reflection):
  // radiance along the path scales by 1/etap² there, which the path's Russian roulette
  // undoes (pbrt-v4's etaScale) so that paths inside glass are not killed for it.
  float etap = 1.0f;
};

// What a first hit reports as ground truth (integrator/render/aov_film.h): the reflectance
// the surface shows at λ — a diffuse or plastic surface's ρ, a mirror's ρ, a metal's
// normal-incidence Fresnel reflectance F(0), 1 for (lossless) glass — and its roughness α
// as the scene gives it (diffuse 1; a mirror 0).
struct SurfaceAov {
  SampledSpectrum albedo;
  float roughness = 0.0f;
};

class Material {
 public:
  virtual ~Material() = default;
  virtual SampledSpectrum f(const glm::vec3& wo, const glm::vec3& wi,
                            const SampledWavelengths& lambda, const BsdfContext& ctx) const = 0;
  virtual std::optional<BsdfSample> sample(const glm::vec3& wo, float uc, glm::vec2 u,
                                           const SampledWavelengths& lambda,
                                           const BsdfContext& ctx) const = 0;
  virtual float pdf(const glm::vec3& wo, const glm::vec3& wi, const SampledWavelengths& lambda,
                    const BsdfContext& ctx) const = 0;
  virtual SurfaceAov aov(const SampledWavelengths& lambda, const BsdfContext& ctx) const = 0;
  // What the path loop asks at every bounce, fixed when the material is made (plain
  // members, not virtual calls).
  // False for a material that reflects nothing (lets the integrator stop a path).
  bool reflects() const { return traits_.reflects; }
  // False when every lobe is a delta (mirror, smooth glass): light sampling is skipped.
  bool hasNonSpecular() const { return traits_.nonSpecular; }
  // True when η depends on wavelength (see above).
  bool dispersive() const { return traits_.dispersive; }

 protected:
  struct Traits {
    bool reflects = true;
    bool nonSpecular = true;
    bool dispersive = false;
  };
  Traits traits_;  // set by the constructors of the materials
};

}  // namespace camsim
