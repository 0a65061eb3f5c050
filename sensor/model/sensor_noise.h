// Gain-dependent sensor noise: what changes with the ISO setting, as the low-light raw
// denoising literature models real cameras (ELD, Wei et al. CVPR 2020 / TPAMI 2021; PMRID,
// Wang et al. ECCV 2020; LED, Jin et al. ICCV 2023). Every term is off unless the sensor
// description states it (docs/sensor-format.md, "Gain-dependent noise").
//
// | YAML key (sensor description)     | unit   | meaning |
// |-----------------------------------|--------|---------|
// | read_noise_post_dn                | DN rms | Gaussian read noise after the analog gain (output stage, ADC) |
// | dual_conversion_gain.iso          | —      | from this ISO up the pixel uses its high conversion gain |
// | dual_conversion_gain.conversion_gain_e_per_dn | e⁻/DN | 1/K at that ISO (K ∝ ISO above it) |
// | dual_conversion_gain.read_noise_e | e⁻ rms | σ_pre in the high-gain mode |
// | dual_conversion_gain.full_well_e  | e⁻     | full well in the high-gain mode (default: unchanged) |
// | iso_table                         | —      | measured rows {iso, system_gain_dn_per_e, read_noise_e, read_noise_post_dn, tukey_lambda, tukey_scale_dn, row_noise_dn, black_offsets_dn}; a column given replaces the parametric value; between rows linear in log ISO (log-log for K and the σ's); ISO outside the rows refused |
// | noise_fits.{read_noise_dn, tukey_scale_dn, row_noise_dn} | DN | ELD's log-linear fits ln σ = slope · ln K + bias (K in DN/e⁻); read_noise_dn is the whole Gaussian read noise after the gain (σ_pre = 0) |
// | read_noise_shape                  | —      | gaussian (default) or tukey_lambda: the after-gain read noise is Tukey-λ(λ, scale) instead of N(0, σ_post²) |
// | tukey_lambda                      | —      | the shape λ when the table has no column (λ = 0: logistic) |
// | row_noise_dn                      | DN rms | temporal row noise: one N(0, σ²) offset per row per frame (the fixed row_fpn_e stays) |
// | black_offsets_dn                  | DN     | mean offset from the black level per CFA tile position (row-major; ELD's colour bias) |
// | hot_pixels.{fraction, dark_current_e_per_s} | —, e⁻/s | photosites with extra dark current (at dark_reference_c, doubling like the rest) |
// | stuck_pixels.{fraction, value_dn} | —, DN  | photosites whose output is fixed |
//
// Per photosite, in DN (μ_e photo-electrons, μ_d dark electrons, K system gain):
//   y = clip(Poisson(μ_e + μ_d + μ_hot)·(1 + PRNU) + FPN + N(0, σ_pre²), full well)·K
//       + R + r_row(frame, y) + b_tile + black level,  R ~ N(0, σ_post²) or TL(λ, s)
// so that the temporal variance (without clipping, quantisation and hot pixels) is
//   σ_y² = K²(σ_pre² + μ_e + μ_d) + σ_R² + σ_row²      (docs/sensor-format.md)
// with σ_R² = σ_post² (Gaussian) or s²·v(λ) (Tukey-λ, tukeyVarianceFactor).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sensor/base/enum_names.h"

