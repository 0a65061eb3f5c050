// Colour correction: white-balanced camera RGB → CIE XYZ (D65-adapted) → working space.
// The colour correction matrix (CCM) is fitted, never typed in: by least squares over the
// 24 patches of the ColorChecker Classic (reflectances R_p(λ)) under a chosen illuminant I,
// from the sensor's QE curves (1 nm grid, QE_k in R, G, B order):
//
//   camera        c_p,k = Σ_λ QE_k(λ) R_p(λ) I(λ) λ,   white w_k = Σ_λ QE_k(λ) I(λ) λ
//   balanced      ĉ_p,k = c_p,k / w_k           (white balance g_k = w_G / w_k, then ÷ w_G:
//                                                the perfect white becomes (1, 1, 1))
//   colorimetry   X_p = Σ cmf R_p I / Σ ȳ I     (CIE 1931 2°, the white has Y = 1)
//   adaptation    X′_p = B(I → D65) X_p
//   CCM           M = argmin Σ_p ‖M ĉ_p − X′_p‖² = (Σ_p X′_p ĉ_pᵀ)(Σ_p ĉ_p ĉ_pᵀ)⁻¹
//   optional white preservation: the same minimum subject to M (1, 1, 1)ᵀ = X_D65 (each
//     row's sum fixed: the balanced white maps exactly to the D65 white — the illuminant's
//     white after adaptation — so neutrals stay neutral), solved per row with a Lagrange
//     multiplier: M = M₀ + (X_D65 − M₀ u)(A⁻¹u)ᵀ / (uᵀA⁻¹u),  A = Σ ĉ ĉᵀ, u = (1, 1, 1)ᵀ
//   working       rgb = W M ĉ,   W = rgbFromXyz_ws · B(D65 → white_ws)   (ACEScg by default)
//
// B is the Bradford chromatic adaptation transform (sensor/spectra/color_space.h).
// Choice: the CCM outputs the colours a D65-adapted observer would match, whatever the scene
// illuminant, so that the image needs one output white (D65, then the working space's) and
// the fit's error is measured against the same corresponding colours. B(D65 → D65) is the
// identity, so a D65 fit involves no adaptation. D65 white X_D65 = the tabulated D65
// spectrum through the CIE 1931 observer, Y = 1 (xy ≈ 0.3127, 0.3290).
//
// | parameter      | unit                    | default   | meaning                           |
// |----------------|-------------------------|-----------|-----------------------------------|
// | qe             | e⁻/photon               | —         | three QE curves, R, G, B order    |
// | illuminant I   | relative spectral power | —         | scene / calibration illuminant    |
// | colorCheckerCsv| —                       | —         | reflectance table (24 columns)    |
// | preserveWhite  | —                       | true      | constrain M (1,1,1) = X_D65       |
// | workingSpace   | —                       | ACEScg    | RgbColorSpace of the output       |
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "sensor/base/image.h"
#include "sensor/spectra/color_space.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

// The chart seen by a camera under an illuminant (shared with the DNG colour fit).
struct ChartSamples {
  std::vector<glm::dvec3> camera;  // c_p (raw, unbalanced), one per patch
  std::vector<glm::dvec3> xyz;     // X_p, white Y = 1
  glm::dvec3 cameraWhite{0.0};     // w: the perfect diffuser's camera response
  glm::dvec3 xyzWhite{0.0};        // XYZ of the illuminant's white, Y = 1
};
// Reflectances are held constant beyond the table's range. Throws InputError if qe does
// not hold 3 curves or the CSV cannot be read or has fewer than 3 columns.
ChartSamples colorCheckerSamples(const std::vector<Spectrum>& qe, const Spectrum& illuminant,
                                 const std::filesystem::path& colorCheckerCsv);

// argmin_M Σ_i ‖M from_i − to_i‖² = (Σ to fromᵀ)(Σ from fromᵀ)⁻¹; InputError if singular.
glm::dmat3 fitLinearMap(const std::vector<glm::dvec3>& from, const std::vector<glm::dvec3>& to);
// The same subject to M u = target (u a fixed input, e.g. the white).
glm::dmat3 fitLinearMapConstrained(const std::vector<glm::dvec3>& from,
                                   const std::vector<glm::dvec3>& to, const glm::dvec3& u,
                                   const glm::dvec3& target);

struct ColorCorrectionOptions {
  bool preserveWhite = true;
  const RgbColorSpace* workingSpace = &RgbColorSpace::acesCg();
};

struct ColorCorrection {
  glm::dvec3 whiteBalance{1.0};  // g_k = w_G / w_k (G = 1): what white_balance.h computes
  glm::dmat3 cameraToXyz{1.0};   // the CCM M: balanced camera RGB → D65-adapted XYZ
  glm::dmat3 adaptation{1.0};    // B(I → D65), applied to the fit's targets
  glm::dmat3 xyzToWorking{1.0};  // W
  std::string workingSpace;      // W's name, e.g. "acescg"
  // Balanced camera RGB → working RGB: W · M.
  glm::dmat3 cameraToWorking() const { return xyzToWorking * cameraToXyz; }
  // Unbalanced camera RGB (divided by w_G) → XYZ: M · diag(g). For a sensor whose QE·λ is
  // the CIE observer this is the identity under D65.
  glm::dmat3 rawToXyz() const;
};

ColorCorrection fitColorCorrection(const std::vector<Spectrum>& qe, const Spectrum& illuminant,
                                   const std::filesystem::path& colorCheckerCsv,
                                   const ColorCorrectionOptions& options = {});

// The fit's residual on the chart: ΔE2000 of M ĉ_p against X′_p, both in CIELAB with the
// D65 white (Y = 1) as the reference white.
struct ChartError {
  std::vector<double> deltaE;  // per patch
  double mean = 0.0, max = 0.0;
};
ChartError colorCheckerError(const ColorCorrection& cc, const std::vector<Spectrum>& qe,
                             const Spectrum& illuminant,
                             const std::filesystem::path& colorCheckerCsv);

// out(x, y) = m · in(x, y) for a 3-channel image; the result has the given channel names.
// Throws InputError if the image does not have 3 channels.
Image applyColorMatrix(const Image& image, const glm::dmat3& m,
                       const std::vector<std::string>& outputChannels);

}  // namespace camsim
