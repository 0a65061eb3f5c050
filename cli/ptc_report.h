// The machine-readable side of `camsim ptc`: ptc_<sensor>.json (every EMVA 1288 quantity per
// ISO with its standard error and configured value, and the fits across ISOs; docs/ptc.md
// lists every field) and `camsim ptc --compare A.json B.json`, which says per quantity
// whether B moved from A beyond the combined uncertainty:
//   moved  ⇔  |a − b| > k·√(u_a² + u_b²),  k = kCompareCoverage = 4
// (4 rather than 3: a report holds ~25 quantities per ISO, and at 3σ one of 75 would be
// flagged by chance one run in six).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "sensor/model/photon_transfer.h"
#include "sensor/model/ptc_statistics.h"
#include "sensor/model/sensor_spec.h"

namespace camsim {

constexpr double kCompareCoverage = 4.0;

// One measured ISO: the measurement, its standard errors and the configuration's values.
struct PtcIsoReport {
  PtcResult measured;
  PtcUncertainty uncertainty;
  PtcConfigured configured;
};

// The JSON text of the report (sensor/io/json_writer.h).
// Pads to `width` code points (UTF-8: continuation bytes do not count), on the right or
// (right = true) on the left.
std::string padColumn(const std::string& s, std::size_t width, bool right = false);

std::string formatPtcJson(const SensorSpec& sensor, const PtcOptions& options,
                          const std::vector<PtcIsoReport>& isos, const IsoFit& fit);

// The text summary of the fits across ISOs (K(ISO) segments, the σ_pre/σ_post split).
std::string formatIsoFit(const SensorSpec& sensor, const std::vector<PtcIsoReport>& isos,
                         const IsoFit& fit);

// One compared quantity.
struct PtcComparison {
  std::string path;   // JSON path in A, e.g. isos[0].quantities.system_gain_k
  std::string label;  // ISO and quantity, for the table
  double a = 0.0, ua = 0.0, b = 0.0, ub = 0.0;
  double z = 0.0;      // |a − b| / √(u_a² + u_b²) (∞ when both u are 0 and a ≠ b)
  bool moved = false;  // z > k, or a structural difference (missing in B, another segment count)
  std::string note;    // for structural differences
};

// Reads and compares the two reports. InputError (file, line, JSON path) for a file that is
// not a camsim ptc report.
std::vector<PtcComparison> comparePtcReports(const std::string& fileA, const std::string& fileB);

// The table `--compare` prints; returns whether anything moved.
bool formatPtcComparison(const std::vector<PtcComparison>& rows, const std::string& fileA,
                         const std::string& fileB, std::ostream& out);

}  // namespace camsim
