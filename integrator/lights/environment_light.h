// EnvironmentLight: radiance from every direction, read from a lat-long (equirectangular)
// EXR of linear Rec.709 RGB, importance sampled by texel luminance.
//
// | parameter      | unit             | default  | meaning |
// |----------------|------------------|----------|---------|
// | texels         | W·m⁻²·sr⁻¹ (Y)   | —        | R, G, B, linear Rec.709 (negatives read as 0) |
// | scale          | —                | 1        | s(λ), multiplies the uplifted spectrum |
// | worldFromLight | —                | identity | rotation, map space → world |
//
// Map space: +z is the zenith (row 0), θ from +z, φ clockwise seen from +z, from +x:
//   u = φ / 2π,  v = θ / π,  d = (sin θ cos φ, −sin θ sin φ, cos θ)
// (clockwise so that a panorama seen from inside is not mirrored). Texel (i, j) covers
// u ∈ [i, i+1)/W, v ∈ [j, j+1)/H; lookups are nearest (piecewise constant per texel), so
// sampling and evaluation agree exactly.
//
// Spectrum of a texel of colour c (Jakob–Hanika uplift, as rgbToEmissionShape):
//   L(λ) = s(λ) · k_c · S(c₀λ'² + c₁λ' + c₂) · D65(λ),  Σ k_c S(…) D65 ȳ Δλ = Y(c),
// with (c₀, c₁, c₂) from RgbEmissionTable (bilinear in a table of fits made once, never
// per lookup) and k_c fixing the luminance (to ≤ 5e-4) (Σ over 3 nm bins of the 1 nm grid):
// a texel (1, 1, 1) has L = D65 / Σ D65 ȳ, i.e. luminance 683 cd/m².
//
//   p(ω) = p(u, v) / (2π² sin θ),  p(u, v) ∝ Y(texel) · sin θ_texel centre
//   Φ = π r² ∫_Ω ∫_λ L dλ dω   (W through a disc of the scene's bounding radius r, from
//       every direction; for a uniform map 4π² r² ∫ L dλ)
#pragma once

#include <vector>

#include <glm/mat3x3.hpp>

#include "integrator/lights/light.h"
#include "integrator/lights/rgb_emission_table.h"
#include "integrator/sampling/distribution_2d.h"
#include "sensor/base/image.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

class EnvironmentLight final : public Light {
 public:
  // rgb: channels "R", "G", "B" (others ignored), finite values.
  EnvironmentLight(const Image& rgb, const Spectrum& scale, const glm::mat3& worldFromLight);

  std::optional<LightSample> sample(const glm::vec3& ref, double time, float u1, glm::vec2 u2,
                                    const SampledWavelengths& lambda) const override;
  double power() const override;
  bool isInfinite() const override { return true; }
  SampledSpectrum Le(const glm::vec3& direction, const SampledWavelengths& lambda) const override;
  float pdfDirection(const glm::vec3& direction) const override;
  void setSceneBounds(const glm::vec3& centre, float radius) override;

  int width() const { return width_; }
  int height() const { return height_; }
  // The texel's spectral radiance (scale applied), W·m⁻²·sr⁻¹·nm⁻¹.
  SampledSpectrum texelRadiance(int column, int row, const SampledWavelengths& lambda) const;

  // Map-space direction of (u, v) and back (u, v in [0, 1]).
  static glm::vec3 directionOf(glm::vec2 uv);
  static glm::vec2 uvOf(const glm::vec3& mapDirection);
  // Illuminance (lx) the map delivers at scale 1 to a plane facing the map's zenith:
  //   E_v = 683 lm/W · Σ_texels Y(texel) ∫_texel max(0, cos θ) dω.
  static double zenithIlluminance(const Image& rgb);

 private:
  struct Texel {
    SigmoidCoefficients shape;  // see rgb_emission_table.h
    float k = 0.0f;             // luminance normalisation (0: black)
  };
  const Texel& texel(int column, int row) const {
    return texels_[static_cast<size_t>(row) * static_cast<size_t>(width_) +
                   static_cast<size_t>(column)];
  }

  int width_ = 0, height_ = 0;
  std::vector<Texel> texels_;
  Spectrum illuminant_;  // D65 · scale
  glm::mat3 worldFromLight_, lightFromWorld_;
  PiecewiseConstant2D distribution_;
  double radiantIntegral_ = 0.0;  // ∫_Ω ∫_λ L dλ dω, W·m⁻²
  float sceneRadius_ = 0.0f;
};

}  // namespace camsim
