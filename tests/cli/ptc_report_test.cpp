// Tests for cli/ptc_report.cpp and cli/ptc_compare.cpp: the JSON report of `camsim ptc` and
// `camsim ptc --compare`. Reports are measured with the library on a small region (192 × 192
// photosites, 50 levels, ~2 s each in Release; measured once) and compared by the real binary: a 3 %
// conversion-gain change is flagged (exit 1), a re-measurement with another noise seed is not
// (exit 0), and a file that is not a report exits 2 naming the file and the JSON path.
#include "cli/ptc_report.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/args.h"
#include "cli/ptc_command.h"
#include "sensor/base/yaml_reader.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim::ptc_report_test {
namespace {

namespace fs = std::filesystem;
using test::quote;

SensorSpec sensorWithGain(double conversionGain) {
  const std::string text =
      "name: test-compare\n"
      "pixel_pitch_um: 4.0\n"
      "cfa: RGGB\n"
      "qe: {curves: cameras/nikon_d850.csv, peak_qe: 0.5}\n"
      "full_well_e: 20000\n"
      "conversion_gain_e_per_dn: " +
      std::to_string(conversionGain) +
      "\n"
      "base_iso: 100\n"
      "adc_bits: 16\n"
      "black_level_dn: 1024\n"
      "read_noise_e: 2.0\n"
      "read_noise_post_dn: 3.0\n"
      "row_noise_dn: 0.5\n"
      "dsnu_e: 0.5\n"
      "prnu_percent: 0.5\n"
      "pattern_seed: 3\n";
  return parseSensorSpec(text, "test-compare.yaml", CAMSIM_LUTS_DIR, CAMSIM_LUTS_DIR);
}

// The report of `sensor` at ISO 100 and 800 with noise seed `seed`.
std::string report(const SensorSpec& sensor, std::uint64_t seed) {
  PtcOptions options;
  options.width = options.height = 192;
  options.levels = 50;
  options.seed = seed;
  std::vector<PtcIsoReport> isos;
  std::vector<IsoPoint> points;
  for (double iso : {100.0, 800.0}) {
    options.iso = iso;
    PtcIsoReport r;
    r.measured = measurePhotonTransfer(sensor, options);
    r.configured = configuredPhotonTransfer(sensor, options);
    r.uncertainty = photonTransferUncertainty(r.measured);
    points.push_back(isoPoint(r.measured, r.uncertainty));
    isos.push_back(r);
  }
  return formatPtcJson(sensor, options, isos, fitAcrossIsos(points));
}

test::RunResult compare(const fs::path& dir, const std::string& a, const std::string& b) {
  return test::runCamsim(
      "ptc --compare " + quote((dir / a).string()) + " " + quote((dir / b).string()), dir);
}

// The row of the --compare table that starts with `label`.
std::string tableRow(const std::string& out, const std::string& label) {
  const std::size_t at = out.find(label);
  return at == std::string::npos ? "" : out.substr(at, out.find('\n', at) - at);
}

// One test for the three measured reports (measured once: six measurements, ~15 s).
TEST(PtcCompare, ReportsAnotherSeedPassesAThreePercentGainChangeMoves) {
  test::TempDir dir;
  test::writeFile(dir.path() / "a.json", report(sensorWithGain(4.0), 1));
  test::writeFile(dir.path() / "b.json", report(sensorWithGain(4.0), 2));
  test::writeFile(dir.path() / "c.json", report(sensorWithGain(4.0 * 1.03), 2));

  // The report holds every quantity with unit, value, uncertainty (and configured values).
  const YamlValue root =
      parseYaml(test::readFile(dir.path() / "a.json"), (dir.path() / "a.json").string());
  YamlMap m(root);
  EXPECT_EQ(m.require("format").string(), "camsim-ptc");
  const std::vector<YamlValue> isos = m.require("isos").items();
  ASSERT_EQ(isos.size(), 2u);
  YamlMap iso(isos[1]);
  EXPECT_EQ(iso.require("iso").number(), 800.0);
  YamlMap q(iso.require("quantities"));
  for (const char* name : {"system_gain_k",
                           "responsivity_r",
                           "quantum_efficiency",
                           "mu_y_dark",
                           "sigma2_y_dark",
                           "sigma_y_dark",
                           "dark_noise_e",
                           "mu_e_clip",
                           "mu_p_sat",
                           "mu_e_sat",
                           "snr_max_db",
                           "mu_p_min",
                           "dynamic_range_db",
                           "dsnu_e",
                           "prnu_percent",
                           "linearity_error_percent",
                           "row_noise_dn",
                           "row_pattern_dn",
                           "read_noise_gaussian_dn",
                           "normal_ppcc",
                           "tukey_lambda",
                           "tukey_scale_dn",
                           "tukey_ppcc"}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(q.has(name));
    YamlMap v(*q.find(name));
    EXPECT_FALSE(v.require("unit").string().empty());
    EXPECT_GE(v.require("uncertainty").number(), 0.0);
    v.require("value").number();
  }
  YamlMap k(*q.find("system_gain_k"));
  EXPECT_NEAR(k.require("configured").number(), 2.0, 1e-9);  // 800/100/4
  EXPECT_NEAR(k.require("value").number(), 2.0, 0.02 * 2.0);
  EXPECT_GT(k.require("uncertainty").number(), 0.0);
  YamlMap row(*q.find("row_noise_dn"));
  EXPECT_NEAR(row.require("value").number(), 0.5, 0.1 * 0.5);
  YamlMap fits(m.require("fits"));
  ASSERT_EQ(fits.require("gain_segments").items().size(), 1u);
  YamlMap split(fits.require("dark_noise_split"));
  EXPECT_TRUE(split.require("fitted").boolean());
  YamlMap post(split.require("sigma_post_dn"));
  EXPECT_NEAR(post.require("value").number(), 3.0, 0.03 * 3.0);

  // Another noise seed: nothing moves.
  test::RunResult r = compare(dir.path(), "a.json", "b.json");
  EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("ISO 800 system_gain_k"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" 0 moved"), std::string::npos) << r.out;
  std::printf("[ measured ] %s\n[ measured ] %s\n",
              tableRow(r.out, "ISO 100 system_gain_k").c_str(),
              tableRow(r.out, "ISO 800 system_gain_k").c_str());

