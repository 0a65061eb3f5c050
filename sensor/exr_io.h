// OpenEXR reading and writing. This module is the only one that includes OpenEXR.
// Pixels are written as 32-bit float, ZIP-compressed, one EXR channel per image channel.
#pragma once

#include <filesystem>
#include <optional>

#include "sensor/cie.h"
#include "sensor/image.h"

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

}  // namespace camsim
