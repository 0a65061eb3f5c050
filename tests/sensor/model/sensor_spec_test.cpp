// Tests for sensor/sensor_spec: the presets, the YAML format's QE forms, validation with
// located errors, and the derived quantities (dark current, saturation).
#include "sensor/model/sensor_spec.h"
#include "sensor/spectra/cie.h"

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"
#include "tests/support/lut_paths.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;

// A valid description; tests replace or append lines (line numbers are 1-based).
const std::vector<std::string> kBase = {
    "name: test",                                          // 1
    "pixel_pitch_um: 4.0",                                 // 2
    "cfa: RGGB",                                           // 3
    "qe: {curves: cameras/nikon_d850.csv, peak_qe: 0.5}",  // 4
    "full_well_e: 20000",                                  // 5
    "conversion_gain_e_per_dn: 2.0",                       // 6
    "adc_bits: 12",                                        // 7
    "black_level_dn: 100",                                 // 8
    "read_noise_e: 2.0",                                   // 9
};

std::string join(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  return text;
}
std::string replaced(int line, const std::string& content) {
  std::vector<std::string> lines = kBase;
  lines.at(static_cast<size_t>(line - 1)) = content;
  return join(lines);
}
std::string appended(const std::string& content) {
  return join(kBase) + content + "\n";
}

SensorSpec parse(const std::string& text, const fs::path& baseDir = fs::path(".")) {
  return parseSensorSpec(text, "sensor.yaml", baseDir, test::kLuts);
}

struct Expected {
  std::string text;
  std::string key;
  int line;
  int column;  // 0: not checked
};

TEST(SensorSpec, MalformedDescriptionsAreRejectedWithLineAndKey) {
  const std::vector<Expected> cases = {
      {replaced(2, "pixel_pich_um: 4.0"), "pixel_pich_um", 2, 1},      // typo of a required key
      {appended("fill_factor: 1.5"), "fill_factor", 10, 14},           // > 1
      {appended("fill_factor: 0"), "fill_factor", 10, 14},             // must be > 0
      {replaced(7, "adc_bits: 17"), "adc_bits", 7, 11},                // 1..16
      {replaced(7, "adc_bits: 12.5"), "adc_bits", 7, 11},              // not an integer
      {replaced(8, "black_level_dn: 4095"), "black_level_dn", 8, 17},  // = white level (12 bit)
      {replaced(9, "read_noise_e: -1"), "read_noise_e", 9, 15},        // negative noise
      {replaced(5, "full_well_e: 0"), "full_well_e", 5, 14},           // must be > 0
      {replaced(2, "pixel_pitch_um: abc"), "pixel_pitch_um", 2, 17},   // not a number
      {replaced(2, "pixel_pitch_um: -4"), "pixel_pitch_um", 2, 17},    // negative pitch
      {replaced(3, "cfa: RGBG"), "cfa", 3, 6},                         // unknown layout
      {replaced(4, "qe: {curves: cameras/nope.csv, peak_qe: 0.5}"), "qe.curves", 4, 14},
      // A name the OS rejects (> NAME_MAX): "not found", not a filesystem_error (fuzzer).
      {replaced(4, "qe: {curves: " + std::string(300, 'n') + ".csv, peak_qe: 0.5}"), "qe.curves", 4,
       14},
      {replaced(4, "qe: {curves: cameras/nikon_d850.csv, peak_qe: 1.5}"), "qe.peak_qe", 4, 47},
      {replaced(4, "qe: {curves: cameras/nikon_d850.csv}"), "qe.peak_qe", 4, 5},  // missing
      {replaced(4, "qe: {ideal_xyz: true}"), "qe.ideal_xyz", 4, 17},  // RGGB is not X, Y, Z
      {replaced(4, "qe: {curves: cameras/nikon_d850.csv, peak_qe: 0.5, csv: a.csv}"), "qe.csv", 4,
       0},
      {replaced(3, "cfa: mono"), "qe.curves", 4, 14},  // no column 'y'
      {replaced(3, "cfa: {tile: [[0, 1], [1, 3]], channels: [R, G, B]}"), "cfa.tile[1][1]", 3, 0},
      {replaced(3, "cfa: {tile: [[0, 1], [2]], channels: [R, G, B]}"), "cfa.tile[1]", 3, 0},
      {replaced(3, "cfa: {tile: [[0, 1], [1, 0]], channels: [R, G, B]}"), "cfa.tile", 3, 0},
      {replaced(3, "cfa: {tile: [[0, 1], [1, 2]], channels: [R, G, G]}"), "cfa.channels[2]", 3, 0},
      {appended("ir_cut: {cutoff_nm: 650}"), "ir_cut.width_nm", 10, 9},
      {appended("ir_cut: {cutoff_nm: 650, width_nm: 20, slope: 2}"), "ir_cut.slope", 10, 0},
      {appended("dark_doubling_c: 0"), "dark_doubling_c", 10, 18},
      // 1e-300: an infinite gain, refused as "<input>: key 'iso'" when the model was built.
      {replaced(6, "conversion_gain_e_per_dn: 1e-300"), "conversion_gain_e_per_dn", 6, 27},
      {appended("prnu_percent: 150"), "prnu_percent", 10, 15},
      {appended("noiseless: maybe"), "noiseless", 10, 12},
      // Printed "photon transfer of  at ISO 50" (found by probing).
      {replaced(1, "name: ''"), "name", 1, 7},
      {replaced(1, "name: \"a\\tb\""), "name", 1, 7},
      {appended("gain: 3"), "gain", 10, 1},                          // unknown key
      {appended("read_noise_e: 3"), "read_noise_e", 10, 1},          // duplicate key
      {join({kBase[0], kBase[1], kBase[2], kBase[4]}), "qe", 1, 1},  // qe missing
  };
  for (const Expected& c : cases) {
    try {
      parse(c.text);
      ADD_FAILURE() << "accepted:\n" << c.text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, "sensor.yaml");
      EXPECT_EQ(e.key(), c.key) << e.what();
      EXPECT_EQ(e.where().line, c.line) << e.what();
      if (c.column > 0) {
        EXPECT_EQ(e.where().column, c.column) << e.what();
      }
      EXPECT_GT(e.where().column, 0) << e.what();
    }
  }
}

