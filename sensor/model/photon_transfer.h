// Photon transfer: the EMVA 1288 characterisation (Release 4.0 Linear) of a simulated sensor.
//
// Measurement: uniform monochromatic light at λ₀ on a region of photosites, photons per pixel
// μ_p = E·A·t_exp·λ₀/(hc) (A = pitch², the whole pixel: the fill factor is part of η)
// stepped from dark to beyond saturation; two frames per step (distinct frame indices), a
// stack of L dark frames and a stack of L frames at 50 % saturation. Expected electrons per
// photosite are η_c(λ₀)·μ_p (η_c = fill factor · QE of its CFA channel c), fed through
// expose() at the ISO of PtcOptions (base ISO by default). A CFA sensor is analysed on the photosites of the channel with the
// highest QE at λ₀ (G at 550 nm for a Bayer sensor); the others are exposed but not used.
//
// Analysis (EMVA 1288 Release 4.0 Linear), all per analysed photosite set:
//   μ_y = ½(μ_A + μ_B),  σ²_y = 1/(2N)·Σ[(y_A − μ_A) − (y_B − μ_B)]²   (two-frame difference)
//   μ_y.dark, σ²_y.dark from the dark stack (mean, mean per-pixel temporal variance)
//   saturation: μ_p.sat at the maximum of σ²_y;  fit range: μ_y − μ_y.dark ≤ 70 % of the
//   value at saturation
//   K: least squares through the origin of σ²_y − σ²_y.dark against μ_y − μ_y.dark
//   R: least squares through the origin of μ_y − μ_y.dark against μ_p;  η = R/K
//   σ_d = √(σ²_y.dark − σ²_q)/K, σ²_q = 1/12 DN² (σ²_y.dark < 0.24 DN² is raised to 0.24:
//   below that the quantiser hides the dark noise)
//   μ_e.sat = η·μ_p.sat;  SNR_max = √μ_e.sat.  The variance peaks before the mean clips:
//   a photosite's clipped-normal variance falls once the clip is ~3 shot-noise σ away
//   (μ_e.sat ≈ c − 3·√c for a clip at c e⁻, 4 % low at c = 5000), so the configured
//   clip is compared with μ_e.clip = (max μ_y − μ_y.dark)/K, and μ_e.sat with the maximum
//   of the variance the configuration implies (PtcConfigured::muESatEmva)
//   μ_p.min = (½ + √(¼ + σ²_y.dark/K²))/η   (SNR = 1, exact solution of the linear model)
//   DR = μ_p.sat/μ_p.min
//   s²_y = s²_y.measured − σ²_y.stack/L (spatial variance of the L-frame mean minus the
//   temporal part left in it);  DSNU₁₂₈₈ = s_y.dark/K [e⁻];
//   PRNU₁₂₈₈ = √(s²_y.50 − s²_y.dark)/(μ_y.50 − μ_y.dark) [%]
//   LE: fit μ_y − μ_y.dark = a·μ_p + b minimising the relative deviations over 5–95 % of
//   saturation; δ = (y − fit)/fit; LE = (max δ − min δ)/2 [%]
// Beyond EMVA: the dark stack's row noise and read-noise shape (dark_frame_analysis.h);
// standard errors of every quantity (ptc_statistics.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sensor/model/dark_frame_analysis.h"
#include "sensor/model/raw_image.h"
#include "sensor/model/sensor_spec.h"

