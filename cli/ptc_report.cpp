// ptc_<sensor>.json and `camsim ptc --compare`; see ptc_report.h and docs/ptc.md.
#include "cli/ptc_report.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>

#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/base/yaml_reader.h"
#include "sensor/io/json_writer.h"

namespace camsim {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

JsonObject quantity(const char* unit, double value, double uncertainty,
                    std::optional<double> configured = std::nullopt) {
  JsonObject q;
  q.set("unit", unit).set("value", value).set("uncertainty", uncertainty);
  if (configured) q.set("configured", *configured);
  return q;
}

JsonObject isoObject(const PtcIsoReport& r) {
  const PtcResult& m = r.measured;
  const PtcUncertainty& u = r.uncertainty;
  const PtcConfigured& c = r.configured;
  const DarkFrameAnalysis& d = m.data.dark;
  const double eta = c.quantumEfficiency;
  JsonObject q;
  q.set("system_gain_k", quantity("DN/e-", m.systemGainK, u.systemGainK, c.systemGainK))
      .set("responsivity_r",
           quantity("DN/photon", m.responsivityR, u.responsivityR, c.systemGainK * eta))
      .set("quantum_efficiency",
           quantity("e-/photon", m.quantumEfficiency, u.quantumEfficiency, eta))
      .set("mu_y_dark", quantity("DN", m.data.muYDark, u.muYDark))
      .set("sigma2_y_dark", quantity("DN^2", m.data.varYDark, u.varYDark, c.darkVarianceDn2))
      .set("sigma_y_dark", quantity("DN", m.sigmaYDark, u.sigmaYDark, std::sqrt(c.darkVarianceDn2)))
      .set("dark_noise_e", quantity("e-", m.darkNoiseE, u.darkNoiseE, c.darkNoiseE))
      .set("mu_e_clip", quantity("e-", m.muEClip, u.muEClip, c.muESat))
      .set("mu_p_sat", quantity("photons", m.muPSat, u.muPSat, c.muESatEmva / eta))
      .set("mu_e_sat", quantity("e-", m.muESat, u.muESat, c.muESatEmva))
      .set("snr_max_db", quantity("dB", m.snrMaxDb, u.snrMaxDb, c.snrMaxDb))
      .set("mu_p_min", quantity("photons", m.muPMin, u.muPMin, c.muPMin))
      .set("dynamic_range_db", quantity("dB", m.dynamicRangeDb, u.dynamicRangeDb, c.dynamicRangeDb))
      .set("dsnu_e", quantity("e-", m.dsnuE, u.dsnuE, c.dsnuE))
      .set("prnu_percent", quantity("%", m.prnuPercent, u.prnuPercent, c.prnuPercent))
      .set("linearity_error_percent",
           quantity("%", m.linearityErrorPercent, u.linearityErrorPercent, 0.0))
      .set("row_noise_dn",
           quantity("DN", d.rowTemporalDn.value, d.rowTemporalDn.uncertainty, c.rowNoiseDn))
      .set("row_pattern_dn", quantity("DN", d.rowFixedDn.value, d.rowFixedDn.uncertainty))
      .set("read_noise_gaussian_dn",
           quantity("DN", d.readGaussianDn.value, d.readGaussianDn.uncertainty, c.readGaussianDn))
      .set("normal_ppcc", quantity("-", d.normalCorrelation.value, d.normalCorrelation.uncertainty))
      .set("tukey_lambda", quantity("-", d.tukeyLambda.value, d.tukeyLambda.uncertainty,
                                    c.tukey ? std::optional<double>(c.tukeyLambda) : std::nullopt))
      .set("tukey_scale_dn",
           quantity("DN", d.tukeyScaleDn.value, d.tukeyScaleDn.uncertainty,
                    c.tukey ? std::optional<double>(c.tukeyScaleDn) : std::nullopt))
      .set("tukey_ppcc", quantity("-", d.tukeyCorrelation.value, d.tukeyCorrelation.uncertainty));
  JsonObject iso;
  iso.set("iso", m.iso)
      .set("high_conversion_gain", c.highConversionGain)
      .set("configured_read_noise_pre_e", c.readPreE)
      .set("configured_read_noise_post_dn", c.readPostDn)
      .set("quantities", q);
  return iso;
}

}  // namespace

std::string padColumn(const std::string& s, std::size_t width, bool right) {
  std::size_t points = 0;
  for (unsigned char ch : s) points += (ch & 0xC0) != 0x80;
  const std::string fill(points < width ? width - points : 0, ' ');
  return right ? fill + s : s + fill;
}