TEST(SensorSpec, SyntaxErrorsAreLocated) {
  try {
    parse(replaced(4, "qe: {curves: cameras/nikon_d850.csv, peak_qe: 0.5"));
    FAIL() << "accepted an unclosed brace";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 4);
  }
}

TEST(SensorSpec, ParsesTheBaseDescription) {
  const SensorSpec s = parse(join(kBase));
  EXPECT_EQ(s.name, "test");
  EXPECT_DOUBLE_EQ(s.pixelPitchM, 4e-6);
  EXPECT_EQ(s.cfa.name, "RGGB");
  ASSERT_EQ(s.qe.size(), 3u);
  // Scaled so that the maximum over all channels is peak_qe (G peaks at 1 in the table).
  EXPECT_NEAR(std::max({s.qe[0].maxValue(), s.qe[1].maxValue(), s.qe[2].maxValue()}), 0.5, 1e-6);
  EXPECT_NEAR(s.qe[1].maxValue(), 0.5, 1e-6);
  EXPECT_NEAR(s.qe[0].maxValue(), 0.5 * 0.675574, 1e-6);  // r's peak in nikon_d850.csv
  EXPECT_GT(s.qe[0](620.0f), s.qe[2](620.0f));            // channel 0 is R, channel 2 is B
  EXPECT_GT(s.qe[2](450.0f), s.qe[0](450.0f));
  EXPECT_EQ(s.qe[1](800.0f), 0.0f);  // zero beyond the table
  EXPECT_EQ(s.adcBits, 12);
  EXPECT_EQ(s.whiteLevelDn(), 4095.0);
  EXPECT_EQ(s.blackLevelDn, 100.0);
  // Defaults of the keys not given.
  EXPECT_EQ(s.fillFactor, 1.0);
  EXPECT_EQ(s.baseIso, 100.0);
  EXPECT_EQ(s.prnuFraction, 0.0);
  EXPECT_EQ(s.patternSeed, 1u);
  EXPECT_FALSE(s.noiseless);
  EXPECT_EQ(parse(join({kBase[1], kBase[2], kBase[3]})).name, "sensor");  // default name: file stem
}

