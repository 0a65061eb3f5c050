// PNG writing (libpng). This module is the only one that includes libpng.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace camsim {

// 8-bit RGB, rows top to bottom; rgb.size() == width·height·3. The file is tagged sRGB.
void writePng8(const std::filesystem::path& path, int width, int height,
               const std::vector<std::uint8_t>& rgb);

}  // namespace camsim