std::string formatPtcJson(const SensorSpec& sensor, const PtcOptions& options,
                          const std::vector<PtcIsoReport>& isos, const IsoFit& fit) {
  JsonObject setup;
  const PtcResult& first = isos.front().measured;
  setup.set("wavelength_nm", options.wavelengthNm)
      .set("exposure_time_s", options.exposureTimeS)
      .set("region", std::vector<double>{static_cast<double>(options.width),
                                         static_cast<double>(options.height)})
      .set("channel", first.channel)
      .set("pixels", static_cast<double>(first.pixels))
      .set("levels", static_cast<double>(options.levels))
      .set("stack_frames", static_cast<double>(options.spatialFrames))
      .setInteger("seed", options.seed)
      .set("compare_coverage_k", kCompareCoverage);
  std::vector<JsonObject> isoObjects;
  for (const PtcIsoReport& r : isos) isoObjects.push_back(isoObject(r));

  std::vector<JsonObject> segments;
  for (const GainSegment& g : fit.segments) {
    // The configured σ_pre of the segment: at its first ISO (with the dark shot noise).
    std::optional<double> preConfigured;
    for (const PtcIsoReport& r : isos)
      if (r.measured.iso == g.isoMin) preConfigured = r.configured.readPreDarkE;
    const double cg = 1.0 / (g.gainPerIso.value * g.isoMin);
    JsonObject s;
    s.set("iso_min", g.isoMin)
        .set("iso_max", g.isoMax)
        .set("count", static_cast<double>(g.count))
        .set("gain_per_iso",
             quantity("DN/e- per ISO", g.gainPerIso.value, g.gainPerIso.uncertainty))
        .set("conversion_gain_e_per_dn_at_iso_min",
             quantity("e-/DN", cg, cg * g.gainPerIso.uncertainty / g.gainPerIso.value))
        .set("sigma_pre_e",
             quantity("e-", g.sigmaPreFitted ? g.sigmaPreE.value : kNan,
                      g.sigmaPreFitted ? g.sigmaPreE.uncertainty : kNan, preConfigured));
    segments.push_back(s);
  }
  std::optional<double> postConfigured;
  for (const PtcIsoReport& r : isos) postConfigured = r.configured.readPostDn;
  JsonObject split;
  split.set("fitted", fit.splitFitted)
      .set("sigma_post_dn",
           quantity("DN", fit.splitFitted ? fit.sigmaPostDn.value : kNan,
                    fit.splitFitted ? fit.sigmaPostDn.uncertainty : kNan, postConfigured))
      .set("chi2", fit.splitFitted ? fit.chi2 : kNan)
      .set("dof", static_cast<double>(fit.dof));
  std::vector<JsonObject> darkNoise;
  for (const PtcIsoReport& r : isos) {
    JsonObject p;
    p.set("iso", r.measured.iso)
        .set("measured_e", r.measured.darkNoiseE)
        .set("fitted_e",
             fittedDarkNoiseE(fit, r.measured.iso, r.measured.data.dark.rowTemporalDn.value))
        .set("configured_e", r.configured.darkNoiseE);
    darkNoise.push_back(p);
  }
  JsonObject fits;
  fits.set("gain_segments", segments).set("dark_noise_split", split).set("dark_noise_e", darkNoise);

  JsonObject root;
  root.set("format", "camsim-ptc")
      .set("version", 1.0)
      .set("sensor", sensor.name)
      .set("standard", "EMVA 1288 Release 4.0 Linear")
      .set("setup", setup)
      .set("isos", isoObjects)
      .set("fits", fits);
  return root.str() + "\n";
}

std::string formatIsoFit(const SensorSpec& sensor, const std::vector<PtcIsoReport>& isos,
                         const IsoFit& fit) {
  std::ostringstream out;
  out << "Across ISOs (" << sensor.name << "): K(ISO) = g·ISO per conversion-gain segment\n";
  for (const GainSegment& g : fit.segments) {
    out << "  ISO " << formatShortest(g.isoMin) << "–" << formatShortest(g.isoMax) << " ("
        << g.count << "): K/ISO = " << formatNumber(g.gainPerIso.value, 5) << " ± "
        << formatNumber(g.gainPerIso.uncertainty, 2) << " DN/e⁻, "
        << formatNumber(1.0 / (g.gainPerIso.value * g.isoMin), 5) << " e⁻/DN at ISO "
        << formatShortest(g.isoMin);
    if (g.sigmaPreFitted)
      out << "; σ_pre = " << formatNumber(g.sigmaPreE.value, 4) << " ± "
          << formatNumber(g.sigmaPreE.uncertainty, 2) << " e⁻";
    out << "\n";
  }
  if (fit.segments.size() > 1) out << "  conversion-gain step(s) between the segments above\n";
  if (fit.splitFitted)
    out << "  σ²_y.dark − 1/12 − σ²_row = K²σ²_pre + σ²_post: σ_post = "
        << formatNumber(fit.sigmaPostDn.value, 4) << " ± "
        << formatNumber(fit.sigmaPostDn.uncertainty, 2) << " DN (χ² = " << formatNumber(fit.chi2, 3)
        << ", " << fit.dof << " dof)\n";
  else
    out << "  σ_pre/σ_post split: needs at least one ISO more than segments (" << isos.size()
        << " measured)\n";
  return out.str();
}

}  // namespace camsim
