// `camsim ptc SENSOR [-o DIR] [--seed N]`: the EMVA 1288 photon-transfer measurement of a
// sensor preset or YAML file (sensor/model/photon_transfer.h). Prints the measured parameters next
// to the values the configuration implies, writes DIR/ptc_<sensor>.csv (one row per
// irradiation step) and, when /usr/bin/python3 has matplotlib, the plots
// DIR/ptc_<sensor>_ptc.png and DIR/ptc_<sensor>_snr.png (scripts/ptc_plot.py, embedded).
// All files appear at once (OutputSet). The environment variable CAMSIM_PYTHON replaces
// /usr/bin/python3.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sensor/model/photon_transfer.h"

namespace camsim {

struct PtcArgs {
  std::string sensor;  // preset name or YAML path
  std::string outputDir = "out";
  std::optional<std::uint64_t> seed;
  bool help = false;
};

// args[0] == "ptc". UsageError on bad usage.
PtcArgs parsePtcArgs(const std::vector<std::string>& args);
std::string ptcUsageText();

// The embedded plot script (scripts/ptc_plot.py at build time).
std::string_view ptcPlotScriptFile(std::string_view relPath);

// The results table (configured, measured, relative error), as printed.
std::string formatPtcTable(const PtcResult& measured, const PtcConfigured& configured);
// The per-level CSV.
std::string formatPtcCsv(const PtcResult& measured);

// Runs the measurement and writes the files; `out` gets the table, `log` the progress and
// warnings. Throws InputError for a bad sensor (nothing written then). Returns the files.
std::vector<std::filesystem::path> runPtc(const PtcArgs& args, std::ostream& out,
                                          std::ostream& log);

// Entry point from main(): parses `args` (args[0] == "ptc"), runs, returns the exit code.
int runPtcCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log);

}  // namespace camsim