TEST(SensorSpec, CustomTileAndIrCut) {
  const SensorSpec plain = parse(join(kBase));
  const SensorSpec s = parse(replaced(3, "cfa: {tile: [[2, 1], [1, 0]], channels: [R, G, B]}") +
                             "ir_cut: {cutoff_nm: 650, width_nm: 20}\n");
  EXPECT_EQ(s.cfa.name, "custom");
  EXPECT_EQ(s.cfa.channelAt(0, 0), 2);
  EXPECT_EQ(s.cfa.channelAt(1, 1), 0);
  // Logistic edge: 50 % at the cutoff, 90 % and 10 % half a width either side.
  EXPECT_NEAR(s.qe[0](650.0f) / plain.qe[0](650.0f), 0.5, 1e-5);
  EXPECT_NEAR(s.qe[0](640.0f) / plain.qe[0](640.0f), 0.9, 1e-5);
  EXPECT_NEAR(s.qe[0](660.0f) / plain.qe[0](660.0f), 0.1, 1e-5);
  EXPECT_NEAR(s.qe[1](500.0f) / plain.qe[1](500.0f), 1.0, 1e-5);
}

TEST(SensorSpec, CsvQeAndIrCutTablesResolveNextToTheDescription) {
  const test::TempDir dir;
  test::writeFile(dir.path() / "qe.csv", "wavelength_nm,mono,other\n400,0.2,0.9\n700,0.4,0.9\n");
  test::writeFile(dir.path() / "ir.csv", "wavelength_nm,t\n400,1\n600,1\n700,0\n");
  test::writeFile(dir.path() / "cam.yaml",
                  "pixel_pitch_um: 2\ncfa: mono\nqe: {csv: qe.csv, columns: [mono]}\n"
                  "ir_cut: {csv: ir.csv}\n");
  const SensorSpec s = loadSensorSpec((dir.path() / "cam.yaml").string(), test::kLuts);
  EXPECT_EQ(s.name, "cam");
  ASSERT_EQ(s.qe.size(), 1u);
  EXPECT_NEAR(s.qe[0](400.0f), 0.2, 1e-6);  // absolute QE: no peak_qe, no scaling
  EXPECT_NEAR(s.qe[0](550.0f), 0.3, 1e-6);
  EXPECT_NEAR(s.qe[0](650.0f), (0.2 + 0.2 * 250.0 / 300.0) * 0.5, 1e-6);  // × IR cut (0.5)
  EXPECT_EQ(s.qe[0](700.0f), 0.0f);
  // The files it was read from, in order (the bench's reference key and the render sidecar
  // list them): the description, then its tables.
  EXPECT_EQ(s.sourceFiles, (std::vector<fs::path>{dir.path() / "cam.yaml", dir.path() / "qe.csv",
                                                  dir.path() / "ir.csv"}));
  // Absolute QE above 1 without peak_qe is an error, at the csv key.
  test::writeFile(dir.path() / "big.csv", "wavelength_nm,y\n400,2\n700,2\n");
  try {
    parse("pixel_pitch_um: 2\nqe: {csv: big.csv, columns: [y]}\n", dir.path());
    ADD_FAILURE() << "accepted QE > 1";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "qe.csv");
    EXPECT_EQ(e.where().line, 2);
  }
  EXPECT_NEAR(
      parse("pixel_pitch_um: 2\nqe: {csv: big.csv, columns: [y], peak_qe: 0.4}\n", dir.path())
          .qe[0](500.0f),
      0.4, 1e-6);
  // A channel without response within 360-830 nm (an IR-only curve, or one the IR-cut filter
  // blocks) is refused at its key: it was found only after rendering, as a white-balance
  // error of the scene.
  test::writeFile(dir.path() / "ir_qe.csv", "wavelength_nm,r,g\n900,0.5,0.5\n1000,0.5,0.5\n");
  test::writeFile(dir.path() / "red.csv",
                  "wavelength_nm,r,g\n360,0,0.5\n590,0,0.5\n600,0.5,0.5\n830,0.5,0.5\n");
  test::writeFile(dir.path() / "cut.csv", "wavelength_nm,t\n360,1\n550,1\n560,0\n830,0\n");
  const struct {
    std::string text, key, says;
  } blind[] = {
      {"cfa: {tile: [[0, 1], [1, 0]], channels: [R, G]}\nqe: {csv: ir_qe.csv, columns: [r, g]}\n",
       "qe", "channel R has no response within 360-830 nm"},
      {"cfa: {tile: [[0, 1], [1, 0]], channels: [R, G]}\nqe: {csv: red.csv, columns: [r, g]}\n"
       "ir_cut: {csv: cut.csv}\n",
       "ir_cut",
       "channel R has no response within 360-830 nm once the IR-cut filter is applied (the "
       "range camsim traces)"},
  };
  for (const auto& c : blind) {
    try {
      parse("pixel_pitch_um: 2\n" + c.text, dir.path());
      ADD_FAILURE() << "accepted:\n" << c.text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), c.key) << e.what();
      EXPECT_NE(e.message().find(c.says), std::string::npos) << e.what();
    }
  }
}