  // A 3 % conversion-gain change: K at each ISO (u ≈ 0.25 %: ≈ 8 combined standard errors)
  // and the fit's g move.
  r = compare(dir.path(), "a.json", "c.json");
  EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
  for (const char* label :
       {"ISO 100 system_gain_k", "ISO 800 system_gain_k", "fits.gain_segments[0].gain_per_iso"}) {
    const std::string line = tableRow(r.out, label);
    EXPECT_NE(line.find("MOVED"), std::string::npos) << label << ": " << line << "\n" << r.out;
    std::printf("[ measured ] %s\n", line.c_str());
  }
}

// A minimal valid report, and broken ones: exit 2 naming the file and the JSON path.
TEST(PtcCompare, BadFilesExitTwoNamingFileAndPath) {
  test::TempDir dir;
  const std::string good =
      "{\"format\": \"camsim-ptc\", \"version\": 1, \"isos\": [{\"iso\": 100, \"quantities\": "
      "{\"system_gain_k\": {\"unit\": \"DN/e-\", \"value\": 0.25, \"uncertainty\": 0.001}}}],"
      " \"fits\": {}}\n";
  test::writeFile(dir.path() / "a.json", good);
  test::RunResult r = compare(dir.path(), "a.json", "a.json");
  EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
  std::string bad = good;
  bad.replace(bad.find("0.25"), 4, "\"x\"");
  test::writeFile(dir.path() / "bad.json", bad);
  r = compare(dir.path(), "a.json", "bad.json");
  EXPECT_EQ(r.exitCode, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("bad.json:1:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("isos[0].quantities.system_gain_k.value"), std::string::npos) << r.err;
  test::writeFile(dir.path() / "other.json", "{\"format\": \"something\", \"isos\": []}\n");
  r = compare(dir.path(), "other.json", "a.json");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("other.json:1:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("format"), std::string::npos) << r.err;
  r = compare(dir.path(), "a.json", "missing.json");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("missing.json"), std::string::npos) << r.err;
  test::writeFile(dir.path() / "broken.json", "{\"format\": \"camsim-ptc\", \"isos\": [\n");
  r = compare(dir.path(), "broken.json", "a.json");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("broken.json"), std::string::npos) << r.err;
  // Both valid, one with a second ISO: listed, not counted as moved.
  std::string two = good;
  two.replace(two.find("]"), 1,
              ", {\"iso\": 200, \"quantities\": {\"system_gain_k\": {\"unit\": \"DN/e-\", "
              "\"value\": 0.5, \"uncertainty\": 0.001}}}]");
  test::writeFile(dir.path() / "two.json", two);
  r = compare(dir.path(), "a.json", "two.json");
  EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("not measured in A"), std::string::npos) << r.out;
  // Found by probing, each exit 0 before: another version or none, no ISO at all, and a
  // quantity one report lacks ("missing in B", then "0 moved").
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = good;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  const struct {
    std::string text, says;
    int exitCode;
  } cases[] = {
      {replaced("\"version\": 1", "\"version\": 2"), "reads reports of version 1", 2},
      {replaced("\"version\": 1, ", ""), "version", 2},
      {"{\"format\": \"camsim-ptc\", \"version\": 1, \"isos\": [], \"fits\": {}}\n",
       "no ISO measured", 2},
      {replaced("\"system_gain_k\"", "\"read_noise_e\""), "MOVED", 1},
  };
  for (const auto& c : cases) {
    test::writeFile(dir.path() / "c.json", c.text);
    r = compare(dir.path(), "a.json", "c.json");
    EXPECT_EQ(r.exitCode, c.exitCode) << c.text << r.out << r.err;
    EXPECT_NE((r.out + r.err).find(c.says), std::string::npos) << c.text << r.out << r.err;
  }
}

