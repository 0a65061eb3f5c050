// DNG output of a RawImage: the raw digital numbers as an Adobe DNG 1.4 file (readable by
// DNG 1.1 readers) that raw converters (LibRaw/dcraw, darktable, RawTherapee, Lightroom)
// develop like a camera raw. libtiff is included here, in the dark-frame reader
// (dark_frame_reader.h) and in tiff_file.cpp, which opens files for both; in no header.
//
// File layout: one IFD (IFD0, NewSubFileType 0) holding the whole raw image, uncompressed
// 16-bit, one strip per few rows.
//   Bayer:  PhotometricInterpretation CFA (32803), CFARepeatPatternDim = tile (rows, cols),
//           CFAPattern = tile codes (0 = R, 1 = G, 2 = B), CFAPlaneColor = {0, 1, 2},
//           CFALayout 1 (rectangular), ColorMatrix1 + CalibrationIlluminant1 (and a
//           second pair when the white balance used another illuminant), AsShotNeutral.
//   Mono:   PhotometricInterpretation LinearRaw (34892), 1 sample, no CFA or colour tags.
//   Both:   BlackLevel (BlackLevelRepeatDim 1×1), WhiteLevel, DNGVersion 1.4.0.0,
//           DNGBackwardVersion 1.1.0.0, Make "camsim", Model / UniqueCameraModel
//           "camsim <sensor>", Orientation 1, Software "camsim <version>",
//           BaselineExposure, NoiseProfile (when DngCapture has one),
//           ImageDescription = the metadata as "key: value" lines; an EXIF IFD with
//           ExposureTime, FNumber, FocalLength, ISOSpeedRatings, DateTimeOriginal and
//           ExposureBiasValue (DngCapture: each omitted when 0, empty or unset).
// The sensor name is the value of the metadata key "camsim:sensor" (omitted if absent).
//
// Colour (DNG 1.4 spec, chapter 6): ColorMatrixN maps XYZ — of a scene lit by calibration
// illuminant N, white Y = 1 — to camera RGB (rows in R, G, B order, whatever the
// CfaLayout's channel order), scaled so that that illuminant's white maps to a camera value
// whose largest component is 1; a reader interpolates between the two by the colour
// temperature of AsShotNeutral. AsShotNeutral is the camera RGB of the scene white,
// normalised so that its largest component is 1 (the DNG SDK's camera-white convention;
// G = 1 whenever G is the largest, as for a Bayer sensor in daylight; a raw converter
// divides by it to white-balance, so the scale does not change the picture): it must be
// the white balance the scene was developed with (1/g of the ISP's gains), so that dcraw
// -w or LibRaw develop the same greys as camsim's own ISP.
//
// Noise (DNG 1.3+, NoiseProfile, tag 51041, DOUBLE): the temporal noise of a raw value
// normalised as a reader does, x = (DN − BlackLevel) / (WhiteLevel − BlackLevel) ∈ [0, 1],
// is N(x) = √(S·x + O). camsim writes one (S, O) pair per colour plane (count 2·ColorPlanes:
// 6 for R, G, B; 2 for mono), the same pair for each: the sensor model's gain and read noise
// belong to the photosite, not to its filter. dngNoiseProfile() takes them from the sensor
// model at the frame's ISO.
//
// BaselineExposure (tag 50730, SRATIONAL, EV) is what a reader adds to its exposure so that
// the camera's normal exposure renders at normal brightness. camsim's ISP maps the
// normalised raw to scene-linear × 1 (isp_pipeline.h, step 5: values are fractions of
// saturation, auto-exposure puts its target there), which is a raw converter's own
// convention: 0 EV, so that a raw converter renders the DNG as bright as NAME_acescg.exr.
// A bracket's offset is not a baseline: it goes in EXIF ExposureBiasValue, as cameras
// write it for auto-exposure bracketing (a BaselineExposure of −EV would undo the bracket).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "sensor/base/image.h"
#include "sensor/model/raw_image.h"
#include "sensor/model/sensor_model.h"
#include "sensor/model/sensor_spec.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

struct DngCalibration {
  glm::dmat3 xyzToCamera{1.0};  // ColorMatrixN: XYZ lit by the illuminant → camera R, G, B
  int lightSource = 21;         // CalibrationIlluminantN, EXIF LightSource code (21 = D65)
};

struct DngColor {
  DngCalibration calibration1;                 // ColorMatrix1, CalibrationIlluminant1
  std::optional<DngCalibration> calibration2;  // ColorMatrix2, CalibrationIlluminant2
  glm::dvec3 asShotNeutral{1.0};  // camera R, G, B of the scene white (written with max 1)
};

