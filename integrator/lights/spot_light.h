// SpotLight: a point source whose intensity falls off smoothly away from its axis
// (the falloff of pbrt-v4's spot light).
//
// | parameter     | unit         | default | meaning |
// |---------------|--------------|---------|---------|
// | position      | m            | —       | p_l |
// | axis          | —            | —       | unit direction the spot points to |
// | intensity     | W·sr⁻¹·nm⁻¹  | —       | I₀(λ), on the axis |
// | cone angle    | rad          | —       | θ_e: no light beyond this angle from the axis |
// | falloff start | rad          | —       | θ_s ≤ θ_e: full intensity inside this angle |
//
//   I(λ, θ) = I₀(λ) · smoothstep(cos θ; cos θ_e, cos θ_s)
//   smoothstep(x; a, b) = t²(3 − 2t),  t = clamp((x − a)/(b − a), 0, 1)   (a step if a = b)
//   E⊥(λ) = I(λ, θ) / d²  (the point light's sample, weighted by the falloff)
//   Φ = 2π ∫ I₀ dλ · [(1 − cos θ_s) + (cos θ_s − cos θ_e)/2]
// (exact: dω = d(cos θ) dφ and ∫ smoothstep over [cos θ_e, cos θ_s] is half the interval).
#pragma once

#include "integrator/lights/light.h"
#include "integrator/lights/point_light.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

class SpotLight final : public Light {
 public:
  SpotLight(const glm::vec3& position, const glm::vec3& axis, const Spectrum& intensity,
            float coneAngle, float falloffStart);

  std::optional<LightSample> sample(const glm::vec3& ref, double time, float u1, glm::vec2 u2,
                                    const SampledWavelengths& lambda) const override;
  double power() const override;
  bool isDelta() const override { return true; }

  // ∫ smoothstep dω over the sphere (sr): Φ = effectiveSolidAngle · ∫ I₀ dλ.
  static double effectiveSolidAngle(double coneAngle, double falloffStart);

  // The falloff factor in [0, 1] for a direction w (unit) leaving the light.
  float falloff(const glm::vec3& w) const;

 private:
  PointLight point_;  // the same source without the cone
  glm::vec3 axis_;
  double intensitySum_;  // ∫ I₀ dλ
  float cosEnd_;         // cos θ_e
  float cosStart_;       // cos θ_s
  double coneAngle_, falloffStart_;
};

}  // namespace camsim
