#include "sensor/model/sensor_noise.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/base/yaml_reader.h"
#include "sensor/model/sensor_spec.h"

namespace camsim {

double LogLinearFit::at(double systemGainK) const {
  return std::exp(slope * std::log(systemGainK) + bias);
}

double tukeyVarianceFactor(double lambda) {
  if (std::abs(lambda) < 1e-6) return std::numbers::pi * std::numbers::pi / 3.0;
  const double g = std::lgamma(lambda + 1.0), g2 = std::lgamma(2.0 * lambda + 2.0);
  return 2.0 / (lambda * lambda) * (1.0 / (1.0 + 2.0 * lambda) - std::exp(2.0 * g - g2));
}

double tukeyQuantile(double lambda, double u) {
  if (std::abs(lambda) < 1e-6) return std::log(u / (1.0 - u));
  return (std::pow(u, lambda) - std::pow(1.0 - u, lambda)) / lambda;
}

double NoiseAtIso::postReadVarianceDn2() const {
  if (shape == ReadNoiseShape::kTukeyLambda)
    return tukeyScaleDn * tukeyScaleDn * tukeyVarianceFactor(tukeyLambda);
  return readPostDn * readPostDn;
}

double NoiseAtIso::readVarianceDn2() const {
  return systemGainK * systemGainK * readPreE * readPreE + postReadVarianceDn2() +
         rowNoiseDn * rowNoiseDn;
}

IsoRange isoRange(const SensorSpec& sensor) {
  const auto& table = sensor.noise.isoTable;
  if (table.empty()) return {};
  return {table.front().iso, table.back().iso};
}

namespace {

// Interpolation between two rows at t ∈ [0, 1] of log ISO: log-log for positive values
// (gains, σ's), linear for the rest (λ, offsets).
double between(double a, double b, double t, bool logScale) {
  if (t <= 0.0) return a;
  if (t >= 1.0) return b;
  if (logScale && a > 0.0 && b > 0.0) return std::exp(std::lerp(std::log(a), std::log(b), t));
  return std::lerp(a, b, t);
}

// A column of the table at `iso` (rows i, i+1, fraction t), or nullopt when either row lacks it.
std::optional<double> column(const IsoTableRow& a, const IsoTableRow& b, double t,
                             std::optional<double> IsoTableRow::*field, bool logScale) {
  const auto& va = a.*field;
  const auto& vb = b.*field;
  if (!va || !vb) return std::nullopt;
  return between(*va, *vb, t, logScale);
}

}  // namespace

std::string isoRangeProblem(double iso) {
  if (iso >= kMinIso && iso <= kMaxIso) return "";
  return "ISO " + formatShortest(iso) + " is outside [" + formatShortest(kMinIso) + ", " +
         formatShortest(kMaxIso) + "]";
}

NoiseAtIso noiseAtIso(const SensorSpec& sensor, double iso) {
  if (!(iso > 0.0) || !std::isfinite(iso))
    throw InputError({}, "iso", "ISO must be a finite number > 0");
  const SensorNoiseSpec& ns = sensor.noise;
  NoiseAtIso n;
  n.iso = iso;
  n.fullWellE = sensor.fullWellE;
  n.readPreE = sensor.readNoiseE;
  n.readPostDn = ns.readNoisePostDn;
  n.shape = ns.shape;
  n.tukeyLambda = ns.tukeyLambda;
  n.rowNoiseDn = ns.rowNoiseDn;
  n.blackOffsetsDn = ns.blackOffsetsDn;
  // K ∝ ISO within a conversion-gain mode.
  const DualConversionGain& dcg = ns.dualGain;
  if (dcg.iso > 0.0 && iso >= dcg.iso) {
    n.highConversionGain = true;
    n.systemGainK = (iso / dcg.iso) / dcg.conversionGainEPerDn;
    n.readPreE = dcg.readNoiseE;
    if (dcg.fullWellE) n.fullWellE = *dcg.fullWellE;
  } else {
    n.systemGainK = (iso / sensor.baseIso) / sensor.conversionGainEPerDn;
  }
  // Measured rows replace what they state.
  if (!ns.isoTable.empty()) {
    const auto& rows = ns.isoTable;
    if (iso < rows.front().iso || iso > rows.back().iso)
      throw InputError({}, "iso",
                       "ISO " + formatShortest(iso) + " is outside the range the sensor '" +
                           sensor.name + "' was calibrated at (" +
                           formatShortest(rows.front().iso) + " to " +
                           formatShortest(rows.back().iso) + ")");
    std::size_t i = 0;
    while (i + 2 < rows.size() && iso > rows[i + 1].iso) ++i;
    const IsoTableRow& a = rows[i];
    const IsoTableRow& b = rows.size() > 1 ? rows[i + 1] : rows[i];
    const double t = b.iso > a.iso ? std::log(iso / a.iso) / std::log(b.iso / a.iso) : 0.0;
    if (auto v = column(a, b, t, &IsoTableRow::systemGain, true)) n.systemGainK = *v;
    if (auto v = column(a, b, t, &IsoTableRow::readNoiseE, true)) n.readPreE = *v;
    if (auto v = column(a, b, t, &IsoTableRow::readNoisePostDn, true)) n.readPostDn = *v;
    if (auto v = column(a, b, t, &IsoTableRow::tukeyLambda, false)) n.tukeyLambda = *v;
    if (auto v = column(a, b, t, &IsoTableRow::tukeyScaleDn, true)) n.tukeyScaleDn = *v;
    if (auto v = column(a, b, t, &IsoTableRow::rowNoiseDn, true)) n.rowNoiseDn = *v;
    if (!a.blackOffsetsDn.empty() && !b.blackOffsetsDn.empty()) {
      n.blackOffsetsDn.resize(a.blackOffsetsDn.size());
      for (std::size_t k = 0; k < a.blackOffsetsDn.size(); ++k)
        n.blackOffsetsDn[k] = between(a.blackOffsetsDn[k], b.blackOffsetsDn[k], t, false);
    }
  }
  // ELD's fits, evaluated at this K.
  if (ns.readNoiseFit) {
    n.readPreE = 0.0;
    n.readPostDn = ns.readNoiseFit->at(n.systemGainK);
  }
  if (ns.tukeyScaleFit) n.tukeyScaleDn = ns.tukeyScaleFit->at(n.systemGainK);
  if (ns.rowNoiseFit) n.rowNoiseDn = ns.rowNoiseFit->at(n.systemGainK);
  if (!std::isfinite(n.systemGainK) || !(n.systemGainK > 0.0) ||
      !std::isfinite(n.readVarianceDn2()))
    throw InputError({}, "iso",
                     "the sensor '" + sensor.name + "' gives no finite gain and noise at ISO " +
                         formatShortest(iso) + " (check its gain and noise fits)");
  return n;
}

std::vector<std::string> modelledNoiseTerms(const SensorSpec& sensor, double iso) {
  if (sensor.noiseless) return {};
  const NoiseAtIso n = noiseAtIso(sensor, iso);
  const SensorNoiseSpec& ns = sensor.noise;
  std::vector<std::string> terms = {"shot"};
  const auto add = [&terms](bool on, const char* name) {
    if (on) terms.emplace_back(name);
  };
  add(sensor.darkCurrentEPerS > 0.0, "dark_current");
  add(ns.hotPixelFraction > 0.0 && ns.hotPixelDarkCurrentEPerS > 0.0, "hot_pixels");
  add(ns.stuckPixelFraction > 0.0, "stuck_pixels");
  add(sensor.prnuFraction > 0.0, "prnu");
  add(sensor.dsnuE > 0.0, "dsnu");
  add(sensor.rowFpnE > 0.0, "row_fpn");
  add(sensor.columnFpnE > 0.0, "column_fpn");
  add(n.readPreE > 0.0, "read_pre");
  if (n.shape == ReadNoiseShape::kTukeyLambda)
    add(n.tukeyScaleDn > 0.0, "read_tukey_lambda");
  else
    add(n.readPostDn > 0.0, "read_post");
  add(n.rowNoiseDn > 0.0, "row_temporal");
  add(std::any_of(n.blackOffsetsDn.begin(), n.blackOffsetsDn.end(),
                  [](double v) { return v != 0.0; }),
      "black_offsets");
  add(n.highConversionGain, "dual_conversion_gain");
  return terms;
}

}  // namespace camsim
