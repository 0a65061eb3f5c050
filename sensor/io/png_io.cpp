// libpng glue (see png_io.h). libpng reports errors by longjmp: every setjmp sits in a small
// function whose locals are trivially destructible, and all C++ objects live in the callers,
// so a longjmp never skips a destructor.
#include "sensor/io/png_io.h"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "sensor/base/check.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace {

using FilePtr = std::unique_ptr<FILE, int (*)(FILE*)>;

// Where libpng's error handler leaves its message before jumping back.
struct ErrorSink {
  char message[200] = "unknown libpng error";
};

void onError(png_structp png, png_const_charp message) {
  auto* sink = static_cast<ErrorSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", message);
  png_longjmp(png, 1);
}
void onWarning(png_structp, png_const_charp) {}

struct Header {
  png_uint_32 width = 0, height = 0;
  int channels = 0, bitDepth = 0;
};

// Reads the header and sets up the expansions; false on a libpng error.
bool readHeader(png_structp png, png_infop info, FILE* fp, Header& h) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, fp);
  png_set_user_limits(png, 1u << 20, 1u << 20);
  png_read_info(png, info);
  png_set_expand(png);  // palette → RGB, grey < 8 bits → 8 bits, tRNS → alpha
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  h.width = png_get_image_width(png, info);
  h.height = png_get_image_height(png, info);
  h.channels = png_get_channels(png, info);
  h.bitDepth = png_get_bit_depth(png, info);
  return true;
}

bool readRows(png_structp png, png_infop info, png_bytep* rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, info);
  return true;
}

bool writeAll(png_structp png, png_infop info, FILE* fp, const PngImage& image, bool tagSrgb,
              png_bytep* rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, fp);
  static constexpr int kTypes[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                   PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), image.bitDepth, kTypes[image.channels - 1],
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (tagSrgb) png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  return true;
}

}  // namespace

void writePng8(const std::filesystem::path& path, int width, int height,
               const std::vector<std::uint8_t>& rgb, bool tagSrgb) {
  CAMSIM_CHECK(width > 0 && height > 0 &&
               rgb.size() == static_cast<size_t>(width) * static_cast<size_t>(height) * 3);
  std::unique_ptr<FILE, int (*)(FILE*)> fp(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!fp) throw std::runtime_error("cannot open " + path.string() + " for writing");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("libpng: out of memory");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("libpng failed writing " + path.string());
  }
  png_init_io(png, fp.get());
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  if (tagSrgb) png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y)
    png_write_row(png, rgb.data() + static_cast<size_t>(y) * static_cast<size_t>(width) * 3);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fflush(fp.get()) != 0) throw std::runtime_error("cannot write " + path.string());
}

PngImage readPng(const std::filesystem::path& path) {
  const std::string name = path.string();
  auto fail = [&](const std::string& why) {
    return InputError({name, 0, 0}, "", "cannot read PNG: " + why);
  };
  const FilePtr fp(std::fopen(name.c_str(), "rb"), &std::fclose);
  if (!fp) throw fail(std::string(std::strerror(errno)));
  unsigned char signature[8] = {};
  if (std::fread(signature, 1, 8, fp.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0)
    throw fail("not a PNG file");
  ErrorSink sink;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &sink, onError, onWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  const auto destroy = [&] { png_destroy_read_struct(&png, &info, nullptr); };
  if (!png || !info) {
    destroy();
    throw std::runtime_error("libpng: out of memory");
  }
  png_set_sig_bytes(png, 8);
  Header h;
  if (!readHeader(png, info, fp.get(), h)) {
    destroy();
    throw fail(sink.message);
  }
  if (static_cast<std::uint64_t>(h.width) * h.height > kMaxPngPixels || h.channels < 1 ||
      h.channels > 4 || (h.bitDepth != 8 && h.bitDepth != 16)) {
    destroy();
    throw fail("unsupported size or layout (" + std::to_string(h.width) + "×" +
               std::to_string(h.height) + ", " + std::to_string(h.channels) + " channels, " +
               std::to_string(h.bitDepth) + " bits)");
  }
  const size_t rowBytes = static_cast<size_t>(h.width) * static_cast<size_t>(h.channels) *
                          static_cast<size_t>(h.bitDepth / 8);
  std::vector<png_byte> bytes(rowBytes * h.height);
  std::vector<png_bytep> rows(h.height);
  for (size_t y = 0; y < rows.size(); ++y) rows[y] = bytes.data() + y * rowBytes;
  const bool ok = readRows(png, info, rows.data());
  destroy();
  if (!ok) throw fail(sink.message);

  PngImage image;
  image.width = static_cast<int>(h.width);
  image.height = static_cast<int>(h.height);
  image.channels = h.channels;
  image.bitDepth = h.bitDepth;
  const size_t count = bytes.size() / static_cast<size_t>(h.bitDepth / 8);
  image.samples.reserve(count);
  for (size_t i = 0; i < count; ++i)  // 16-bit samples are big-endian
    image.samples.push_back(
        h.bitDepth == 8 ? bytes[i]
                        : static_cast<std::uint16_t>((bytes[2 * i] << 8) | bytes[2 * i + 1]));
  return image;
}

void writePng(const std::filesystem::path& path, const PngImage& image, bool tagSrgb) {
  CAMSIM_CHECK(image.width > 0 && image.height > 0 && image.channels >= 1 && image.channels <= 4);
  CAMSIM_CHECK(image.bitDepth == 8 || image.bitDepth == 16);
  const size_t perRow = static_cast<size_t>(image.width) * static_cast<size_t>(image.channels);
  CAMSIM_CHECK(image.samples.size() == perRow * static_cast<size_t>(image.height));
  const size_t bytesPerSample = static_cast<size_t>(image.bitDepth / 8);
  std::vector<png_byte> bytes(image.samples.size() * bytesPerSample);
  for (size_t i = 0; i < image.samples.size(); ++i) {
    if (bytesPerSample == 1) {
      bytes[i] = static_cast<png_byte>(image.samples[i]);
    } else {
      bytes[2 * i] = static_cast<png_byte>(image.samples[i] >> 8);
      bytes[2 * i + 1] = static_cast<png_byte>(image.samples[i] & 0xff);
    }
  }
  std::vector<png_bytep> rows(static_cast<size_t>(image.height));
  for (size_t y = 0; y < rows.size(); ++y) rows[y] = bytes.data() + y * perRow * bytesPerSample;
  const FilePtr fp(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!fp) throw std::runtime_error("cannot open " + path.string() + " for writing");
  ErrorSink sink;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, onError, onWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  const bool ok = png && info && writeAll(png, info, fp.get(), image, tagSrgb, rows.data());
  png_destroy_write_struct(&png, &info);
  if (!ok) throw std::runtime_error("libpng failed writing " + path.string() + ": " + sink.message);
  if (std::fflush(fp.get()) != 0) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace camsim
