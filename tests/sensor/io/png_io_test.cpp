// Tests for sensor/png_io: writePng/readPng round trips of every layout and bit depth,
// writePng8's files read back, and unreadable files as InputError naming the file.
#include "sensor/io/png_io.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "sensor/base/input_error.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

PngImage makeImage(int w, int h, int channels, int bitDepth) {
  PngImage image{w, h, channels, bitDepth, {}};
  const int maxCode = (1 << bitDepth) - 1;
  for (int i = 0; i < w * h * channels; ++i)
    image.samples.push_back(static_cast<std::uint16_t>((i * 7919) % (maxCode + 1)));
  return image;
}

TEST(PngIo, RoundTripsEveryLayoutAndDepth) {
  TempDir dir;
  for (int channels = 1; channels <= 4; ++channels)
    for (int depth : {8, 16}) {
      SCOPED_TRACE(std::to_string(channels) + " channels, " + std::to_string(depth) + " bits");
      const PngImage in = makeImage(5, 3, channels, depth);
      const fs::path file = dir.path() / "t.png";
      writePng(file, in, channels >= 3);
      const PngImage out = readPng(file);
      EXPECT_EQ(out.width, 5);
      EXPECT_EQ(out.height, 3);
      EXPECT_EQ(out.channels, channels);
      EXPECT_EQ(out.bitDepth, depth);
      EXPECT_EQ(out.samples, in.samples);
    }
}

TEST(PngIo, ReadsWhatWritePng8Wrote) {
  TempDir dir;
  const std::vector<std::uint8_t> rgb = {0, 128, 255, 10, 20, 30};
  writePng8(dir.path() / "p.png", 2, 1, rgb);
  const PngImage out = readPng(dir.path() / "p.png");
  ASSERT_EQ(out.channels, 3);
  EXPECT_EQ(out.bitDepth, 8);
  EXPECT_EQ(out.samples, std::vector<std::uint16_t>(rgb.begin(), rgb.end()));
}

void expectReadError(const fs::path& file, const std::string& text) {
  try {
    readPng(file);
    ADD_FAILURE() << "no InputError for " << file;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, file.string());
    EXPECT_NE(e.message().find(text), std::string::npos) << e.what();
  }
}

TEST(PngIo, UnreadableFilesAreInputErrors) {
  TempDir dir;
  expectReadError(dir.path() / "missing.png", "cannot read PNG");
  std::ofstream(dir.path() / "text.png") << "hello, not a png";
  expectReadError(dir.path() / "text.png", "not a PNG file");
  writePng(dir.path() / "ok.png", makeImage(64, 64, 3, 8));
  std::ostringstream bytes;
  bytes << std::ifstream(dir.path() / "ok.png", std::ios::binary).rdbuf();
  const std::string full = bytes.str();
  for (size_t cut : {size_t{12}, size_t{40}, full.size() / 2, full.size() - 13}) {
    std::ofstream(dir.path() / "cut.png", std::ios::binary) << full.substr(0, cut);
    expectReadError(dir.path() / "cut.png", "cannot read PNG");
  }
  std::string corrupt = full;
  corrupt[corrupt.size() / 2] = static_cast<char>(corrupt[corrupt.size() / 2] ^ 0x55);
  std::ofstream(dir.path() / "corrupt.png", std::ios::binary) << corrupt;
  expectReadError(dir.path() / "corrupt.png", "cannot read PNG");
}

}  // namespace
}  // namespace camsim
