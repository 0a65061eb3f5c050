// Reading dark frames: uncompressed 16-bit raw DNGs (one CFA or LinearRaw image in IFD0,
// as camsim and most converters' "uncompressed" option write them) and camsim's raw EXRs
// (the "raw.DN" channel, black level in camsim:black_level_dn). Opens DNGs with
// tiff_file.h, as the DNG writer does.
#pragma once

#include <filesystem>
#include <optional>

#include "sensor/model/dark_frames.h"
#include "sensor/model/raw_image.h"
#include "sensor/model/sensor_model.h"
#include "sensor/model/sensor_spec.h"

namespace camsim {

// One raw DNG's digital numbers and levels (cfa left as mono: dark frames do not need it).
// InputError naming the file for anything it cannot read (compressed, tiled, not 16-bit…).
RawImage readRawDng(const std::filesystem::path& path);

// Every *.dng and *.exr in `dir`, sorted by name, checked against each other (size, black
// level) and against the sensor (black level, ADC range). InputError (key "dark_frames")
// naming the file otherwise, or when the directory holds none.
DarkFrameSet loadDarkFrames(const std::filesystem::path& dir, const SensorSpec& sensor);

// The dark frames an exposure in `mode` adds (sensor-format.md, "Dark frames"): the sensor's
// dark_frames folder loaded when the mode is full and the sensor is not noiseless; none
// otherwise. Every exposing front end (render, camsim expose, Python's expose) asks here.
std::optional<DarkFrameSet> darkFramesFor(const SensorSpec& sensor, NoiseMode mode);

}  // namespace camsim