TEST(SensorSpec, PresetsLoad) {
  const SensorSpec xyz = loadSensorSpec("ideal-xyz", test::kLuts);
  EXPECT_TRUE(xyz.noiseless);
  EXPECT_TRUE(xyz.cfa.isStacked());
  ASSERT_EQ(xyz.qe.size(), 3u);
  EXPECT_NEAR(xyz.qe[1].maxValue(), 1.0, 1e-6);  // the Y channel peaks at 1
  // Electrons count photons (∝ energy · λ): QE·λ ∝ cmf makes them proportional to XYZ.
  const Cie1931& cie = Cie1931::get();
  const Spectrum* cmf[3] = {&cie.x, &cie.y, &cie.z};
  for (int c = 0; c < 3; ++c) {
    const double ref = static_cast<double>(xyz.qe[static_cast<size_t>(c)](555.0f)) * 555.0 /
                       static_cast<double>((*cmf[c])(555.0f));
    for (float nm : {420.0f, 450.0f, 500.0f, 600.0f, 650.0f}) {
      if (static_cast<double>((*cmf[c])(nm)) < 1e-3) continue;  // z̄ vanishes in the red
      EXPECT_NEAR(static_cast<double>(xyz.qe[static_cast<size_t>(c)](nm)) *
                      static_cast<double>(nm) / static_cast<double>((*cmf[c])(nm)) / ref,
                  1.0, 1e-5)
          << c << " at " << nm;
    }
  }
  EXPECT_EQ(xyz.whiteLevelDn(), 65535.0);
  EXPECT_EQ(xyz.readNoiseE, 0.0);

  const SensorSpec phone = loadSensorSpec("smartphone-1.4um", test::kLuts);
  EXPECT_DOUBLE_EQ(phone.pixelPitchM, 1.4e-6);
  EXPECT_EQ(phone.cfa.name, "RGGB");
  ASSERT_EQ(phone.qe.size(), 3u);
  EXPECT_NEAR(std::max({phone.qe[0].maxValue(), phone.qe[1].maxValue(), phone.qe[2].maxValue()}),
              0.6, 1e-6);
  EXPECT_EQ(phone.fullWellE, 6000.0);
  EXPECT_EQ(phone.readNoiseE, 5.0);
  EXPECT_EQ(phone.adcBits, 10);
  EXPECT_EQ(phone.blackLevelDn, 64.0);
  EXPECT_DOUBLE_EQ(phone.prnuFraction, 0.007);
  // The ADC range roughly matches the full well at base ISO (within 5 %).
  const double adcRangeE = (phone.whiteLevelDn() - phone.blackLevelDn) * phone.conversionGainEPerDn;
  EXPECT_NEAR(adcRangeE / phone.fullWellE, 1.0, 0.05);
  EXPECT_DOUBLE_EQ(phone.saturationElectrons(phone.baseIso), 959.0 * 6.25);

  const SensorSpec d850 = loadSensorSpec("fullframe-d850", test::kLuts);
  EXPECT_DOUBLE_EQ(d850.pixelPitchM, 4.35e-6);
  EXPECT_EQ(d850.adcBits, 14);
  EXPECT_EQ(d850.whiteLevelDn(), 16383.0);
  EXPECT_EQ(d850.blackLevelDn, 400.0);
  EXPECT_EQ(d850.fullWellE, 50000.0);
  EXPECT_NEAR(d850.qe[1].maxValue(), 0.55, 1e-6);
  EXPECT_DOUBLE_EQ(d850.saturationElectrons(d850.baseIso), 50000.0);
}

