// SensorSpec: a camera sensor described by its EMVA 1288 parameters (plain data, SI and
// camera units), loaded from YAML (luts/sensors/*.yaml, documented in docs/sensor-format.md).
//
// | field                  | unit         | meaning |
// |------------------------|--------------|---------|
// | name                   | —            | display name (default: the file's stem) |
// | pixel_pitch_um         | µm           | photosite pitch (the camera's sensor size must agree) |
// | fill_factor            | —            | photosensitive fraction of the pixel area |
// | cfa                    | —            | RGGB, BGGR, GRBG, GBRG, mono, xyz (stacked), custom tile |
// | qe                     | e⁻/photon    | per channel: relative curve × peak_qe, or ideal CIE XYZ, or a CSV |
// | ir_cut                 | —            | optional transmittance multiplying every channel's QE |
// | full_well_e            | e⁻           | full-well capacity |
// | conversion_gain_e_per_dn | e⁻/DN      | at base ISO (1/K) |
// | base_iso               | —            | ISO at which the conversion gain applies; analog gain g = ISO / base_iso |
// | read_noise_e           | e⁻ rms       | temporal read noise (at the sense node, before gain) |
// | dark_current_e_per_s   | e⁻/s         | at dark_reference_c, doubling every dark_doubling_c |
// | dark_reference_c, dark_doubling_c | °C | reference temperature (25), doubling interval (6) |
// | temperature_c          | °C           | operating temperature |
// | dsnu_e                 | e⁻ rms       | dark signal non-uniformity (fixed offset pattern) |
// | prnu_percent           | %            | photo-response non-uniformity (fixed gain pattern) |
// | row_fpn_e, column_fpn_e| e⁻ rms       | fixed row/column offsets (optional) |
// | adc_bits               | bits         | ADC resolution; white level = 2^bits − 1 |
// | black_level_dn         | DN           | offset added before quantisation |
// | pattern_seed           | —            | seed of the fixed patterns (PRNU, DSNU, FPN): same sensor ⇒ same pattern |
// | noiseless              | —            | true: expose() never adds noise (NoiseMode none) |
// | dark_frames            | —            | directory of dark frames (DNG or raw EXR) replacing the signal-independent noise |
// | (gain-dependent noise) | —            | read_noise_post_dn, dual_conversion_gain, iso_table, noise_fits, … (sensor_noise.h) |
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sensor/model/cfa.h"
#include "sensor/model/sensor_noise.h"
#include "sensor/model/spectral_response.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

struct SensorSpec {
  std::string name;
  double pixelPitchM = 4e-6;
  double fillFactor = 1.0;
  CfaLayout cfa;
  std::vector<Spectrum>
      qe;  // per CFA channel: absolute quantum efficiency QE(λ) in [0, 1], IR cut included
  double fullWellE = 20000.0;
  double conversionGainEPerDn = 1.0;  // e⁻/DN at base ISO
  double baseIso = 100.0;
  double readNoiseE = 2.0;
  double darkCurrentEPerS = 0.0;
  double darkReferenceC = 25.0;
  double darkDoublingC = 6.0;
  double temperatureC = 25.0;
  double dsnuE = 0.0;
  double prnuFraction = 0.0;  // prnu_percent / 100
  double rowFpnE = 0.0, columnFpnE = 0.0;
  int adcBits = 12;
  double blackLevelDn = 0.0;
  std::uint64_t patternSeed = 1;
  bool noiseless = false;  // the ideal-xyz preset: expose() always uses NoiseMode::kNone
  SensorNoiseSpec noise;   // gain-dependent terms (sensor/model/sensor_noise.h)
  // A directory of dark frames that replace the signal-independent terms in noise mode full
  // (sensor/model/dark_frames.h; loaded by loadDarkFrames, sensor/io/dark_frame_reader.h).
  std::filesystem::path darkFramesDir;
  // The files it was read from: the description (loadSensorSpec) and each CSV, in order.
  std::vector<std::filesystem::path> sourceFiles;
  // Whether loadSensorSpec read it as a preset (luts/sensors/NAME.yaml, by its name). A raw
  // EXR records it as camsim:sensor_source, so that camsim expose does not take a
  // description file's sensor for the preset of the same name.
  bool preset = false;
  const char* sourceKind() const { return preset ? "preset" : "file"; }
  // How messages name the description: its file when it came from one (a preset's too),
  // else its name.
  std::string sourceName() const {
    return sourceFiles.empty() ? name : sourceFiles.front().string();
  }

  double whiteLevelDn() const { return static_cast<double>((1u << adcBits) - 1u); }
  // Mean dark electrons per second at the operating temperature.
  double darkCurrentAtTemperature() const;
  // A dark current of `ePerSAtReference` e⁻/s at dark_reference_c, at the operating
  // temperature: × 2^((T − T_ref)/T_double); 0 stays 0 (the factor may overflow: the loader
  // refuses a sensor whose dark currents at temperature exceed 1e9 e⁻/s).
  double darkAtTemperature(double ePerSAtReference) const;
  // System gain K (DN/e⁻) at an ISO (noiseAtIso: conversion-gain mode, iso_table).
  double systemGain(double iso) const;
  // Electrons at which the output saturates at an ISO: min(full well, ADC range / K),
  // ADC range = white level − black level.
  double saturationElectrons(double iso) const;
};

// Parses a sensor description; relative CSV paths resolve against baseDir then lutsDir.
// Errors: InputError with file, line, column and key.
SensorSpec parseSensorSpec(const std::string& yamlText, const std::string& displayName,
                           const std::filesystem::path& baseDir,
                           const std::filesystem::path& lutsDir);
// A preset name ("smartphone-1.4um", …) from lutsDir/sensors/NAME.yaml, or a file path.
SensorSpec loadSensorSpec(const std::string& presetOrPath, const std::filesystem::path& lutsDir);
// Whether loadSensorSpec takes this as a file path rather than a preset name: it has a
// folder part or ends in .yaml, .yml or .json.
bool isSensorSpecPath(const std::string& presetOrPath);

// The film response recording this sensor's expected electrons: through its CFA (one
// plane), or one plane per channel for a stacked sensor.
SpectralResponse sensorResponse(const SensorSpec& spec);

}  // namespace camsim
