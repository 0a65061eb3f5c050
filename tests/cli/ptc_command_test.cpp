// Tests for `camsim ptc` (cli/ptc_command.cpp): argument parsing and the table as units,
// then the real binary (CAMSIM_BINARY): a preset measured into a directory (CSV, and the
// two PNGs when /usr/bin/python3 has matplotlib), a plot-less run when Python is missing,
// and exit code 2 with a located message (and no file) for a bad sensor.
#include "cli/ptc_command.h"
#include "tests/support/temp_dir.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/args.h"
#include "tests/support/run_command.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

using test::quote;
using test::readFile;
using test::runCommand;
using test::RunResult;

namespace fs = std::filesystem;

TEST(PtcArgs, ParsesSensorOutputAndSeed) {
  PtcArgs a = parsePtcArgs({"ptc", "smartphone-1.4um"});
  EXPECT_EQ(a.sensor, "smartphone-1.4um");
  EXPECT_EQ(a.outputDir, "out");
  EXPECT_FALSE(a.seed.has_value());
  a = parsePtcArgs({"ptc", "-o", "dir", "my.yaml", "--seed", "42"});
  EXPECT_EQ(a.sensor, "my.yaml");
  EXPECT_EQ(a.outputDir, "dir");
  EXPECT_EQ(a.seed, 42u);
  EXPECT_TRUE(parsePtcArgs({"ptc", "--help"}).help);
  EXPECT_NE(ptcUsageText().find("camsim ptc"), std::string::npos);
  EXPECT_NE(ptcUsageText().find("SENSOR"), std::string::npos);
}

TEST(PtcArgs, BadUsageThrows) {
  using Args = std::vector<std::string>;
  for (const Args& args : {Args{"ptc"}, Args{"ptc", "a", "b"}, Args{"ptc", "a", "--bogus"},
                           Args{"ptc", "a", "--seed"}, Args{"ptc", "a", "--seed", "-1"},
                           Args{"ptc", "a", "--seed", "1x"}, Args{"ptc", "a", "-o", ""}}) {
    std::string joined;
    for (const auto& a : args) joined += "'" + a + "' ";
    EXPECT_THROW(parsePtcArgs(args), UsageError) << joined;
  }
}

TEST(PtcTable, ShowsConfiguredMeasuredAndRelativeError) {
  PtcResult m;
  m.systemGainK = 0.202;
  PtcConfigured c;
  c.systemGainK = 0.2;
  const std::string table = formatPtcTable(m, c);
  EXPECT_NE(table.find("system gain K"), std::string::npos) << table;
  EXPECT_NE(table.find("+1.00 %"), std::string::npos) << table;
  for (const char* row : {"quantum efficiency", "temporal dark noise", "μ_e.sat", "μ_e.clip",
                          "μ_p.min", "dynamic range", "DSNU", "PRNU", "linearity error"})
    EXPECT_NE(table.find(row), std::string::npos) << row;
  // Magnitudes the fixed columns cannot hold (a QE of 4e-20 printed as 0.00000, μ_p.min of
  // 6e56 as 57 digits running into the next column: found by probing).
  m.quantumEfficiency = 4.113e-20;
  m.muPMin = 6.421e56;
  const std::string tiny = formatPtcTable(m, c);
  EXPECT_NE(tiny.find("4.113e-20"), std::string::npos) << tiny;
  EXPECT_NE(tiny.find("6.421e+56"), std::string::npos) << tiny;
}

// ---- the binary -----------------------------------------------------------------------------

using test::TempDir;

// `env camsim args` with stdout and stderr captured into files in logDir.
RunResult camsim(const std::string& env, const std::string& args, const fs::path& logDir) {
  return test::runCamsim(args, logDir, env);
}

bool hasMatplotlib() {
  return std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") == 0;
}

