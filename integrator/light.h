// Light: a source of radiance the integrator samples directly (next-event estimation).
// This version has area lights; point, spot, sun and environment lights come later
// through the same interface.
//   sample(ref, t, …) a point on the light at time t as seen from ref: incident radiance Li
//                   (W·m⁻²·sr⁻¹·nm⁻¹), direction wi (unit, towards the light), its
//                   solid-angle pdf (sr⁻¹) and the point (for the shadow ray)
//   pdf(ref, p)     solid-angle density of sample() producing the light point p
//   power()         Φ = ∫∫∫ L cosθ dA dω dλ (W), for choosing lights in proportion
#pragma once

#include <optional>

#include <glm/vec2.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "integrator/shape.h"
#include "sensor/sampled_spectrum.h"

namespace camsim {

struct LightSample {
  SampledSpectrum L;
  glm::vec3 wi{0.0f};
  float pdf = 0.0f;
  SurfaceInteraction point;
};

class Light {
 public:
  virtual ~Light() = default;
  virtual std::optional<LightSample> sample(const glm::vec3& ref, float time, float u1, glm::vec2 u2,
                                            const SampledWavelengths& lambda) const = 0;
  virtual float pdf(const glm::vec3& ref, const SurfaceInteraction& onLight) const = 0;
  virtual double power() const = 0;
};

}  // namespace camsim
