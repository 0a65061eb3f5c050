#include "cli/ptc_command.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <ostream>
#include <sstream>

#include "cli/args.h"
#include "cli/command_line.h"
#include "cli/python_script.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/base/luts_directory.h"
#include "sensor/io/output_set.h"
#include "sensor/model/sensor_spec.h"

namespace camsim {
namespace {

// Fixed with an explicit sign (deviations: "+0.12").
std::string formatSigned(double v, int decimals) {
  return (std::signbit(v) ? "" : "+") + formatFixed(v, decimals);  // as printf "%+.*f"
}

// Pads to `width` code points (UTF-8: continuation bytes do not count).
std::string pad(const std::string& s, std::size_t width, bool right = false) {
  std::size_t points = 0;
  for (unsigned char ch : s) points += (ch & 0xC0) != 0x80;
  const std::string fill(points < width ? width - points : 0, ' ');
  return right ? fill + s : s + fill;
}

// Significant digits without an exponent for the magnitudes in the table.
std::string number(double v) {
  const double a = std::abs(v);
  if (a == 0.0) return "0";
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
      "linearity) on the simulated sensor, prints the results next to the values its\n"
      "configuration implies, and writes into DIR:\n"
      "  ptc_SENSOR.csv      one row per irradiation step (mu_p, mu_y, var_y, SNR)\n"
      "  ptc_SENSOR_ptc.png  photon transfer curve with the fitted system gain\n"
      "  ptc_SENSOR_snr.png  SNR against photons, with the ideal and model curves\n"
      "(the plots need python3-matplotlib; without it only the CSV is written).");
  app->add_option("sensor", p.sensor, "sensor preset or file")->type_name("SENSOR");
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
  if (p.sensor.empty())
    throw UsageError("ptc needs a sensor preset or file (try 'camsim ptc --help')");
  return p;
}

std::string formatPtcTable(const PtcResult& m, const PtcConfigured& c) {
  struct Row {
    std::string name, unit;
    double configured, measured;
    bool db;  // difference in dB instead of a relative error
  };
  const Row rows[] = {
      {"system gain K", "DN/e⁻", c.systemGainK, m.systemGainK, false},
      {"quantum efficiency η", "e⁻/photon", c.quantumEfficiency, m.quantumEfficiency, false},
      {"responsivity R = K·η", "DN/photon", c.systemGainK * c.quantumEfficiency, m.responsivityR,
       false},
      {"temporal dark noise σ_d", "e⁻", c.darkNoiseE, m.darkNoiseE, false},
      {"clip capacity μ_e.clip", "e⁻", c.muESat, m.muEClip, false},
      {"saturation capacity μ_e.sat", "e⁻", c.muESatEmva, m.muESat, false},
      {"SNR_max", "dB", c.snrMaxDb, m.snrMaxDb, true},
      {"sensitivity threshold μ_p.min", "photons", c.muPMin, m.muPMin, false},
      {"dynamic range DR", "dB", c.dynamicRangeDb, m.dynamicRangeDb, true},
      {"DSNU₁₂₈₈", "e⁻", c.dsnuE, m.dsnuE, false},
      {"PRNU₁₂₈₈", "%", c.prnuPercent, m.prnuPercent, false},
      {"linearity error LE", "%", 0.0, m.linearityErrorPercent, true},
  };
  std::ostringstream out;
  out << pad("quantity", 31) << pad("unit", 11) << pad("configured", 12, true)
      << pad("measured", 12, true) << pad("error", 11, true) << "\n";
  for (const Row& r : rows) {
    std::string err;
    if (r.db)
      err = formatSigned(r.measured - r.configured, 2) + (r.unit == "%" ? " pt" : " dB");
    else if (r.configured != 0.0)
      err = formatSigned(100.0 * (r.measured / r.configured - 1.0), 2) + " %";
    out << pad(r.name, 31) << pad(r.unit, 11) << pad(number(r.configured), 12, true)
        << pad(number(r.measured), 12, true) << pad(err, 11, true) << "\n";
  }
  return out.str();
}

std::string formatPtcCsv(const PtcResult& m) {
  std::ostringstream out;
  out << "level,irradiance_w_m2,mu_p,mu_e,mu_y,var_y,mu_y_minus_dark,var_y_minus_dark,snr,"
         "in_gain_fit,saturation\n";
  char buf[256];
  for (std::size_t i = 0; i < m.data.levels.size(); ++i) {
    const PtcLevel& l = m.data.levels[i];
    std::snprintf(buf, sizeof buf, "%zu,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d\n", i,
                  l.irradianceWm2, l.muP, m.quantumEfficiency * l.muP, l.muY, l.varY,
                  l.muY - m.data.muYDark, l.varY - m.data.varYDark, l.snr,
                  static_cast<int>(i) < m.gainFitCount ? 1 : 0,
                  static_cast<int>(i) == m.saturationIndex ? 1 : 0);
    out << buf;
  }
  return out.str();
}

std::vector<std::filesystem::path> runPtc(const PtcArgs& args, std::ostream& out,
                                          std::ostream& log) {
  const SensorSpec sensor = loadSensorSpec(args.sensor, lutsDirectory());
  const std::filesystem::path outDir(args.outputDir);
  for (const auto& stale : OutputSet::prepareDirectory(outDir))
    log << "removed " << stale.string() << " (left by a run that was killed)\n";

  PtcOptions options;
  if (args.seed) options.seed = *args.seed;
  log << "camsim ptc: measuring " << sensor.name << " (" << options.levels << " levels, "
      << options.width << "×" << options.height << " photosites)\n";
  const PtcResult m = measurePhotonTransfer(sensor, options);
  const PtcConfigured c = configuredPhotonTransfer(sensor, options);

  out << "EMVA 1288 (Release 4.0 Linear) photon transfer of " << sensor.name << "\n"
      << "  light " << formatFixed(options.wavelengthNm, 0) << " nm on channel " << m.channel
      << " (highest QE at that wavelength): " << m.pixels << " of "
      << options.width * options.height << " photosites analysed\n"
      << "  exposure " << formatNumber(options.exposureTimeS * 1e3, 3) << " ms at base ISO "
      << formatNumber(sensor.baseIso, 6) << "; " << m.data.levels.size() << " levels × 2 frames; "
      << options.spatialFrames << " dark + " << options.spatialFrames
      << " half-saturation frames; seed " << options.seed << "\n"
      << "  configured μ_e.clip = saturationElectrons(); configured μ_e.sat = where the\n"
      << "  configuration's temporal variance peaks (EMVA's definition), see docs/ptc.md\n\n"
      << formatPtcTable(m, c);

  const std::string stem = "ptc_" + fileStem(sensor.name);
  OutputSet outputs(outDir);
  const std::filesystem::path csv = outputs.addText(stem + ".csv", formatPtcCsv(m));
  if (const std::optional<std::string> python = pythonWithMatplotlib(); !python) {
    log << "camsim ptc: python3 with matplotlib not found ($CAMSIM_PYTHON or /usr/bin/python3; "
           "Debian: apt-get install "
        << "python3-matplotlib): plots skipped, CSV only\n";
  } else {
    const auto ptcPng = outputs.add(stem + "_ptc.png"), snrPng = outputs.add(stem + "_snr.png");
    out.flush();
    runPythonScript(
        *python, ptcPlotScriptFile("ptc_plot.py"),
        {csv.string(), ptcPng.string(), snrPng.string(), sensor.name,
         formatNumber(m.systemGainK, 9), formatNumber(m.quantumEfficiency, 9),
         formatNumber(m.darkNoiseE, 9), formatNumber(m.muPSat, 9), formatNumber(m.muPMin, 9)});
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
  runPtc(parsed, out, log);
  return 0;
}

}  // namespace camsim
