// `camsim ptc --compare A.json B.json`: every quantity of report A (an object with "value"
// and "uncertainty") against the same JSON path in B; ISOs are matched by their "iso" value,
// other lists by position. moved ⇔ |a − b| > k·√(u_a² + u_b²) (ptc_report.h); a fit with
// another number of conversion-gain segments has moved too (fits.dark_noise_e, plain numbers
// per ISO for the plot, is not compared). Quantities whose value is null
// (not measurable: the σ_pre/σ_post split with too few ISOs) in both are skipped; one that
// a report lacks has moved. An ISO measured in one report only is listed, not moved. Both
// files must be reports of version 1 with at least one ISO.
#include <cmath>
#include <limits>
#include <optional>
#include <ostream>

#include "cli/ptc_report.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/base/input_file.h"
#include "sensor/base/yaml_reader.h"

namespace camsim {
namespace {

YamlValue loadReport(const std::string& file) {
  const YamlValue root = parseYaml(readInputFile(file, "ptc report"), file);
  if (!root.isMap()) root.fail("expected a camsim ptc report (a JSON object)");
  YamlMap map(root);
  const YamlValue format = map.require("format");
  if (format.string() != "camsim-ptc")
    format.fail("expected \"camsim-ptc\" (a report written by camsim ptc)");
  // The report layout this camsim writes (ptc_report.cpp); another may mean other paths.
  const YamlValue version = map.require("version");
  if (version.number(0.0, 1e9) != 1.0)
    version.fail("this camsim reads reports of version 1 (it is " + version.string() + ")");
  const YamlValue isos = map.require("isos");
  if (isos.items().empty()) isos.fail("a report with no ISO measured: nothing to compare");
  if (!map.require("fits").isMap()) map.require("fits").fail("expected an object");
  return root;
}

std::optional<double> numberOrNull(const YamlValue& v, double lo) {
  if (v.isNull()) return std::nullopt;
  return v.number(lo, std::numeric_limits<double>::max());
}

class Comparer {
 public:
  std::vector<PtcComparison> rows;

  // label: how the table names the value's path (ISO instead of the list index).
  void walk(const YamlValue& a, const YamlValue& b, const std::string& label) {
    if (a.isMap()) {
      if (!b.isMap()) b.fail("expected an object, as in the first report");
      YamlMap ma(a), mb(b);
      if (ma.has("value")) return quantity(ma, mb, label);
      for (const std::string& key : ma.keys()) {
        const YamlValue va = *ma.find(key);
        // A quantity one report has and the other lacks cannot be shown unchanged: moved.
        if (!mb.has(key)) {
          if (va.isMap() || va.isSequence())
            structural(va.key(), label + key, "missing in B", true);
          continue;
        }
        const std::string sub = key == "quantities" ? label : label + key + (va.isMap() ? "." : "");
        walk(va, *mb.find(key), sub);
      }
      for (const std::string& key : mb.keys()) {
        const YamlValue vb = *mb.find(key);
        if (!ma.has(key) && (vb.isMap() || vb.isSequence()))
          structural(vb.key(), label + key, "missing in A", true);
      }
    } else if (a.isSequence()) {
      if (!b.isSequence()) b.fail("expected a list, as in the first report");
      const std::vector<YamlValue> ia = a.items(), ib = b.items();
      if (a.key() == "isos") return matchIsos(ia, ib);
      if (a.key() == "fits.dark_noise_e") return;  // derived per ISO: no quantities
      if (ia.size() != ib.size()) {
        structural(
            a.key(), label,
            std::to_string(ia.size()) + " entries in A, " + std::to_string(ib.size()) + " in B",
            true);
        return;
      }
      for (std::size_t i = 0; i < ia.size(); ++i)
        walk(ia[i], ib[i], label + "[" + std::to_string(i) + "].");
    }
  }

 private:
  static double isoOf(const YamlValue& item) {
    if (!item.isMap()) item.fail("expected an object {iso: …, quantities: …}");
    YamlMap m(item);
    return m.require("iso").number(0.0, 1e9, true);
  }