std::size_t lineCount(const std::string& text) {
  std::size_t n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

TEST(PtcBinary, MeasuresAPresetAndWritesCsvAndPlots) {
  TempDir dir;
  const fs::path out = dir.path() / "ptc";
  const RunResult r = camsim("", "ptc smartphone-1.4um -o " + quote(out.string()), dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("system gain K"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("channel G"), std::string::npos) << r.out;
  const std::string csv = readFile(out / "ptc_smartphone-1.4um.csv");
  EXPECT_EQ(csv.rfind("level,irradiance_w_m2,mu_p,mu_e,mu_y,var_y,", 0), 0u) << csv.substr(0, 100);
  EXPECT_GE(lineCount(csv), 51u);  // header + ≥ 50 levels
  if (!hasMatplotlib()) GTEST_SKIP() << "no matplotlib for /usr/bin/python3: plots not checked";
  for (const char* png : {"ptc_smartphone-1.4um_ptc.png", "ptc_smartphone-1.4um_snr.png"}) {
    const std::string data = readFile(out / png);
    EXPECT_GT(data.size(), 1000u) << png;
    EXPECT_EQ(data.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << png;
  }
  EXPECT_NE(readFile(out / "ptc_smartphone-1.4um.json").find("\"format\": \"camsim-ptc\""),
            std::string::npos);
  // Nothing else (one ISO: no K(ISO) or noise(ISO) plots), no temporary left behind.
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(out)) files += entry.is_regular_file();
  EXPECT_EQ(files, 4u);
}

TEST(PtcBinary, WithoutPythonWritesTheCsvOnly) {
  TempDir dir;
  const fs::path out = dir.path() / "ptc";
  const RunResult r = camsim("CAMSIM_PYTHON=/nonexistent/python3",
                             "ptc fullframe-d850 -o " + quote(out.string()), dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("plots skipped"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(out / "ptc_fullframe-d850.csv"));
  EXPECT_TRUE(fs::exists(out / "ptc_fullframe-d850.json"));
  EXPECT_FALSE(fs::exists(out / "ptc_fullframe-d850_ptc.png"));
}

TEST(PtcBinary, BadSensorExitsTwoWithALocatedMessageAndWritesNothing) {
  TempDir dir;
  // The smartphone preset with a negative full well on its line.
  std::string text = readFile(fs::path(CAMSIM_LUTS_DIR) / "sensors" / "smartphone-1.4um.yaml");
  const std::size_t at = text.find("full_well_e: ");
  ASSERT_NE(at, std::string::npos);
  text.insert(at + 13, "-");
  const std::size_t line = 1 + lineCount(text.substr(0, at));
  const fs::path bad = dir.path() / "bad.yaml";
  test::writeFile(bad, text);
  const fs::path out = dir.path() / "ptc";
  RunResult r = camsim("", "ptc " + quote(bad.string()) + " -o " + quote(out.string()), dir.path());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("bad.yaml:" + std::to_string(line) + ":"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("full_well_e"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  // An unknown preset and a missing argument are bad input too.
  r = camsim("", "ptc no-such-sensor -o " + quote(out.string()), dir.path());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("<command line>: key 'sensor': unknown sensor preset 'no-such-sensor'"),
            std::string::npos)
      << r.err;  // it said "<input>"
  EXPECT_EQ(camsim("", "ptc", dir.path()).exitCode, 2);
  EXPECT_EQ(camsim("", "ptc --help", dir.path()).exitCode, 0);
}

// Sensors the description allows but that give no photon-transfer curve: a full well of
// 1e-30 e⁻ (every level clipped: NaN in the table, and the plot script failed with exit 1)
// and a stacked xyz layout (no photosite of one channel: a check failed, exit 134). Both
// exit 2 naming the sensor, and write no file (found by probing).
TEST(PtcBinary, SensorsWithoutACurveExitTwoAndWriteNothing) {
  TempDir dir;
  std::string text = readFile(fs::path(CAMSIM_LUTS_DIR) / "sensors" / "smartphone-1.4um.yaml");
  const std::size_t at = text.find("full_well_e: ");
  ASSERT_NE(at, std::string::npos);
  const std::size_t end = text.find('\n', at);
  text.replace(at, end - at, "full_well_e: 1e-30");
  const fs::path tiny = dir.path() / "tiny_well.yaml";
  test::writeFile(tiny, text);
  const fs::path stacked = dir.path() / "stacked.yaml";
  test::writeFile(stacked, R"({"pixel_pitch_um": 2, "qe": {"ideal_xyz": true}, "cfa": "xyz"})");
  const struct {
    fs::path sensor;
    const char* says;
  } cases[] = {{tiny, "gives no photon-transfer curve"}, {stacked, "no photosites of channel"}};
  for (const auto& c : cases) {
    const fs::path out = dir.path() / ("ptc_" + c.sensor.stem().string());
    const RunResult r =
        camsim("", "ptc " + quote(c.sensor.string()) + " -o " + quote(out.string()), dir.path());
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    // Named by its file (it was the description's name, "stacked").
    EXPECT_NE(r.err.find(c.sensor.string() + ": "), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    // The folder is made before measuring (an unwritable one fails first), and removed
    // again, empty, when the measurement is refused (it was left behind).
    EXPECT_FALSE(fs::exists(out)) << out;
  }
}

// An --iso outside a calibrated sensor's iso_table names the option (it said "<input>: key
// 'iso'"); the sensor's own base ISO is not the option's.
TEST(PtcBinary, AnIsoOutsideTheCalibrationNamesTheOption) {
  TempDir dir;
  const fs::path out = dir.path() / "ptc";
  const RunResult r =
      camsim("", "ptc eld-canon-5d4 --iso 50 -o " + quote(out.string()), dir.path());
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("<command line>: key '--iso': ISO 50 is outside the range"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out));
}

// A sensor with a curve at its base ISO but none at the --iso asked for: the option is named,
// with the sensor's file and base ISO (it named the file only, as if the sensor were bad).
TEST(PtcBinary, AnIsoWithoutACurveNamesTheOption) {
  TempDir dir;
  const fs::path out = dir.path() / "ptc";
  const RunResult r =
      camsim("", "ptc smartphone-1.4um --iso 1e7 -o " + quote(out.string()), dir.path());
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("<command line>: key '--iso': at ISO 1e+07 this sensor gives no "
                       "photon-transfer curve"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("smartphone-1.4um.yaml; its base ISO is 50)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace camsim
