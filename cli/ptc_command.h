// `camsim ptc SENSOR [--iso N ...] [-o DIR] [--seed N]`: the EMVA 1288 photon-transfer
// measurement of a sensor preset or YAML file (sensor/model/photon_transfer.h) at each ISO
// (default: the base ISO). Prints the measured parameters with their standard errors next
// to the values the configuration implies, and the fits across ISOs; writes
// DIR/ptc_<sensor>.csv (one row per irradiation step and ISO), DIR/ptc_<sensor>.json
// (cli/ptc_report.h) and, when /usr/bin/python3 has matplotlib, the plots
// DIR/ptc_<sensor>_ptc.png, _snr.png and, for several ISOs, _gain.png and _noise.png
// (scripts/ptc_plot.py, embedded). All files appear at once (OutputSet). The environment
// variable CAMSIM_PYTHON replaces /usr/bin/python3.
// `camsim ptc --compare A.json B.json`: exit 0 when nothing moved, 1 when something did,
// 2 for a bad file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sensor/model/photon_transfer.h"
#include "sensor/model/ptc_statistics.h"

namespace camsim {

struct PtcArgs {
  std::string sensor;  // preset name or YAML path
  std::string outputDir = "out";
  std::optional<std::uint64_t> seed;
  std::vector<double> isos;          // empty: the base ISO
  std::vector<std::string> compare;  // A.json, B.json: compare instead of measuring
  bool help = false;
};

// args[0] == "ptc". UsageError on bad usage.
PtcArgs parsePtcArgs(const std::vector<std::string>& args);
std::string ptcUsageText();

// The embedded plot script (scripts/ptc_plot.py at build time).
std::string_view ptcPlotScriptFile(std::string_view relPath);

// The results table (configured, measured ± standard error, relative error), as printed;
// without `uncertainty` the ± column is left empty.
std::string formatPtcTable(const PtcResult& measured, const PtcConfigured& configured,
                           const PtcUncertainty* uncertainty = nullptr);
// The per-level CSV of every measured ISO (header and rows), and one ISO's rows.
std::string formatPtcCsv(const std::vector<PtcResult>& results);
std::string formatPtcCsvRows(const PtcResult& measured);

// Runs the measurement and writes the files; `out` gets the table, `log` the progress and
// warnings. Throws InputError for a bad sensor (nothing written then). Returns the files.
std::vector<std::filesystem::path> runPtc(const PtcArgs& args, std::ostream& out,
                                          std::ostream& log);

// Entry point from main(): parses `args` (args[0] == "ptc"), runs, returns the exit code.
int runPtcCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log);

}  // namespace camsim