namespace camsim {

inline constexpr double kPtcQuantisationVarDn2 = 1.0 / 12.0;  // σ²_q, DN²
inline constexpr double kPtcMinDarkVarDn2 = 0.24;  // EMVA: lower limit of σ²_y.dark, DN²

struct PtcOptions {
  double wavelengthNm = 550.0;         // λ₀
  int width = 256, height = 256;       // region of photosites exposed
  int levels = 60;                     // irradiation steps (≥ 50), dark excluded
  double maxSaturationFraction = 1.4;  // last step, relative to the nominal saturation
  int spatialFrames = 16;              // L: frames averaged for DSNU and PRNU
  double exposureTimeS = 0.01;
  double iso = 0.0;        // ISO setting; 0: the sensor's base ISO
  std::uint64_t seed = 1;  // noise seed
  int threads = 0;         // 0: all cores (the result does not depend on it)
};

// One irradiation step.
struct PtcLevel {
  double muP = 0.0;            // photons per pixel
  double muY = 0.0;            // DN, mean of the two frames
  double varY = 0.0;           // DN², temporal variance from the two-frame difference
  double snr = 0.0;            // (μ_y − μ_y.dark)/σ_y
  double irradianceWm2 = 0.0;  // E at λ₀: μ_p = E·A·t_exp·λ₀/(hc)
};

// What the measurement hands to the analysis.
struct PtcMeasurements {
  std::vector<PtcLevel> levels;  // increasing μ_p
  double muYDark = 0.0, varYDark = 0.0;
  int spatialFrames = 1;                            // L
  double darkSpatialVar = 0.0, darkStackVar = 0.0;  // s²_y.measured.dark, σ²_y.stack.dark
  double brightMuY = 0.0, brightSpatialVar = 0.0, brightStackVar = 0.0;  // at 50 % saturation
  DarkFrameAnalysis dark;  // row noise and read-noise shape of the dark stack
  std::size_t pixels = 0;  // N: analysed photosites per frame
  std::size_t rows = 0;    // H: rows holding them
};

struct PtcResult {
  PtcMeasurements data;
  // The set-up (filled by measurePhotonTransfer).
  std::string channel;  // analysed CFA channel
  double wavelengthNm = 0.0, exposureTimeS = 0.0, iso = 0.0;
  std::size_t pixels = 0;  // analysed photosites per frame
  // EMVA 1288 results.
  double systemGainK = 0.0;        // DN/e⁻
  double responsivityR = 0.0;      // DN/photon
  double quantumEfficiency = 0.0;  // η, e⁻/photon
  double sigmaYDark = 0.0;         // DN
  double darkNoiseE = 0.0;         // σ_d, e⁻
  double muPSat = 0.0, muESat = 0.0;
  double muEClip = 0.0;  // (max μ_y − μ_y.dark)/K: where the output clips (not EMVA's μ_e.sat)
  double snrMax = 0.0, snrMaxDb = 0.0;
  double muPMin = 0.0, muEMin = 0.0;
  double dynamicRange = 0.0, dynamicRangeDb = 0.0;
  double dsnuE = 0.0, prnuPercent = 0.0;
  double linearityErrorPercent = 0.0;
  int saturationIndex = 0;  // into data.levels
  int gainFitCount = 0;     // levels 0 … gainFitCount−1 are the 0–70 % fit range
};

// What the sensor's configuration implies for the same quantities, for comparison.
struct PtcConfigured {
  std::string channel;
  double iso = 0.0;
  bool highConversionGain = false;
  double systemGainK = 0.0;        // noiseAtIso(iso).systemGainK
  double quantumEfficiency = 0.0;  // fill factor · QE_c(λ₀)
  double darkNoiseE = 0.0;  // √(σ_pre² + μ_d + (σ_R² + σ_row²)/K²): all temporal dark noise
  double darkVarianceDn2 = 0.0;  // σ²_y.dark = K²(σ_pre² + μ_d) + σ_R² + σ_row² + 1/12
  double readPreE = 0.0;         // σ_pre (e⁻) at the ISO
  double readPreDarkE = 0.0;     // √(σ_pre² + μ_d): what the σ_pre/σ_post split measures
  double readPostDn = 0.0;       // σ_R: std of the after-gain read noise (Gaussian or Tukey-λ)
  double rowNoiseDn = 0.0;       // temporal σ_row
  double readGaussianDn = 0.0;  // √(K²(σ_pre² + μ_d + dsnu²) + σ_R² + 1/12): the residuals' std
  bool tukey = false;           // read_noise_shape tukey_lambda
  double tukeyLambda = 0.0, tukeyScaleDn = 0.0;
  double muESat = 0.0;      // saturationElectrons(iso): where the output clips
  double muESatEmva = 0.0;  // where the temporal variance peaks, below the clip
  double muPMin = 0.0, dynamicRangeDb = 0.0, snrMaxDb = 0.0;
  // √(dsnu² + row² + column² + the analysed channel's black offsets' variance / K²)
  double dsnuE = 0.0;
  double prnuPercent = 0.0;
};

// The EMVA analysis of measured statistics (pure; used on synthetic data by the tests).
PtcResult analysePhotonTransfer(const PtcMeasurements& data);

// Simulates the measurement on `sensor` and analyses it. InputError for a sensor that
// cannot be characterised (noiseless, no QE at λ₀).
PtcResult measurePhotonTransfer(const SensorSpec& sensor, const PtcOptions& options);

// At the ISO of the options (photon_transfer_configured.cpp has the table).
PtcConfigured configuredPhotonTransfer(const SensorSpec& sensor, const PtcOptions& options);

// The share of dark photosites the configuration reads at 0 DN: Φ(−(black + K μ_d) / σ), σ
// the dark signal's temporal and spatial spread in DN (Gaussian). EMVA 1288 needs an
// unclipped dark signal: above about 1e-3 the gain, dark noise and DSNU are biased (found by
// probing: smartphone-1.4um at ISO 3200, a 64 DN pedestal 1.25 σ of the dark noise, 11 % at
// 0 DN, K 14 % and σ_d 20 % off).
double darkClippedFraction(const PtcConfigured& c, const SensorSpec& sensor,
                           const PtcOptions& options);

// The noise seed of the measurement: options.seed at the base ISO, a key derived from it and
// the ISO at any other (the ISOs of one run are independent measurements, and each ISO's
// result does not depend on which others were measured).
std::uint64_t photonTransferSeed(const SensorSpec& sensor, const PtcOptions& options);

// The ISO a measurement with `options` uses: options.iso, or the base ISO when it is 0.
double photonTransferIso(const SensorSpec& sensor, const PtcOptions& options);

// The CFA channel with the highest QE at λ (the first of equals).
int photonTransferChannel(const SensorSpec& sensor, double wavelengthNm);

// μ_y and σ²_y of two frames over the photosites `pixels` (indices into dn), EMVA's way.
struct PairStatistics {
  double mean = 0.0, variance = 0.0;
};
PairStatistics pairStatistics(const RawImage& a, const RawImage& b,
                              const std::vector<std::size_t>& pixels);

// The temporal SNR of the linear model: η·μ_p / √(σ²_d + σ²_q/K² + η·μ_p).
double modelSnr(double muP, double eta, double darkNoiseE, double systemGainK);

}  // namespace camsim
