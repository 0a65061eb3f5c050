// PNG reading and writing (libpng). This module is the only one that includes libpng.
//
//   writePng8  8-bit RGB (display pictures)
//   writePng   8- or 16-bit, 1–4 channels (grey, grey+alpha, RGB, RGBA)
//   readPng    any PNG: palette → RGB(A), grey below 8 bits → 8-bit, tRNS → alpha; 8- and
//              16-bit samples kept as they are (no gamma or colour conversion: the caller
//              decides what the numbers mean)
// Samples are interleaved, rows top to bottom.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace camsim {

// 8-bit RGB, rows top to bottom; rgb.size() == width·height·3. tagSrgb: mark the file
// as sRGB (sRGB/gAMA/cHRM chunks) — only when the pixels are sRGB-encoded.
void writePng8(const std::filesystem::path& path, int width, int height,
               const std::vector<std::uint8_t>& rgb, bool tagSrgb = true);

struct PngImage {
  int width = 0;
  int height = 0;
  int channels = 0;                    // 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA
  int bitDepth = 8;                    // 8 or 16
  std::vector<std::uint16_t> samples;  // width·height·channels, each < 2^bitDepth
};

// Largest image readPng accepts (width·height), so a hostile header cannot make it
// allocate without bound.
inline constexpr std::uint64_t kMaxPngPixels = std::uint64_t{1} << 28;

// Throws InputError (file name, no line) if the file is missing, not a PNG, corrupt or
// larger than kMaxPngPixels.
PngImage readPng(const std::filesystem::path& path);
// Throws std::runtime_error if the file cannot be written.
void writePng(const std::filesystem::path& path, const PngImage& image, bool tagSrgb = false);

}  // namespace camsim
