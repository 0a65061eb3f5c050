// AreaLight: a shape that emits.
//
// | parameter | unit             | default |
// |-----------|------------------|---------|
// | radiance  | W·m⁻²·sr⁻¹·nm⁻¹  | —       |  L_e(λ), uniform over the surface (Lambertian)
// | two_sided | —                | false   |  one-sided lights emit on the normal's side
//
//   L(p, ω) = L_e(λ) if ω is on the emitting side of n, else 0
//   Φ = π · A · ∫ L_e dλ · (2 if two-sided)
// A one-sided planar emitter (a lamp quad) rejects a reference point behind its plane
// before sampling a point on it (FrontPlane, shape.h): the sample would have L = 0. Same
// images; in the Cornell box a sixth of the light samples (points on the ceiling).
//
// The spectral control variate (integrator/render/spectral_control_variate.h) writes the
// path's light as B(λ)·E(λ), E the scene's reference emission: this light's bins hold
// ∫_bin L_e dλ / ∫_bin E dλ (1 in every bin for the reference light itself).
#pragma once

#include <optional>

#include "integrator/lights/light.h"
#include "sensor/spectra/spectral_bins.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

class AreaLight final : public Light {
 public:
  AreaLight(const Shape& shape, Spectrum radiance, bool twoSided);

  // Radiance leaving the light point along w (unit, away from the surface).
  SampledSpectrum L(const SurfaceInteraction& onLight, const glm::vec3& w,
                    const SampledWavelengths& lambda) const {
    if (!emitsTowards(onLight, w)) return SampledSpectrum(0.0f);
    return sampleSpectrum(radiance_, lambda);
  }
  // Whether the light point emits along w at all (whatever the wavelength).
  bool emitsTowards(const SurfaceInteraction& onLight, const glm::vec3& w) const {
    return twoSided_ || glm::dot(onLight.n, w) > 0.0f;
  }
  const Spectrum& radiance() const { return radiance_; }
  // Sets the bins above against the reference emission E, given as E's bin averages
  // (binAverages; W·m⁻²·sr⁻¹·nm⁻¹, any scale).
  void setControlVariateReference(const SpectralBins& referenceAverages);
  const SpectralBins* controlVariateBins() const override { return cvBins_ ? &*cvBins_ : nullptr; }

  std::optional<LightSample> sample(const glm::vec3& ref, double time, float u1, glm::vec2 u2,
                                    const SampledWavelengths& lambda) const override;
  float pdf(const glm::vec3& ref, const SurfaceInteraction& onLight) const override;
  double power() const override;

 private:
  const Shape& shape_;
  Spectrum radiance_;
  bool twoSided_;
  std::optional<FrontPlane> front_;  // one-sided planar emitters: skip points behind
  std::optional<SpectralBins> cvBins_;
};

}  // namespace camsim
