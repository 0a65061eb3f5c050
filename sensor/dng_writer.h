// DNG output of a RawImage: the raw digital numbers as an Adobe DNG 1.4 file (readable by
// DNG 1.1 readers) that raw converters (LibRaw/dcraw, darktable, RawTherapee, Lightroom)
// develop like a camera raw. This module is the only one that includes libtiff.
//
// File layout: one IFD (IFD0, NewSubFileType 0) holding the whole raw image, uncompressed
// 16-bit, one strip per few rows.
//   Bayer:  PhotometricInterpretation CFA (32803), CFARepeatPatternDim = tile (rows, cols),
//           CFAPattern = tile codes (0 = R, 1 = G, 2 = B), CFAPlaneColor = {0, 1, 2},
//           CFALayout 1 (rectangular), ColorMatrix1 + CalibrationIlluminant1 = 21 (D65),
//           AsShotNeutral.
//   Mono:   PhotometricInterpretation LinearRaw (34892), 1 sample, no CFA or colour tags.
//   Both:   BlackLevel (BlackLevelRepeatDim 1×1), WhiteLevel, DNGVersion 1.4.0.0,
//           DNGBackwardVersion 1.1.0.0, Make "camsim", Model / UniqueCameraModel
//           "camsim <sensor>", Orientation 1, Software "camsim <version>",
//           ImageDescription = the metadata as "key: value" lines.
// The sensor name is the value of the metadata key "camsim:sensor" (omitted if absent).
//
// Colour (DNG 1.4 spec, chapter 6): ColorMatrix1 maps XYZ — of a scene lit by the
// calibration illuminant D65, white Y = 1 — to camera RGB (rows in R, G, B order, whatever
// the CfaLayout's channel order), scaled so that the D65 white maps to a camera value
// whose largest component is 1. AsShotNeutral is the camera RGB of the scene white,
// normalised so that G = 1 (a raw converter divides by it to white-balance).
#pragma once

#include <filesystem>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "sensor/image.h"
#include "sensor/raw_image.h"
#include "sensor/spectrum.h"

namespace camsim {

struct DngColor {
  glm::dmat3 xyzToCamera{1.0};    // ColorMatrix1: D65-lit XYZ → camera R, G, B
  glm::dvec3 asShotNeutral{1.0};  // camera R, G, B of the scene white, G = 1
};

// The DNG colour of a sensor from its absolute QE curves (R, G, B order), by least
// squares over the 24 patches of the ColorChecker Classic (reflectances R_p(λ) read from
// colorCheckerCsv, normally CAMSIM_LUTS_DIR "/spectra/colorchecker_classic_reflectance.csv",
// held constant beyond the table's range):
//
//   camera response  c_p,k = Σ_λ QE_k(λ) · R_p(λ) · D65(λ) · λ      (photo-electrons ∝ energy·λ)
//   colorimetry      X_p   = Σ_λ cmf(λ) · R_p(λ) · D65(λ) / Σ_λ ȳ(λ) · D65(λ)
//   M  = argmin Σ_p ‖M X_p − c_p‖² = (Σ_p c_p X_pᵀ) (Σ_p X_p X_pᵀ)⁻¹
//   xyzToCamera = M / max_k (M · X_D65)_k,   X_D65 = XYZ of the D65 white with Y = 1
//
// The fit always uses D65 because the writer declares CalibrationIlluminant1 = D65; the
// scene illuminant I only sets the white balance:
//
//   w_k = Σ_λ QE_k(λ) · I(λ) · λ,   asShotNeutral = w / w_G
//
// Note the λ factor: a sensor whose QE is exactly x̄ȳz̄ counts photons, not energy, so its
// matrix is only approximately the identity; QE_k = cmf_k(λ) · λ₀/λ gives exactly XYZ.
// Throws InputError if qe does not hold 3 curves or the CSV cannot be read.
DngColor dngColorFromQe(const std::vector<Spectrum>& qe, const Spectrum& illuminant,
                        const std::filesystem::path& colorCheckerCsv);

// Writes raw as a DNG (see above). color is ignored for a monochrome CfaLayout.
// Throws InputError for a CFA with channels other than R, G, B, and std::runtime_error
// (with libtiff's message) if the file cannot be written.
void writeDng(const std::filesystem::path& path, const RawImage& raw, const DngColor& color,
              const Metadata& meta);

}  // namespace camsim
