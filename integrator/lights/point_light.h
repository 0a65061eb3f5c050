// PointLight: an isotropic point source.
//
// | parameter | unit         | default | meaning |
// |-----------|--------------|---------|---------|
// | position  | m            | —       | p_l |
// | intensity | W·sr⁻¹·nm⁻¹  | —       | I(λ), the same in every direction |
//
//   irradiance at x, normal to the direction to the light:  E⊥(λ) = I(λ) / |p_l − x|²
//   (a surface with normal n receives E⊥ · |cos θ|; sample() returns E⊥ as a delta light)
//   Φ = 4π ∫ I(λ) dλ   (W, 360–830 nm)
#pragma once

#include "integrator/lights/light.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

class PointLight final : public Light {
 public:
  PointLight(const glm::vec3& position, const Spectrum& intensity);

  std::optional<LightSample> sample(const glm::vec3& ref, double time, float u1, glm::vec2 u2,
                                    const SampledWavelengths& lambda) const override;
  double power() const override;
  bool isDelta() const override { return true; }

  const glm::vec3& position() const { return position_; }

 private:
  glm::vec3 position_;
  Spectrum intensity_;
};

// The light point of a delta light at p (no surface: zero normal and error bound), for the
// shadow ray, which then ends exactly at p.
SurfaceInteraction deltaLightPoint(const glm::vec3& p, double time);

}  // namespace camsim