  void matchIsos(const std::vector<YamlValue>& ia, const std::vector<YamlValue>& ib) {
    for (const YamlValue& a : ia) {
      const double iso = isoOf(a);
      const std::string label = "ISO " + formatShortest(iso) + " ";
      bool found = false;
      for (const YamlValue& b : ib)
        if (isoOf(b) == iso) {
          walk(a, b, label);
          found = true;
        }
      if (!found) structural(a.key(), label, "not measured in B", false);
    }
    for (const YamlValue& b : ib) {
      bool found = false;
      for (const YamlValue& a : ia) found = found || isoOf(a) == isoOf(b);
      if (!found)
        structural(b.key(), "ISO " + formatShortest(isoOf(b)), "not measured in A", false);
    }
  }

  void quantity(YamlMap& ma, YamlMap& mb, const std::string& label) {
    if (!mb.has("value")) mb.self().fail("expected a quantity {value, uncertainty}, as in A");
    const std::optional<double> a = numberOrNull(ma.require("value"), -1e300);
    const std::optional<double> ua = numberOrNull(ma.require("uncertainty"), 0.0);
    const std::optional<double> b = numberOrNull(mb.require("value"), -1e300);
    const std::optional<double> ub = numberOrNull(mb.require("uncertainty"), 0.0);
    std::string name = label;
    if (!name.empty() && name.back() == '.') name.pop_back();
    if (!a && !b) return;
    if (!a || !b) {
      structural(ma.self().key(), name, a ? "not measurable in B" : "not measurable in A", true);
      return;
    }
    PtcComparison c;
    c.path = ma.self().key();
    c.label = name;
    c.a = *a, c.b = *b, c.ua = ua.value_or(0.0), c.ub = ub.value_or(0.0);
    const double combined = std::hypot(c.ua, c.ub);
    const double diff = std::abs(c.a - c.b);
    c.z = combined > 0.0 ? diff / combined
                         : (diff > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
    c.moved = c.z > kCompareCoverage;
    rows.push_back(c);
  }

  void structural(const std::string& path, const std::string& label, const std::string& note,
                  bool moved) {
    PtcComparison c;
    c.path = path;
    c.label = label;
    c.note = note;
    c.moved = moved;
    c.z = std::numeric_limits<double>::quiet_NaN();
    rows.push_back(c);
  }
};

// Pads to `width` code points, with at least one space after the text.
std::string padCell(const std::string& s, std::size_t width) {
  return padColumn(s, width - 1) + " ";
}

std::string withError(double v, double u) {
  return formatNumber(v, 6) + " ± " + formatNumber(u, 2);
}

}  // namespace

std::vector<PtcComparison> comparePtcReports(const std::string& fileA, const std::string& fileB) {
  const YamlValue a = loadReport(fileA);
  const YamlValue b = loadReport(fileB);
  Comparer c;
  YamlMap ma(a), mb(b);
  c.walk(*ma.find("isos"), *mb.find("isos"), "");
  c.walk(*ma.find("fits"), *mb.find("fits"), "fits.");
  return c.rows;
}

bool formatPtcComparison(const std::vector<PtcComparison>& rows, const std::string& fileA,
                         const std::string& fileB, std::ostream& out) {
  out << "camsim ptc --compare: A = " << fileA << ", B = " << fileB << "\n"
      << "moved: |a − b| > " << formatShortest(kCompareCoverage)
      << "·√(u_a² + u_b²) (u: standard errors from the reports)\n\n"
      << padCell("quantity", 48) << padCell("A", 26) << padCell("B", 26) << padCell("z", 8) << "\n";
  int moved = 0;
  for (const PtcComparison& r : rows) {
    moved += r.moved;
    if (!r.note.empty()) {
      out << padCell(r.label, 48) << r.note << (r.moved ? "  MOVED" : "") << "\n";
      continue;
    }
    out << padCell(r.label, 48) << padCell(withError(r.a, r.ua), 26)
        << padCell(withError(r.b, r.ub), 26)
        << padCell(std::isfinite(r.z) ? formatFixed(r.z, 2) : "inf", 8) << (r.moved ? "MOVED" : "")
        << "\n";
  }
  out << "\n"
      << rows.size() << " quantities compared, " << moved << " moved"
      << (moved ? " (exit code 1)" : "") << "\n";
  return moved > 0;
}

}  // namespace camsim
