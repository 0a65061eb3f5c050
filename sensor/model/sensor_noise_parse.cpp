// Reading the gain-dependent noise keys of a sensor description (sensor_noise.h has the
// table of keys and units).
#include <algorithm>
#include <cmath>

#include "sensor/base/input_error.h"
#include "sensor/base/yaml_reader.h"
#include "sensor/model/sensor_noise.h"
#include "sensor/model/sensor_spec.h"

namespace camsim {
namespace {

constexpr double kMaxNoiseDn = 65535.0;
constexpr double kMaxNoiseE = 1e6;

LogLinearFit parseFit(const YamlValue& value) {
  YamlMap map(value);
  LogLinearFit fit;
  fit.slope = map.require("slope").number(-10.0, 10.0);
  fit.bias = map.require("bias").number(-50.0, 50.0);
  // sigma: ELD's residual spread, informative — checked, then ignored (read before finish():
  // a key finish() has not seen read was refused as "not allowed together with …").
  if (const auto s = map.find("sigma")) s->number(0.0, 100.0);
  map.finish({"slope", "bias", "sigma"});
  return fit;
}

std::vector<double> parseOffsets(const YamlValue& value, std::size_t tileSize) {
  std::vector<double> offsets;
  for (const YamlValue& item : value.items())
    offsets.push_back(item.number(-kMaxNoiseDn, kMaxNoiseDn));
  if (offsets.size() != tileSize)
    value.fail("expected " + std::to_string(tileSize) +
               " offsets, one per CFA tile position (row-major)");
  return offsets;
}

IsoTableRow parseRow(const YamlValue& value, std::size_t tileSize) {
  YamlMap map(value);
  IsoTableRow row;
  row.iso = map.require("iso").number(0.0, kMaxIso, true);
  if (const auto v = map.find("system_gain_dn_per_e")) row.systemGain = v->number(0.0, 1e6, true);
  if (const auto v = map.find("read_noise_e")) row.readNoiseE = v->number(0.0, kMaxNoiseE);
  if (const auto v = map.find("read_noise_post_dn"))
    row.readNoisePostDn = v->number(0.0, kMaxNoiseDn);
  if (const auto v = map.find("tukey_lambda")) row.tukeyLambda = v->number(-0.25, 1.0);
  if (const auto v = map.find("tukey_scale_dn")) row.tukeyScaleDn = v->number(0.0, kMaxNoiseDn);
  if (const auto v = map.find("row_noise_dn")) row.rowNoiseDn = v->number(0.0, kMaxNoiseDn);
  if (const auto v = map.find("black_offsets_dn")) row.blackOffsetsDn = parseOffsets(*v, tileSize);
  map.finish({"iso", "system_gain_dn_per_e", "read_noise_e", "read_noise_post_dn", "tukey_lambda",
              "tukey_scale_dn", "row_noise_dn", "black_offsets_dn"});
  return row;
}

}  // namespace

const std::vector<std::string>& sensorNoiseKeys() {
  static const std::vector<std::string> keys = {
      "read_noise_post_dn", "dual_conversion_gain", "iso_table",    "noise_fits",
      "read_noise_shape",   "tukey_lambda",         "row_noise_dn", "black_offsets_dn",
      "hot_pixels",         "stuck_pixels"};
  return keys;
}

void parseSensorNoise(YamlMap& map, SensorSpec& spec) {
  SensorNoiseSpec& ns = spec.noise;
  const std::size_t tileSize = static_cast<std::size_t>(spec.cfa.width * spec.cfa.height);
  if (const auto v = map.find("read_noise_post_dn"))
    ns.readNoisePostDn = v->number(0.0, kMaxNoiseDn);
  if (const auto v = map.find("dual_conversion_gain")) {
    YamlMap m(*v);
    DualConversionGain& d = ns.dualGain;
    const YamlValue iso = m.require("iso");
    d.iso = iso.number(0.0, kMaxIso, true);
    if (d.iso <= spec.baseIso) iso.fail("the switch ISO must be above base_iso");
    d.conversionGainEPerDn = m.require("conversion_gain_e_per_dn").number(1e-6, 1e6);
    d.readNoiseE = m.require("read_noise_e").number(0.0, kMaxNoiseE);
    if (const auto w = m.find("full_well_e")) d.fullWellE = w->number(0.0, 1e9, true);
    m.finish({"iso", "conversion_gain_e_per_dn", "read_noise_e", "full_well_e"});
  }
  if (const auto v = map.find("iso_table")) {
    for (const YamlValue& item : v->items()) {
      IsoTableRow row = parseRow(item, tileSize);
      if (!ns.isoTable.empty() && !(row.iso > ns.isoTable.back().iso))
        item.fail("iso_table rows must be in increasing ISO");
      ns.isoTable.push_back(std::move(row));
    }
    if (ns.isoTable.empty()) v->fail("expected at least one row {iso: …}");
    if (spec.baseIso < ns.isoTable.front().iso || spec.baseIso > ns.isoTable.back().iso)
      v->fail("base_iso must lie within the table's ISO range");
  }
  if (const auto v = map.find("noise_fits")) {
    YamlMap m(*v);
    if (const auto f = m.find("read_noise_dn")) ns.readNoiseFit = parseFit(*f);
    if (const auto f = m.find("tukey_scale_dn")) ns.tukeyScaleFit = parseFit(*f);
    if (const auto f = m.find("row_noise_dn")) ns.rowNoiseFit = parseFit(*f);
    m.finish({"read_noise_dn", "tukey_scale_dn", "row_noise_dn"});
  }
  if (const auto v = map.find("read_noise_shape"))
    ns.shape = v->choice<ReadNoiseShape>("read-noise shape");
  if (const auto v = map.find("tukey_lambda")) ns.tukeyLambda = v->number(-0.25, 1.0);
  if (const auto v = map.find("row_noise_dn")) ns.rowNoiseDn = v->number(0.0, kMaxNoiseDn);
  if (const auto v = map.find("black_offsets_dn")) ns.blackOffsetsDn = parseOffsets(*v, tileSize);
  if (const auto v = map.find("hot_pixels")) {
    YamlMap m(*v);
    ns.hotPixelFraction = m.require("fraction").number(0.0, 1.0);
    ns.hotPixelDarkCurrentEPerS = m.require("dark_current_e_per_s").number(0.0, 1e9);
    m.finish({"fraction", "dark_current_e_per_s"});
  }
  if (const auto v = map.find("stuck_pixels")) {
    YamlMap m(*v);
    ns.stuckPixelFraction = m.require("fraction").number(0.0, 1.0);
    ns.stuckPixelValueDn = m.require("value_dn").number(0.0, spec.whiteLevelDn());
    m.finish({"fraction", "value_dn"});
  }
  // A Tukey-λ read noise needs a scale from somewhere.
  if (ns.shape == ReadNoiseShape::kTukeyLambda && !ns.tukeyScaleFit &&
      std::none_of(ns.isoTable.begin(), ns.isoTable.end(),
                   [](const IsoTableRow& r) { return r.tukeyScaleDn.has_value(); }))
    (map.has("read_noise_shape") ? *map.find("read_noise_shape") : map.self())
        .fail(
            "read_noise_shape: tukey_lambda needs a scale: noise_fits.tukey_scale_dn or an "
            "iso_table column tukey_scale_dn");
}

}  // namespace camsim
