// OpenEXR reading and writing. This module is the only one that includes OpenEXR.
// Pixels are written as 32-bit float, ZIP-compressed, one EXR channel per image channel.
#pragma once

#include <filesystem>
#include <optional>

#include "sensor/base/image.h"
#include "sensor/model/raw_image.h"
#include "sensor/spectra/cie.h"

namespace camsim {

// Primaries and white of the RGB channels, stored as the standard `chromaticities`
// attribute so viewers can interpret R, G, B.
struct ExrChromaticities {
  Chromaticity red, green, blue, white;
};

void writeExr(const std::filesystem::path& path, const Image& image, const Metadata& metadata,
              const std::optional<ExrChromaticities>& chromaticities);

struct ExrFile {
  Image image;
  Metadata metadata;  // string attributes only
  std::optional<ExrChromaticities> chromaticities;
};
// Throws InputError if the file cannot be read as an EXR.
ExrFile readExr(const std::filesystem::path& path);

// Raw EXR: the sensor's output and its noise-free input side by side, same size.
//   "raw.DN"          the digital numbers as float (exact: every 16-bit integer is a float)
//   "electrons.<c>"   every channel c of expectedElectrons (e.g. "electrons.expected")
// String attributes: meta, then camsim:cfa (the layout name, e.g. "RGGB", "mono"),
// camsim:black_level_dn and camsim:white_level_dn (shortest round-trip decimal), which
// replace any meta entries of the same names.
void writeRawExr(const std::filesystem::path& path, const RawImage& raw,
                 const Image& expectedElectrons, const Metadata& meta);

}  // namespace camsim
