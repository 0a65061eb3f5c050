#include "cli/ptc_command.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <ostream>
#include <sstream>

#include "cli/args.h"
#include "cli/command_line.h"
#include "cli/ptc_report.h"
#include "cli/python_script.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/base/luts_directory.h"
#include "sensor/io/output_set.h"
#include "sensor/model/sensor_noise.h"
#include "sensor/model/sensor_spec.h"

namespace camsim {
namespace {

// A sensor whose configuration leaves no photon-transfer curve (every level clipped or
// black: a full well below an electron, a black level at the white level, every pixel
// stuck) measures no finite gain, quantum efficiency or saturation; its table, CSV and plots
// would be NaN and the plot script failed (exit 1; found by probing). Refused before
// anything is written, naming the sensor's file.
void requireUsableMeasurement(const PtcResult& m, const SensorSpec& sensor, double iso) {
  const auto refuse = [&](const std::string& measured) {
    return InputError(
        {sensor.sourceName(), 0, 0}, "",
        "at ISO " + formatShortest(iso) + " this sensor gives no photon-transfer curve (" +
            measured +
            "): its exposures clip or read black before they vary; check full_well_e, "
            "conversion_gain_e_per_dn, read_noise_e, black_level_dn and the defects");
  };
  if (m.gainFitCount < 2) throw refuse(std::to_string(m.gainFitCount) + " levels in the gain fit");
  const std::pair<const char*, double> checks[] = {{"system gain K", m.systemGainK},
                                                   {"quantum efficiency", m.quantumEfficiency},
                                                   {"saturation μ_p.sat", m.muPSat},
                                                   {"SNR maximum", m.snrMax}};
  for (const auto& [what, value] : checks)
    if (!std::isfinite(value) || !(value > 0.0))
      throw refuse(std::string(what) + " measured as " + formatShortest(value));
}

// Fixed with an explicit sign (deviations: "+0.12").
std::string formatSigned(double v, int decimals) {
  return (std::signbit(v) ? "" : "+") + formatFixed(v, decimals);  // as printf "%+.*f"
}

// Significant digits without an exponent for the magnitudes in the table; beyond them
// (1e-95 of a QE, 6e56 photons: found by probing, printed as 0.00000 and as 57 digits that
// ran into the next column) with one.
std::string number(double v) {
  const double a = std::abs(v);
  if (a == 0.0) return "0";
  if (a >= 1e9 || a < 1e-4) return formatNumber(v, 4);
  if (a >= 1000.0) return formatFixed(v, 0);
  if (a >= 10.0) return formatFixed(v, 2);
  if (a >= 0.1) return formatFixed(v, 4);
  return formatFixed(v, 5);
}

// Characters a file name keeps; others become '_'.
std::string fileStem(const std::string& name) {
  std::string s;
  for (char ch : name)
    s += (std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '.' || ch == '_')
             ? ch
             : '_';
  return s.empty() ? "sensor" : s;
}

}  // namespace

namespace {

std::unique_ptr<CLI::App> ptcApp(PtcArgs& p) {
  auto app = newCommandApp(
      "ptc",
      "Measures SENSOR (a preset name such as smartphone-1.4um, or a sensor YAML file) the\n"
      "EMVA 1288 way (Release 4.0 Linear: photon transfer, SNR, dark noise, DSNU, PRNU,\n"
      "linearity; with row noise and the read-noise shape of the dark frames) on the\n"
      "simulated sensor at each --iso (default: its base ISO), prints the results with\n"
      "their standard errors next to the values its configuration implies, and the fits\n"
      "across ISOs, and writes into DIR:\n"
      "  ptc_SENSOR.csv      one row per irradiation step and ISO (mu_p, mu_y, var_y, SNR)\n"
      "  ptc_SENSOR.json     every quantity per ISO with uncertainty, and the fits\n"
      "  ptc_SENSOR_ptc.png  photon transfer curve with the fitted system gain\n"
      "  ptc_SENSOR_snr.png  SNR against photons, with the ideal and model curves\n"
      "  ptc_SENSOR_gain.png, ptc_SENSOR_noise.png   K(ISO) and the noise against ISO\n"
      "                      (several ISOs only)\n"
      "(the plots need python3-matplotlib; without it only the CSV and JSON are written).\n"
      "--compare A.json B.json says per quantity whether B moved from A by more than\n"
      "4 combined standard errors: exit 0 if nothing moved, 1 if something did, 2 for a bad\n"
      "file.");
  app->add_option("sensor", p.sensor, "sensor preset or file")->type_name("SENSOR");
  app->add_option_function<std::vector<std::string>>(
         "--iso",
         [&p](const std::vector<std::string>& values) {
           for (const std::string& t : values) {
             char* end = nullptr;
             const double v = std::strtod(t.c_str(), &end);
             if (t.empty() || end != t.c_str() + t.size() || !std::isfinite(v))
               throw UsageError("--iso: expected ISO values (numbers), got '" + t + "'");
             if (const std::string problem = isoRangeProblem(v); !problem.empty())
               throw UsageError("--iso: " + problem);  // the capture range, as render's --iso
             p.isos.push_back(v);
           }
         },
         "ISO settings to measure at, each in [1, 1e7] (default: the base ISO)")
      ->type_name("N ...")
      ->expected(1, -1);
  app->add_option("--compare", p.compare, "compare two reports instead of measuring")
      ->type_name("A.json B.json")
      ->expected(2);
  addOutputOption(*app, p.outputDir, "output directory (created if missing; default: out)");
  app->add_option_function<std::string>(
         "--seed",
         [&p](const std::string& t) {
           p.seed = static_cast<std::uint64_t>(parseInteger("--seed", t, 0, INT64_MAX));
         },
         "noise seed (default 1)")
      ->type_name("N");
  return app;
}

}  // namespace

std::string ptcUsageText() {
  PtcArgs p;
  return commandHelp(*ptcApp(p));
}

PtcArgs parsePtcArgs(const std::vector<std::string>& args) {
  PtcArgs p;
  if (!parseCommand(*ptcApp(p), args)) {
    p.help = true;
    return p;
  }
  if (!p.compare.empty()) {
    if (!p.sensor.empty() || !p.isos.empty())
      throw UsageError("ptc --compare A.json B.json takes no sensor and no --iso");
    return p;
  }
  if (p.sensor.empty())
    throw UsageError("ptc needs a sensor preset or file (try 'camsim ptc --help')");
  std::sort(p.isos.begin(), p.isos.end());
  p.isos.erase(std::unique(p.isos.begin(), p.isos.end()), p.isos.end());
  return p;
}

std::string formatPtcTable(const PtcResult& m, const PtcConfigured& c, const PtcUncertainty* un) {
  struct Row {
    std::string name, unit;
    double configured, measured, u;
    bool db;             // difference in dB instead of a relative error
    bool hasConfigured;  // false: no configured value (shown as "—")
  };
  const PtcUncertainty u = un ? *un : PtcUncertainty{};
  const DarkFrameAnalysis& d = m.data.dark;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Row> rows = {
      {"system gain K", "DN/e⁻", c.systemGainK, m.systemGainK, u.systemGainK, false, true},
      {"quantum efficiency η", "e⁻/photon", c.quantumEfficiency, m.quantumEfficiency,
       u.quantumEfficiency, false, true},
      {"responsivity R = K·η", "DN/photon", c.systemGainK * c.quantumEfficiency, m.responsivityR,
       u.responsivityR, false, true},
      {"temporal dark noise σ_d", "e⁻", c.darkNoiseE, m.darkNoiseE, u.darkNoiseE, false, true},
      {"dark σ_y.dark", "DN", std::sqrt(c.darkVarianceDn2), m.sigmaYDark, u.sigmaYDark, false,
       true},
      {"clip capacity μ_e.clip", "e⁻", c.muESat, m.muEClip, u.muEClip, false, true},
      {"saturation capacity μ_e.sat", "e⁻", c.muESatEmva, m.muESat, u.muESat, false, true},
      {"SNR_max", "dB", c.snrMaxDb, m.snrMaxDb, u.snrMaxDb, true, true},
      {"sensitivity threshold μ_p.min", "photons", c.muPMin, m.muPMin, u.muPMin, false, true},
      {"dynamic range DR", "dB", c.dynamicRangeDb, m.dynamicRangeDb, u.dynamicRangeDb, true, true},
      {"DSNU₁₂₈₈", "e⁻", c.dsnuE, m.dsnuE, u.dsnuE, false, true},
      {"PRNU₁₂₈₈", "%", c.prnuPercent, m.prnuPercent, u.prnuPercent, false, true},
      {"linearity error LE", "%", 0.0, m.linearityErrorPercent, u.linearityErrorPercent, true,
       true},
  };
  if (un) {
    rows.push_back({"row noise σ_row (temporal)", "DN", c.rowNoiseDn, d.rowTemporalDn.value,
                    d.rowTemporalDn.uncertainty, false, true});
    rows.push_back({"row pattern (fixed)", "DN", nan, d.rowFixedDn.value, d.rowFixedDn.uncertainty,
                    false, false});
    rows.push_back({"read noise σ_read (normal plot)", "DN", c.readGaussianDn,
                    d.readGaussianDn.value, d.readGaussianDn.uncertainty, false, true});
    rows.push_back({"Tukey-λ shape λ (PPCC)", "—", c.tukeyLambda, d.tukeyLambda.value,
                    d.tukeyLambda.uncertainty, true, c.tukey});
    rows.push_back({"Tukey-λ scale", "DN", c.tukeyScaleDn, d.tukeyScaleDn.value,
                    d.tukeyScaleDn.uncertainty, false, c.tukey});
  }
  std::ostringstream out;
  out << padColumn("quantity", 33) << padColumn("unit", 11) << padColumn("configured", 12, true)
      << padColumn("measured", 12, true) << padColumn("± u", 10, true)
      << padColumn("error", 11, true) << "\n";
  for (const Row& r : rows) {
    std::string err;
    if (!r.hasConfigured)
      err = "";
    else if (r.db)
      err = formatSigned(r.measured - r.configured, 2) + (r.unit == "%"    ? " pt"
                                                          : r.unit == "dB" ? " dB"
                                                                           : "");
    else if (r.configured != 0.0)
      err = formatSigned(100.0 * (r.measured / r.configured - 1.0), 2) + " %";
    out << padColumn(r.name, 33) << padColumn(r.unit, 11)
        << padColumn(r.hasConfigured ? number(r.configured) : "—", 12, true)
        << padColumn(number(r.measured), 12, true) << padColumn(un ? number(r.u) : "", 10, true)
        << padColumn(err, 11, true) << "\n";
  }
  return out.str();
}

std::string formatPtcCsv(const std::vector<PtcResult>& results) {
  std::ostringstream out;
  out << "level,irradiance_w_m2,mu_p,mu_e,mu_y,var_y,mu_y_minus_dark,var_y_minus_dark,snr,"
         "in_gain_fit,saturation,iso\n";
  for (const PtcResult& m : results) out << formatPtcCsvRows(m);
  return out.str();
}

std::string formatPtcCsvRows(const PtcResult& m) {
  std::ostringstream out;
  char buf[256];
  for (std::size_t i = 0; i < m.data.levels.size(); ++i) {
    const PtcLevel& l = m.data.levels[i];
    std::snprintf(buf, sizeof buf, "%zu,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d,%.6g\n", i,
                  l.irradianceWm2, l.muP, m.quantumEfficiency * l.muP, l.muY, l.varY,
                  l.muY - m.data.muYDark, l.varY - m.data.varYDark, l.snr,
                  static_cast<int>(i) < m.gainFitCount ? 1 : 0,
                  static_cast<int>(i) == m.saturationIndex ? 1 : 0, m.iso);
    out << buf;
  }
  return out.str();
}

std::vector<std::filesystem::path> runPtc(const PtcArgs& args, std::ostream& out,
                                          std::ostream& log) {
  SensorSpec sensor;
  try {
    sensor = loadSensorSpec(args.sensor, lutsDirectory());
  } catch (const InputError& e) {
    throw inFile(e, "<command line>");  // an unknown preset named no file ("<input>")
  }
  const std::filesystem::path outDir(args.outputDir);
  PtcOptions options;
  if (args.seed) options.seed = *args.seed;
  const std::vector<double> isos =
      args.isos.empty() ? std::vector<double>{sensor.baseIso} : args.isos;
  for (double iso : isos) {  // an ISO the sensor refuses: before any work
    try {
      (void)noiseAtIso(sensor, iso);
    } catch (const InputError& e) {
      if (args.isos.empty()) throw;  // the sensor's own base ISO
      throw InputError({"<command line>", 0, 0}, "--iso", e.message());
    }
  }
  const NewDirectoryCleanup cleanup(outDir);  // an error from here on: no empty folder left
  for (const auto& stale : OutputSet::prepareDirectory(outDir))
    log << "removed " << stale.string() << " (left by a run that was killed)\n";

  std::vector<PtcIsoReport> reports;
  std::vector<PtcResult> results;
  std::vector<IsoPoint> points;
  for (double iso : isos) {
    options.iso = iso;
    log << "camsim ptc: measuring " << sensor.name << " at ISO " << formatShortest(iso) << " ("
        << options.levels << " levels, " << options.width << "×" << options.height
        << " photosites)\n";
    PtcIsoReport r;
    r.measured = measurePhotonTransfer(sensor, options);
    try {
      requireUsableMeasurement(r.measured, sensor, iso);
    } catch (const InputError& e) {
      if (args.isos.empty() || iso == sensor.baseIso) throw;  // the sensor's own settings
      throw InputError({"<command line>", 0, 0}, "--iso",
                       e.message() + " (in " + sensor.sourceName() + "; its base ISO is " +
                           formatShortest(sensor.baseIso) + ")");
    }
    r.configured = configuredPhotonTransfer(sensor, options);
    r.uncertainty = photonTransferUncertainty(r.measured);
    if (const double clipped = darkClippedFraction(r.configured, sensor, options); clipped > 1e-3)
      log << "camsim ptc: warning: at ISO " << formatShortest(iso) << " the black level ("
          << formatShortest(sensor.blackLevelDn) << " DN, black_level_dn) leaves about "
          << formatNumber(100.0 * clipped, 2)
          << " % of the dark photosites at 0 DN: EMVA 1288 needs an unclipped dark signal, so "
             "K, σ_d, DSNU and the clip capacity below are biased\n";
    const PtcResult& m = r.measured;
    out << (reports.empty() ? "" : "\n") << "EMVA 1288 (Release 4.0 Linear) photon transfer of "
        << sensor.name << " at ISO " << formatShortest(iso)
        << (r.configured.highConversionGain ? " (high conversion gain)" : "") << "\n"
        << "  light " << formatFixed(options.wavelengthNm, 0) << " nm on channel " << m.channel
        << " (highest QE at that wavelength): " << m.pixels << " of "
        << options.width * options.height << " photosites analysed\n"
        << "  exposure " << formatNumber(options.exposureTimeS * 1e3, 3) << " ms (base ISO "
        << formatNumber(sensor.baseIso, 6) << "); " << m.data.levels.size()
        << " levels × 2 frames; " << options.spatialFrames << " dark + " << options.spatialFrames
        << " half-saturation frames; seed " << options.seed << "\n"
        << "  configured μ_e.clip = saturationElectrons(); configured μ_e.sat = where the\n"
        << "  configuration's temporal variance peaks (EMVA's definition); ± u: standard\n"
        << "  errors; see docs/ptc.md\n\n"
        << formatPtcTable(m, r.configured, &r.uncertainty);
    points.push_back(isoPoint(r.measured, r.uncertainty));
    results.push_back(r.measured);
    reports.push_back(std::move(r));
  }
  const IsoFit fit = fitAcrossIsos(points);
  if (isos.size() > 1) out << "\n" << formatIsoFit(sensor, reports, fit);

  const std::string stem = "ptc_" + fileStem(sensor.name);
  OutputSet outputs(outDir);
  const std::filesystem::path csv = outputs.addText(stem + ".csv", formatPtcCsv(results));
  const std::filesystem::path json =
      outputs.addText(stem + ".json", formatPtcJson(sensor, options, reports, fit));
  if (const std::optional<std::string> python = pythonWithMatplotlib(); !python) {
    log << "camsim ptc: python3 with matplotlib not found ($CAMSIM_PYTHON or /usr/bin/python3; "
           "Debian: apt-get install "
        << "python3-matplotlib): plots skipped, CSV and JSON only\n";
  } else {
    std::vector<std::string> plotArgs = {csv.string(), json.string(), sensor.name,
                                         outputs.add(stem + "_ptc.png").string(),
                                         outputs.add(stem + "_snr.png").string()};
    if (isos.size() > 1) {
      plotArgs.push_back(outputs.add(stem + "_gain.png").string());
      plotArgs.push_back(outputs.add(stem + "_noise.png").string());
    }
    out.flush();
    runPythonScript(*python, ptcPlotScriptFile("ptc_plot.py"), plotArgs);
  }
  const std::vector<std::filesystem::path> files = outputs.commit();
  for (const auto& f : files) log << "camsim ptc: wrote " << f.string() << "\n";
  return files;
}

int runPtcCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log) {
  const PtcArgs parsed = parsePtcArgs(args);
  if (parsed.help) {
    out << ptcUsageText();
    return 0;
  }
  if (!parsed.compare.empty()) {
    const std::vector<PtcComparison> rows = comparePtcReports(parsed.compare[0], parsed.compare[1]);
    return formatPtcComparison(rows, parsed.compare[0], parsed.compare[1], out) ? 1 : 0;
  }
  runPtc(parsed, out, log);
  return 0;
}

}  // namespace camsim