// The EXIF LightSource code of a CIE illuminant name (camsim's cieIlluminant names): D50 23,
// D55 20, D65 21, D75 22, A 17, and the F series by its class (F1 F5 F7 daylight
// fluorescent 12, F8 F10 day white 13, F2 F6 F9 F11 cool white 14, F3 white 15, F4 F12
// warm white 16); 0 when EXIF has none (ACES_D60).
int exifLightSource(const std::string& cieIlluminantName);

// DNG NoiseProfile: variance of the normalised raw value x (see above), S·x + O.
struct DngNoiseProfile {
  double scale = 0.0;   // S, variance per unit of x (> 0)
  double offset = 0.0;  // O, variance at x = 0 (≥ 0)
};

// The largest value an EXIF RATIONAL (two 32-bit unsigned integers) holds: ExposureTime,
// FNumber and FocalLength above it are written as 4294967295/0 (infinite) by libtiff.
inline constexpr double kDngMaxRational = 4294967295.0;

// What a camera records of the shot: the EXIF IFD (a value of 0, an empty date or an unset
// optional is omitted), BaselineExposure (always written) and NoiseProfile (when set).
struct DngCapture {
  double exposureTimeS = 0.0;            // ExposureTime, s (≤ kDngMaxRational)
  double fNumber = 0.0;                  // FNumber (≤ kDngMaxRational)
  double focalLengthMm = 0.0;            // FocalLength, mm (≤ kDngMaxRational)
  double iso = 0.0;                      // ISOSpeedRatings (rounded; ≥ 65535: 65535 and ISOSpeed)
  std::string dateTimeOriginal;          // DateTimeOriginal, "YYYY:MM:DD HH:MM:SS"
  std::optional<double> exposureBiasEv;  // ExposureBiasValue, EV (a bracket's offset)
  double baselineExposureEv = 0.0;       // BaselineExposure, EV
  std::optional<DngNoiseProfile> noiseProfile;  // NoiseProfile, one pair for every plane
};

// The NoiseProfile of a frame that expose(…, spec, settings, mode, …) makes: the sensor
// model's temporal variance line at the frame's ISO (exposedVarianceLine, sensor_model.h:
// σ² = slopeDn·(μ − black) + offsetDn2, in DN) in the DNG's normalised units, with
// r = white level − black level:
//
//   S = slopeDn / r = K / r,    O = offsetDn2 / r² = (K²σ_pre² + σ_R² + σ_row²) / r²
//
// Like that line it leaves out what is not temporal (PRNU, DSNU, FPN, black offsets, hot
// and stuck photosites) and the ADC's rounding (1/12 DN², O += 1/(12 r²) if wanted).
// Mode photon draws shot noise only: O = 0. Mode none, or a noiseless sensor, draws no
// noise: nullopt (the DNG requires S > 0, so the tag is omitted); so does a sensor whose
// dark frames carry the signal-independent noise. Throws InputError as
// temporalVarianceLine does (an ISO ≤ 0 or outside the sensor's iso_table).
std::optional<DngNoiseProfile> dngNoiseProfile(const SensorSpec& spec,
                                               const ExposureSettings& settings, NoiseMode mode);

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
// with D65 replaced by the calibration illuminant for its matrix. The calibrations are the
// scene illuminant I (calibration1) and D65 (calibration2), or D65 alone when I is D65 or
// has no EXIF code. The neutral is the camera's response to the perfect white under I,
//
//   w_k = Σ_λ QE_k(λ) · I(λ) · λ,   asShotNeutral = w / max_k w_k
//
// which is 1/g of the ISP's illuminant white balance up to scale; a region or grey-world balance
// sets asShotNeutral from its own gains (dngNeutralFromGains).
//
// Note the λ factor: a sensor whose QE is exactly x̄ȳz̄ counts photons, not energy, so its
// matrix is only approximately the identity; QE_k = cmf_k(λ) · λ₀/λ gives exactly XYZ.
// Throws InputError if qe does not hold 3 curves or the CSV cannot be read.
DngColor dngColorFromQe(const std::vector<Spectrum>& qe, const std::string& illuminant,
                        const std::filesystem::path& colorCheckerCsv);

// AsShotNeutral from white-balance gains g_k = w_G / w_k (R, G, B): 1/g, scaled to max 1.
glm::dvec3 dngNeutralFromGains(const std::vector<double>& gains);

// Writes raw as a DNG (see above). color is ignored for a monochrome CfaLayout.
// Throws InputError for a CFA with channels other than R, G, B, and std::runtime_error
// (with libtiff's message) if the file cannot be written.
void writeDng(const std::filesystem::path& path, const RawImage& raw, const DngColor& color,
              const Metadata& meta, const DngCapture& capture = {});

}  // namespace camsim
