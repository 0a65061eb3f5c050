#include "sensor/model/sensor_spec.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include "sensor/base/file_status.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/base/input_file.h"
#include "sensor/base/table_search.h"
#include "sensor/base/yaml_reader.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {
namespace fs = std::filesystem;

double SensorSpec::darkCurrentAtTemperature() const {
  return darkAtTemperature(darkCurrentEPerS);
}

double SensorSpec::darkAtTemperature(double ePerSAtReference) const {
  if (ePerSAtReference == 0.0) return 0.0;  // not 0 × an overflowed factor (NaN)
  return ePerSAtReference * std::exp2((temperatureC - darkReferenceC) / darkDoublingC);
}

double SensorSpec::systemGain(double iso) const {
  return noiseAtIso(*this, iso).systemGainK;
}

double SensorSpec::saturationElectrons(double iso) const {
  // The ADC saturates when n·K + black level reaches the white level.
  const NoiseAtIso n = noiseAtIso(*this, iso);
  return std::min(n.fullWellE, (whiteLevelDn() - blackLevelDn) / n.systemGainK);
}

namespace {

constexpr int kMaxTileSize = 16;
constexpr int kMaxChannels = 16;

// A CSV named in the description (TableSearch: absolute, or relative to the description's
// folder, then lutsDir/spectra, then lutsDir), read.
SpectralTable readTable(const YamlValue& file, const TableSearch& tables) {
  const fs::path found = tables.find(file, file.string());
  try {
    return readSpectralCsv(found);
  } catch (const InputError& e) {
    file.fail(std::string("bad spectral table: ") + e.what());
  }
}

Spectrum tableColumn(const SpectralTable& table, const YamlValue& where,
                     const std::string& column) {
  size_t index = 0;
  try {
    index = table.columnIndex(column);
  } catch (const InputError& e) {
    where.fail(e.message() + " in " + table.source);
  }
  const Spectrum s = table.spectrum(index, Extrapolation::kZero);
  if (s.minValue() < 0.0)
    where.fail("column '" + column + "' of " + table.source + " has negative values");
  return s;
}

CfaLayout parseCfa(const YamlValue& value) {
  if (value.isScalar()) {
    try {
      return CfaLayout::fromName(value.string());
    } catch (const InputError& e) {
      value.fail(e.message());
    }
  }
  YamlMap map(value);
  CfaLayout cfa;
  cfa.name = "custom";
  const YamlValue channels = map.require("channels");
  cfa.channels.clear();
  for (const YamlValue& item : channels.items()) {
    const std::string name = item.string();
    if (name.empty()) item.fail("empty channel name");
    if (std::find(cfa.channels.begin(), cfa.channels.end(), name) != cfa.channels.end())
      item.fail("duplicate channel name '" + name + "'");
    cfa.channels.push_back(name);
  }
  if (cfa.channels.empty() || cfa.channels.size() > kMaxChannels)
    channels.fail("expected 1 to " + std::to_string(kMaxChannels) + " channel names");
  const auto channelCount = static_cast<std::int64_t>(cfa.channels.size());
  const YamlValue tile = map.require("tile");
  const std::vector<YamlValue> rows = tile.items();
  if (rows.empty() || rows.size() > kMaxTileSize)
    tile.fail("expected 1 to " + std::to_string(kMaxTileSize) + " rows of channel indices");
  cfa.tile.clear();
  cfa.height = static_cast<int>(rows.size());
  cfa.width = 0;
  for (const YamlValue& row : rows) {
    const std::vector<YamlValue> cells = row.items();
    if (cells.empty() || cells.size() > kMaxTileSize)
      row.fail("expected 1 to " + std::to_string(kMaxTileSize) + " channel indices");
    if (cfa.width == 0) cfa.width = static_cast<int>(cells.size());
    if (static_cast<int>(cells.size()) != cfa.width)
      row.fail("all tile rows must have the same length (" + std::to_string(cfa.width) + ")");
    for (const YamlValue& cell : cells)
      cfa.tile.push_back(static_cast<int>(cell.integer(0, channelCount - 1)));
  }
  for (int c = 0; c < static_cast<int>(channelCount); ++c) {
    if (std::find(cfa.tile.begin(), cfa.tile.end(), c) == cfa.tile.end())
      tile.fail("channel " + std::to_string(c) + " ('" + cfa.channels[static_cast<size_t>(c)] +
                "') appears nowhere in the tile");
  }
  map.finish({"tile", "channels"});
  return cfa;
}

// peak_qe / max over all channels, applied to every channel.
void scaleToPeak(std::vector<Spectrum>& qe, double peak, const YamlValue& where) {
  double maxValue = 0.0;
  for (const Spectrum& s : qe) maxValue = std::max(maxValue, s.maxValue());
  if (!(maxValue > 0.0)) where.fail("the curves are zero everywhere");
  for (Spectrum& s : qe) s *= peak / maxValue;
}

std::vector<Spectrum> parseQe(const YamlValue& value, const CfaLayout& cfa,
                              const TableSearch& tables) {
  YamlMap map(value);
  const std::vector<std::string> known = {"curves", "csv", "columns", "ideal_xyz", "peak_qe"};
  std::vector<Spectrum> qe;
  if (const auto ideal = map.find("ideal_xyz")) {
    if (!ideal->boolean()) ideal->fail("set ideal_xyz: true, or give {curves} or {csv, columns}");
    const Cie1931& cie = Cie1931::get();
    for (const std::string& channel : cfa.channels) {
      if (channel == "X")
        qe.push_back(cie.x);
      else if (channel == "Y")
        qe.push_back(cie.y);
      else if (channel == "Z")
        qe.push_back(cie.z);
      else
        ideal->fail("ideal_xyz needs CFA channels named X, Y or Z (e.g. cfa: xyz), not '" +
                    channel + "'");
    }
    double peak = 1.0;
    if (const auto p = map.find("peak_qe")) peak = p->number(0.0, 1.0, true);
    // Electrons count photons (energy · λ/hc), so QE = cmf(λ) · 555 nm/λ makes the
    // electrons exactly proportional to CIE X, Y, Z of the light's energy. Normalised so
    // that the Y channel peaks at `peak` (an ideal, not a physical QE: X may exceed it).
    Spectrum photonToEnergy;
    for (int i = 0; i < kSpectrumSamples; ++i)
      photonToEnergy.sample(i) = static_cast<float>(555.0 / (kLambdaMinNm + i));
    for (Spectrum& s : qe) s *= photonToEnergy;
    const double yMax = (cie.y * photonToEnergy).maxValue();
    for (Spectrum& s : qe) s *= peak / yMax;
  } else if (const auto curves = map.find("curves")) {
    const SpectralTable table = readTable(*curves, tables);
    for (const std::string& channel : cfa.channels) {
      std::string column = channel;
      std::transform(column.begin(), column.end(), column.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      qe.push_back(tableColumn(table, *curves, column));
    }
    scaleToPeak(qe, map.require("peak_qe").number(0.0, 1.0, true), *curves);
  } else if (const auto csv = map.find("csv")) {
    const SpectralTable table = readTable(*csv, tables);
    const YamlValue columns = map.require("columns");
    const std::vector<YamlValue> names = columns.items();
    if (names.size() != cfa.channels.size())
      columns.fail("expected " + std::to_string(cfa.channels.size()) +
                   " column names, one per CFA channel");
    for (const YamlValue& name : names) qe.push_back(tableColumn(table, name, name.string()));
    if (const auto peak = map.find("peak_qe")) {
      scaleToPeak(qe, peak->number(0.0, 1.0, true), *csv);
    } else {
      for (const Spectrum& s : qe)
        if (s.maxValue() > 1.0)
          csv->fail("absolute QE exceeds 1: give peak_qe to scale relative curves");
    }
  } else {
    map.self().fail(
        "expected {curves: file.csv, peak_qe: p}, {csv: file.csv, columns: [...]} or "
        "{ideal_xyz: true}");
  }
  map.finish(known);
  return qe;
}

// The IR-cut filter's transmittance T(λ) ∈ [0, 1].
Spectrum parseIrCut(const YamlValue& value, const TableSearch& tables) {
  YamlMap map(value);
  if (const auto csv = map.find("csv")) {
    const SpectralTable table = readTable(*csv, tables);
    std::string column;
    if (const auto c = map.find("column")) {
      column = c->string();
    } else if (table.columns.size() == 1) {
      column = table.columns[0];
    } else {
      csv->fail("table has several columns: name one with 'column'");
    }
    map.finish({"csv", "column"});
    const Spectrum s = tableColumn(table, *csv, column);
    if (s.maxValue() > 1.0) csv->fail("a transmittance must lie in [0, 1]");
    return s;
  }
  // Logistic edge: T = 1 / (1 + exp((λ − cutoff) / s)), falling from 90 % to 10 % over
  // width_nm, so s = width / (2 ln 9).
  const double cutoff = map.require("cutoff_nm").number(200.0, 2000.0);
  const double width = map.require("width_nm").number(0.0, 500.0, true);
  map.finish({"cutoff_nm", "width_nm", "csv", "column"});
  const double scale = width / (2.0 * std::log(9.0));
  Spectrum t;
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const double lambda = kLambdaMinNm + i;
    t.sample(i) = static_cast<float>(1.0 / (1.0 + std::exp((lambda - cutoff) / scale)));
  }
  return t;
}

}  // namespace