TEST(SensorSpec, UnknownPresetListsThePresets) {
  try {
    loadSensorSpec("no-such-sensor", test::kLuts);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("smartphone-1.4um"), std::string::npos) << e.what();
  }
  EXPECT_THROW(loadSensorSpec("/no/such/file.yaml", test::kLuts), InputError);
  // A directory with a description's name is not read as an empty (invalid) description.
  const test::TempDir dir;
  fs::create_directories(dir.path() / "folder.yaml");
  try {
    loadSensorSpec((dir.path() / "folder.yaml").string(), test::kLuts);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("no sensor description file"), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("folder.yaml"), std::string::npos) << e.what();
  }
}

TEST(SensorSpec, DarkCurrentDoublesPerDoublingInterval) {
  SensorSpec s;
  s.darkCurrentEPerS = 3.0;
  s.darkReferenceC = 25.0;
  s.darkDoublingC = 6.0;
  s.temperatureC = 25.0;
  EXPECT_DOUBLE_EQ(s.darkCurrentAtTemperature(), 3.0);
  s.temperatureC = 31.0;
  EXPECT_DOUBLE_EQ(s.darkCurrentAtTemperature(), 6.0);
  s.temperatureC = 43.0;
  EXPECT_DOUBLE_EQ(s.darkCurrentAtTemperature(), 24.0);
  s.temperatureC = 19.0;
  EXPECT_DOUBLE_EQ(s.darkCurrentAtTemperature(), 1.5);
  EXPECT_NEAR(loadSensorSpec("smartphone-1.4um", test::kLuts).darkCurrentAtTemperature(),
              2.0 * std::exp2(15.0 / 6.0), 1e-12);
}

// Found by probing: each key in range, 2^((500 − 25)/0.001) overflowed: with a dark current
// every photosite saturated silently, without one 0 × inf made the expected electrons NaN
// (then cast to DN). Refused at the temperature key; no dark current stays no dark current.
TEST(SensorSpec, DarkCurrentOverflowingAtTemperatureIsRefused) {
  const std::string hot = "dark_doubling_c: 0.001\ntemperature_c: 500";
  for (const auto& [text, line] :
       {std::pair{appended("dark_current_e_per_s: 5\n" + hot), 12},
        std::pair{appended("hot_pixels: {fraction: 0.01, dark_current_e_per_s: 50}\n" + hot), 12},
        std::pair{appended("dark_current_e_per_s: 1e8\ntemperature_c: 50"), 11}}) {
    try {
      parse(text);
      ADD_FAILURE() << "accepted:\n" << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "temperature_c") << e.what();
      EXPECT_EQ(e.where().line, line) << e.what();
      EXPECT_NE(e.message().find("above 1e9 e⁻/s"), std::string::npos) << e.what();
    }
  }
  const SensorSpec none = parse(appended("dark_current_e_per_s: 0\n" + hot));
  EXPECT_EQ(none.darkCurrentAtTemperature(), 0.0);
  EXPECT_EQ(none.darkAtTemperature(0.0), 0.0);
  // Within the range: accepted, the law as above.
  EXPECT_DOUBLE_EQ(
      parse(appended("dark_current_e_per_s: 1e8\ntemperature_c: 31")).darkCurrentAtTemperature(),
      2e8);
}

TEST(SensorSpec, SaturationIsTheFullWellOrTheAdcRange) {
  SensorSpec s;
  s.adcBits = 12;
  s.blackLevelDn = 95.0;  // range 4000 DN
  s.conversionGainEPerDn = 2.0;
  s.baseIso = 100.0;
  s.fullWellE = 10000.0;
  EXPECT_DOUBLE_EQ(s.systemGain(100.0), 0.5);
  EXPECT_DOUBLE_EQ(s.saturationElectrons(100.0), 8000.0);  // ADC: 4000 DN / 0.5 DN/e⁻
  EXPECT_DOUBLE_EQ(s.saturationElectrons(400.0), 2000.0);  // 4× gain, 4× fewer electrons
  EXPECT_DOUBLE_EQ(s.saturationElectrons(50.0), 10000.0);  // the full well clips first
  s.fullWellE = 5000.0;
  EXPECT_DOUBLE_EQ(s.saturationElectrons(100.0), 5000.0);
}

}  // namespace
}  // namespace camsim
