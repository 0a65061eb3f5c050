// Material: the BSDF at a surface point, in the local shading frame (z = shading normal),
// following Nori's plain interface. Directions are unit vectors pointing away from the
// surface: wo towards the viewer, wi towards the light.
//   f(wo, wi, λ)   BSDF value, sr⁻¹
//   sample(...)    draws wi ∝ (approximately) f·|cos θi|, returns f, pdf (sr⁻¹)
//   pdf(wo, wi)    density of sample() producing wi
#pragma once

#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sensor/sampled_spectrum.h"

namespace camsim {

struct BsdfSample {
  SampledSpectrum f;
  glm::vec3 wi{0.0f};
  float pdf = 0.0f;
};

class Material {
 public:
  virtual ~Material() = default;
  virtual SampledSpectrum f(const glm::vec3& wo, const glm::vec3& wi,
                            const SampledWavelengths& lambda) const = 0;
  virtual std::optional<BsdfSample> sample(const glm::vec3& wo, float uc, glm::vec2 u,
                                           const SampledWavelengths& lambda) const = 0;
  virtual float pdf(const glm::vec3& wo, const glm::vec3& wi) const = 0;
  // False for a material that reflects nothing (lets the integrator stop a path).
  virtual bool reflects() const { return true; }
};

}  // namespace camsim