SensorSpec parseSensorSpec(const std::string& yamlText, const std::string& displayName,
                           const fs::path& baseDir, const fs::path& lutsDir) {
  const YamlValue root = parseYaml(yamlText, displayName);
  YamlMap map(root);
  SensorSpec spec;
  const TableSearch tables{{baseDir, lutsDir / "spectra", lutsDir}, &spec.sourceFiles};

  spec.name = fs::path(displayName).stem().string();
  if (const auto v = map.find("name")) {
    // It is printed, names camsim ptc's files and is the DNG's camera model (found by
    // probing: "" printed "photon transfer of  at ISO 50").
    spec.name = v->string();
    if (spec.name.empty() || std::any_of(spec.name.begin(), spec.name.end(), [](char c) {
          return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
        }))
      v->fail("name must be non-empty, without control characters");
  }
  spec.pixelPitchM = map.require("pixel_pitch_um").number(0.0, 1000.0, true) * 1e-6;
  if (const auto v = map.find("fill_factor")) spec.fillFactor = v->number(0.0, 1.0, true);
  if (const auto v = map.find("cfa")) spec.cfa = parseCfa(*v);
  // Each channel must respond somewhere in camsim's spectral range: a channel that cannot
  // see light was found only after rendering, and blamed on isp.white_balance.
  const auto checkResponse = [&](const YamlValue& where, const char* cause) {
    for (std::size_t c = 0; c < spec.qe.size(); ++c)
      if (!(spec.qe[c].maxValue() > 0.0))
        where.fail("channel " + spec.cfa.channels[c] + " has no response within " +
                   std::to_string(kLambdaMinNm) + "-" + std::to_string(kLambdaMaxNm) + " nm" +
                   cause + " (the range camsim traces)");
  };
  const YamlValue qeValue = map.require("qe");
  spec.qe = parseQe(qeValue, spec.cfa, tables);
  checkResponse(qeValue, "");
  if (const auto v = map.find("ir_cut")) {
    const Spectrum t = parseIrCut(*v, tables);
    for (Spectrum& s : spec.qe) s *= t;
    checkResponse(*v, " once the IR-cut filter is applied");
  }
  if (const auto v = map.find("full_well_e")) spec.fullWellE = v->number(0.0, 1e9, true);
  if (const auto v = map.find("conversion_gain_e_per_dn"))
    spec.conversionGainEPerDn = v->number(1e-6, 1e6);  // 1e-300 gave an infinite gain
  if (const auto v = map.find("base_iso")) spec.baseIso = v->number(0.0, kMaxIso, true);
  if (const auto v = map.find("read_noise_e")) spec.readNoiseE = v->number(0.0, 1e6);
  if (const auto v = map.find("dark_current_e_per_s")) spec.darkCurrentEPerS = v->number(0.0, 1e9);
  if (const auto v = map.find("dark_reference_c")) spec.darkReferenceC = v->number(-273.15, 500.0);
  if (const auto v = map.find("dark_doubling_c")) spec.darkDoublingC = v->number(0.0, 1000.0, true);
  if (const auto v = map.find("temperature_c")) spec.temperatureC = v->number(-273.15, 500.0);
  if (const auto v = map.find("dsnu_e")) spec.dsnuE = v->number(0.0, 1e6);
  if (const auto v = map.find("prnu_percent")) spec.prnuFraction = v->number(0.0, 100.0) / 100.0;
  if (const auto v = map.find("row_fpn_e")) spec.rowFpnE = v->number(0.0, 1e6);
  if (const auto v = map.find("column_fpn_e")) spec.columnFpnE = v->number(0.0, 1e6);
  if (const auto v = map.find("adc_bits")) spec.adcBits = static_cast<int>(v->integer(1, 16));
  if (const auto v = map.find("black_level_dn")) {
    spec.blackLevelDn = v->number(0.0, 65535.0);
    if (spec.blackLevelDn >= spec.whiteLevelDn())
      v->fail("black level must be below the white level 2^adc_bits − 1 = " +
              std::to_string(static_cast<int>(spec.whiteLevelDn())));
  }
  if (const auto v = map.find("pattern_seed"))
    spec.patternSeed = static_cast<std::uint64_t>(v->integer(0, INT64_MAX));
  if (const auto v = map.find("noiseless")) spec.noiseless = v->boolean();
  parseSensorNoise(map, spec);
  // Each key is in range, but not every combination: found by probing, temperature_c 500 with
  // dark_doubling_c 0.001 overflowed the factor to inf (every photosite saturated), and with
  // dark_current_e_per_s 0 to NaN (cast to DN: undefined). Named at the temperature keys.
  for (const auto& [rate, key] :
       {std::pair{spec.darkCurrentEPerS, "dark_current_e_per_s"},
        std::pair{spec.noise.hotPixelDarkCurrentEPerS, "hot_pixels.dark_current_e_per_s"}}) {
    const double atT = spec.darkAtTemperature(rate);
    if (atT <= 1e9) continue;
    const char* named = "temperature_c";
    for (const char* k : {"temperature_c", "dark_doubling_c", "dark_reference_c"})
      if (map.find(k)) {
        named = k;
        break;
      }
    const auto where = map.find(named);
    const std::string message =
        std::string(key) + " at temperature_c = " + formatShortest(spec.temperatureC) +
        " °C, × 2^((temperature_c − dark_reference_c) / dark_doubling_c), is " +
        formatShortest(atT) + " e⁻/s: above 1e9 e⁻/s, the dark current's range";
    if (where) where->fail(message);
    map.self().fail(message);
  }
  if (const auto v = map.find("dark_frames")) {
    fs::path dir(v->string());
    if (dir.is_relative()) dir = baseDir / dir;
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
      v->fail("no dark-frame directory '" + dir.string() + "' (missing, or not a directory)");
    spec.darkFramesDir = dir;
  }
  std::vector<std::string> known = {"name",
                                    "pixel_pitch_um",
                                    "fill_factor",
                                    "cfa",
                                    "qe",
                                    "ir_cut",
                                    "full_well_e",
                                    "conversion_gain_e_per_dn",
                                    "base_iso",
                                    "read_noise_e",
                                    "dark_current_e_per_s",
                                    "dark_reference_c",
                                    "dark_doubling_c",
                                    "temperature_c",
                                    "dsnu_e",
                                    "prnu_percent",
                                    "row_fpn_e",
                                    "column_fpn_e",
                                    "adc_bits",
                                    "black_level_dn",
                                    "pattern_seed",
                                    "noiseless",
                                    "dark_frames"};
  known.insert(known.end(), sensorNoiseKeys().begin(), sensorNoiseKeys().end());
  map.finish(known);
  return spec;
}