namespace camsim {

// ISO (a sensor's base ISO, its calibration rows, a capture's ISO) is at most kMaxIso; a
// capture's ISO at least kMinIso (render's --iso, expose's).
inline constexpr double kMinIso = 1.0, kMaxIso = 1e7;
// Why a capture's ISO is outside [kMinIso, kMaxIso] ("ISO 1e+12 is outside [1, 1e+07]"), or
// "" when it is inside.
std::string isoRangeProblem(double iso);

class YamlMap;
struct SensorSpec;

enum class ReadNoiseShape { kGaussian, kTukeyLambda };
template <>
struct EnumNames<ReadNoiseShape> {
  static constexpr EnumName<ReadNoiseShape> kTable[] = {
      {ReadNoiseShape::kGaussian, "gaussian"}, {ReadNoiseShape::kTukeyLambda, "tukey_lambda"}};
};

// ln σ = slope · ln K + bias (ELD's fit; σ in DN, K in DN/e⁻).
struct LogLinearFit {
  double slope = 0.0, bias = 0.0;
  double at(double systemGainK) const;
};

// One measured row of iso_table; unset columns fall back to the parametric model.
struct IsoTableRow {
  double iso = 0.0;
  std::optional<double> systemGain, readNoiseE, readNoisePostDn, tukeyLambda, tukeyScaleDn,
      rowNoiseDn;
  std::vector<double> blackOffsetsDn;  // empty: not given
};

struct DualConversionGain {
  double iso = 0.0;  // 0: no switch
  double conversionGainEPerDn = 1.0;
  double readNoiseE = 0.0;
  std::optional<double> fullWellE;
};

// The gain-dependent part of a SensorSpec (plain data, parsed with the description).
struct SensorNoiseSpec {
  double readNoisePostDn = 0.0;
  DualConversionGain dualGain;
  std::vector<IsoTableRow> isoTable;  // increasing ISO; empty: none
  std::optional<LogLinearFit> readNoiseFit, tukeyScaleFit, rowNoiseFit;
  ReadNoiseShape shape = ReadNoiseShape::kGaussian;
  double tukeyLambda = 0.14;  // ≈ Gaussian shape when no table column says otherwise
  double rowNoiseDn = 0.0;
  std::vector<double> blackOffsetsDn;  // per tile position; empty: none
  double hotPixelFraction = 0.0, hotPixelDarkCurrentEPerS = 0.0;
  double stuckPixelFraction = 0.0, stuckPixelValueDn = 0.0;
};

// Everything the sensor stage needs at one ISO setting.
struct NoiseAtIso {
  double iso = 0.0;
  double systemGainK = 0.0;  // DN/e⁻
  double fullWellE = 0.0;
  bool highConversionGain = false;
  double readPreE = 0.0;    // e⁻ rms, Gaussian, before the gain
  double readPostDn = 0.0;  // DN rms, Gaussian, after the gain (shape gaussian)
  ReadNoiseShape shape = ReadNoiseShape::kGaussian;
  double tukeyLambda = 0.0, tukeyScaleDn = 0.0;  // shape tukey_lambda
  double rowNoiseDn = 0.0;                       // temporal, per row per frame
  std::vector<double> blackOffsetsDn;            // per CFA tile position (empty: none)

  // Variance of the after-gain read term R (DN²).
  double postReadVarianceDn2() const;
  // Signal-independent temporal variance in DN² (without dark shot noise, DSNU or FPN):
  // K²σ_pre² + σ_R² + σ_row².
  double readVarianceDn2() const;
};

// The parameters at `iso`. InputError (key "iso") for an ISO ≤ 0 or outside iso_table.
NoiseAtIso noiseAtIso(const SensorSpec& sensor, double iso);

// The ISO range the sensor accepts: [first, last] row of iso_table, or (0, ∞).
struct IsoRange {
  double min = 0.0, max = 0.0;  // max 0: unbounded
};
IsoRange isoRange(const SensorSpec& sensor);

// Var[TL(λ, 1)]: 2/λ² · (1/(1+2λ) − Γ(λ+1)²/Γ(2λ+2)), π²/3 at λ = 0; λ > −½.
double tukeyVarianceFactor(double lambda);
// The Tukey-λ quantile function at u ∈ (0, 1), unit scale: (u^λ − (1−u)^λ)/λ, ln(u/(1−u)).
double tukeyQuantile(double lambda, double u);

// The noise terms a sensor models at `iso` (names as the sidecar lists them: shot,
// dark_current, hot_pixels, stuck_pixels, prnu, dsnu, row_fpn, column_fpn, read_pre,
// read_post, read_tukey_lambda, row_temporal, black_offsets, dual_conversion_gain).
std::vector<std::string> modelledNoiseTerms(const SensorSpec& sensor, double iso);

// Reads the keys above from a sensor description's top-level map (called by
// parseSensorSpec, which lists them as known); checks them against the CFA tile size.
void parseSensorNoise(YamlMap& map, SensorSpec& spec);
// The keys parseSensorNoise reads.
const std::vector<std::string>& sensorNoiseKeys();

}  // namespace camsim
