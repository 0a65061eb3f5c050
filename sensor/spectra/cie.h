// CIE 1931 2° colorimetry on the 1 nm grid.
//
//   X = Σ S(λ) x̄(λ) Δλ,  Y = Σ S(λ) ȳ(λ) Δλ,  Z = Σ S(λ) z̄(λ) Δλ   (Δλ = 1 nm)
//   photometric: luminance Lv [cd/m²] = Km · Σ L(λ) ȳ(λ) Δλ with L in W·m⁻²·sr⁻¹·nm⁻¹,
//   Km = 683 lm/W.
//   reflectance under an illuminant I, normalised so the perfect diffuser has Y = 1:
//   XYZ = Σ R I x̄ / Σ I ȳ, ...
#pragma once

#include <glm/vec3.hpp>

#include "sensor/spectra/spectrum.h"

namespace camsim {

inline constexpr double kMaxLuminousEfficacy = 683.0;  // Km, lm/W

struct Cie1931 {
  Spectrum x, y, z;
  static const Cie1931& get();  // from the embedded luts/spectra/cie1931_2deg_xyz.csv
};

// Σ S·cmf over the grid, in S's unit × nm.
glm::dvec3 spectrumToXyz(const Spectrum& s);
// Luminance in cd/m² of a spectral radiance in W·m⁻²·sr⁻¹·nm⁻¹.
double luminance(const Spectrum& spectralRadiance);
// Reflectance (or transmittance) seen under an illuminant, Y of the perfect diffuser = 1.
glm::dvec3 reflectanceToXyz(const Spectrum& reflectance, const Spectrum& illuminant);

struct Chromaticity {
  double x = 0.0, y = 0.0;
};
Chromaticity xyzToChromaticity(const glm::dvec3& xyz);
// XYZ with the given chromaticity and luminance Y.
glm::dvec3 chromaticityToXyz(Chromaticity c, double Y = 1.0);

}  // namespace camsim
