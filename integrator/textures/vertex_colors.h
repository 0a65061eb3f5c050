// VertexColors: a mesh's per-vertex colours (glTF COLOR_0, MeshData::colors) as the
// reflectance factor they give at a hit. Each vertex's linear Rec.709 RGB (in [0, 1]) is
// uplifted once, as texels are (upliftTexels: each distinct colour fitted once), and at a
// hit on triangle k at barycentrics (b0, b1, b2) the three vertices' spectra are blended as
// texture filtering blends texels (spectra, not coefficients):
//
//   c(λ) = b0·ρ_i0(λ) + b1·ρ_i1(λ) + b2·ρ_i2(λ),  (i0, i1, i2) triangle k's vertices
//
// The material's spectral texture (reflectance, base colour, a conductor's F0) is
// multiplied by c (BsdfContext::lookup). glTF multiplies in RGB (baseColorFactor ·
// texture · COLOR_0); camsim multiplies the two uplifted reflectances, which is exact for a
// white or grey base colour and close to it otherwise. Only meshes with colours have one:
// a mesh without costs the renderer one null test per shading point.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "sensor/spectra/rgb_uplift.h"
#include "sensor/spectra/sampled_spectrum.h"

namespace camsim {

class VertexColors {
 public:
  // rgb: one per vertex; indices: 3 per triangle, as the mesh Embree traces holds them.
  VertexColors(const std::vector<glm::vec3>& rgb, std::vector<std::uint32_t> indices);

  // c(λ) at barycentrics (1 − b1 − b2, b1, b2) of a triangle (Embree's u = b1, v = b2).
  SampledSpectrum evaluate(int triangle, float b1, float b2,
                           const SampledWavelengths& lambda) const {
    const std::size_t k = 3 * static_cast<std::size_t>(triangle);
    const SigmoidCoefficients& c0 = coefficients_[indices_[k]];
    const SigmoidCoefficients& c1 = coefficients_[indices_[k + 1]];
    const SigmoidCoefficients& c2 = coefficients_[indices_[k + 2]];
    const float b0 = 1.0f - b1 - b2;
    SampledSpectrum out;
    for (int i = 0; i < kWavelengthSamples; ++i)
      out[i] = b0 * c0(lambda[i]) + b1 * c1(lambda[i]) + b2 * c2(lambda[i]);
    return out;
  }

 private:
  std::vector<SigmoidCoefficients> coefficients_;  // one per vertex
  std::vector<std::uint32_t> indices_;
};

}  // namespace camsim
