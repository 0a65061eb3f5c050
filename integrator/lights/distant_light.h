// DistantLight: the sun — light from one direction (angular diameter 0, a delta light) or
// from a uniform disc of angular radius α (a light at infinity).
//
// | parameter        | unit        | default | meaning |
// |------------------|-------------|---------|---------|
// | irradiance       | W·m⁻²·nm⁻¹  | —       | E(λ) on a plane facing the light |
// | direction        | —           | —       | unit direction the light travels (from the sun) |
// | angular diameter | rad         | 0       | 2α, apparent diameter of the disc; < π |
//
//   α = 0:  delta direction; sample() returns E⊥ = E(λ) along wi = −direction.
//   α > 0:  radiance L(λ) = E(λ) / (π sin²α) inside the cone of half-angle α around
//           −direction, 0 outside; then ∫_cone L cos θ dω = L π sin²α = E exactly for a
//           plane facing the light (and E cos z for a plane tilted by z, while the disc is
//           above its horizon). Sampled uniformly in the cone: pdf = 1/(2π(1 − cos α)).
//   Φ = π r² ∫ E dλ  (W through a disc of the scene's bounding radius r)
#pragma once

#include "integrator/geometry/math.h"
#include "integrator/lights/light.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

class DistantLight final : public Light {
 public:
  DistantLight(const Spectrum& irradiance, const glm::vec3& direction, float angularDiameter);

  std::optional<LightSample> sample(const glm::vec3& ref, double time, float u1, glm::vec2 u2,
                                    const SampledWavelengths& lambda) const override;
  double power() const override;
  bool isDelta() const override { return delta_; }
  bool isInfinite() const override { return true; }
  SampledSpectrum Le(const glm::vec3& direction, const SampledWavelengths& lambda) const override;
  float pdfDirection(const glm::vec3& direction) const override;
  void setSceneBounds(const glm::vec3& centre, float radius) override;

  // The disc's radiance per unit irradiance, 1/(π sin²α) (sr⁻¹); 0 for a delta light.
  double radiancePerIrradiance() const { return radiancePerIrradiance_; }

 private:
  bool inCone(const glm::vec3& d) const;

  Spectrum irradiance_;
  glm::vec3 toLight_;  // −direction
  Frame frame_;        // z = toLight_
  bool delta_;
  double oneMinusCosAlpha_ = 0.0;  // 1 − cos α, without cancellation
  float sin2Alpha_ = 0.0f;
  float conePdf_ = 0.0f;  // 1/(2π(1 − cos α))
  double radiancePerIrradiance_ = 0.0;
  float sceneRadius_ = 0.0f;
};

}  // namespace camsim