TEST(PtcArgs, IsoListAndCompare) {
  PtcArgs a = parsePtcArgs({"ptc", "fullframe-d850", "--iso", "1600", "64", "400", "64"});
  EXPECT_EQ(a.isos, (std::vector<double>{64, 400, 1600}));
  a = parsePtcArgs({"ptc", "--compare", "a.json", "b.json"});
  EXPECT_EQ(a.compare, (std::vector<std::string>{"a.json", "b.json"}));
  using Args = std::vector<std::string>;
  for (const Args& args :
       {Args{"ptc", "s", "--iso"}, Args{"ptc", "s", "--iso", "0"}, Args{"ptc", "s", "--iso", "x"},
        Args{"ptc", "s", "--iso", "-5"}, Args{"ptc", "s", "--iso", "0.5"},
        Args{"ptc", "s", "--iso", "1e8"}, Args{"ptc", "s", "--iso", "inf"},
        Args{"ptc", "--compare", "a.json"}, Args{"ptc", "s", "--compare", "a.json", "b.json"}})
    EXPECT_THROW(parsePtcArgs(args), UsageError) << args.back();
  // The capture range render's and expose's --iso have ([1, 1e7]: kMinIso, kMaxIso); ptc's
  // own copy accepted 0.5.
  try {
    parsePtcArgs({"ptc", "s", "--iso", "0.5"});
    ADD_FAILURE() << "--iso 0.5 accepted";
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "--iso: ISO 0.5 is outside [1, 1e+07]");
  }
}

}  // namespace
}  // namespace camsim::ptc_report_test
