// PNG writing (libpng). This module is the only one that includes libpng.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace camsim {

// 8-bit RGB, rows top to bottom; rgb.size() == width·height·3. tagSrgb: mark the file
// as sRGB (sRGB/gAMA/cHRM chunks) — only when the pixels are sRGB-encoded.
void writePng8(const std::filesystem::path& path, int width, int height,
               const std::vector<std::uint8_t>& rgb, bool tagSrgb = true);

}  // namespace camsim