bool isSensorSpecPath(const std::string& presetOrPath) {
  const fs::path path(presetOrPath);
  const std::string ext = path.extension().string();
  return path.has_parent_path() || ext == ".yaml" || ext == ".yml" || ext == ".json";
}

SensorSpec loadSensorSpec(const std::string& presetOrPath, const fs::path& lutsDir) {
  if (presetOrPath.empty()) throw InputError({}, "sensor", "empty sensor name");
  fs::path path(presetOrPath);
  const bool isPath = isSensorSpecPath(presetOrPath);
  if (!isPath) path = lutsDir / "sensors" / (presetOrPath + ".yaml");
  if (!isRegularFile(path)) {  // a directory would open and read as empty
    if (isPath)
      throw InputError(
          {path.string(), 0, 0}, "",
          "no sensor description file '" + path.string() + "' (missing, or not a file)");
    std::set<std::string> presets;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(lutsDir / "sensors", ec))
      if (entry.path().extension() == ".yaml") presets.insert(entry.path().stem().string());
    std::string list;
    for (const std::string& p : presets) list += (list.empty() ? "" : ", ") + p;
    throw InputError({}, "sensor",
                     "unknown sensor preset '" + presetOrPath +
                         "' (presets: " + (list.empty() ? "none found" : list) +
                         "; a file path needs a '/' or a .yaml extension)");
  }
  SensorSpec spec = parseSensorSpec(readInputFile(path, "sensor description"), path.string(),
                                    path.parent_path(), lutsDir);
  spec.sourceFiles.insert(spec.sourceFiles.begin(), path);
  spec.preset = !isPath;
  return spec;
}

SpectralResponse sensorResponse(const SensorSpec& spec) {
  return SpectralResponse::electrons(spec.cfa.channels, spec.qe,
                                     spec.cfa.isStacked() ? nullptr : &spec.cfa);
}

}  // namespace camsim
