// Tests for sensor/exr_io: bit-exact float round trips, metadata and chromaticities.
#include "sensor/io/exr_io.h"

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <system_error>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

// A fresh directory per test, removed afterwards.
class ExrIoTest : public testing::Test {
 protected:
  test::TempDir tmp_;
  std::filesystem::path dir_ = tmp_.path();
};

std::uint32_t bits(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

Image testImage() {
  Image image(7, 5, {"R", "G", "B", "XYZ.X", "XYZ.Y", "XYZ.Z"});
  std::mt19937 rng(777u);
  std::uniform_real_distribution<float> dist(-10.0f, 1000.0f);
  for (float& v : image.pixels) v = dist(rng);
  // Values whose bits a lossy path or a half-float conversion would change.
  image.at(0, 0, 0) = -0.0f;
  image.at(1, 0, 0) = std::numeric_limits<float>::denorm_min();
  image.at(2, 0, 0) = std::numeric_limits<float>::max();
  image.at(3, 0, 0) = std::numeric_limits<float>::infinity();
  image.at(4, 0, 0) = 1.0f + std::numeric_limits<float>::epsilon();
  image.at(6, 4, 5) = 1e-30f;
  return image;
}

const ExrChromaticities kRec709{{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, {0.3127, 0.3290}};

TEST_F(ExrIoTest, RoundTripIsBitExact) {
  const Image image = testImage();
  const Metadata metadata{{"camsim.version", "0.1.0"},
                          {"camsim.scene", "scenes/cornell box.yaml"},
                          {"comments", "unicode: λ = 550 nm, ±5 %"},
                          {"empty", ""}};
  const std::filesystem::path path = dir_ / "image.exr";
  writeExr(path, image, metadata, kRec709);
  ASSERT_TRUE(std::filesystem::exists(path));

  const ExrFile read = readExr(path);
  ASSERT_EQ(read.image.width, image.width);
  ASSERT_EQ(read.image.height, image.height);
  // EXR stores channels sorted by name; compare as sets, then pixel by pixel by name.
  std::vector<std::string> expectedNames = image.channels;
  std::vector<std::string> readNames = read.image.channels;
  std::sort(expectedNames.begin(), expectedNames.end());
  std::sort(readNames.begin(), readNames.end());
  ASSERT_EQ(readNames, expectedNames);
  for (int c = 0; c < image.channelCount(); ++c) {
    const int rc = read.image.channelIndex(image.channels[c]);
    ASSERT_GE(rc, 0);
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        // Bit-identical: ZIP is lossless and the channels are 32-bit float.
        ASSERT_EQ(bits(read.image.at(x, y, rc)), bits(image.at(x, y, c)))
            << image.channels[c] << " at (" << x << ", " << y << ")";
  }

  // Metadata: exactly the string attributes written (order not significant).
  const std::map<std::string, std::string> expected(metadata.begin(), metadata.end());
  const std::map<std::string, std::string> got(read.metadata.begin(), read.metadata.end());
  EXPECT_EQ(got, expected);
  EXPECT_EQ(read.metadata.size(), metadata.size());

  // Chromaticities are stored as float: equal to the float-rounded inputs.
  ASSERT_TRUE(read.chromaticities.has_value());
  const auto f = [](double v) { return static_cast<double>(static_cast<float>(v)); };
  const ExrChromaticities& c = *read.chromaticities;
  EXPECT_EQ(c.red.x, f(0.64));
  EXPECT_EQ(c.red.y, f(0.33));
  EXPECT_EQ(c.green.x, f(0.30));
  EXPECT_EQ(c.green.y, f(0.60));
  EXPECT_EQ(c.blue.x, f(0.15));
  EXPECT_EQ(c.blue.y, f(0.06));
  EXPECT_EQ(c.white.x, f(0.3127));
  EXPECT_EQ(c.white.y, f(0.3290));
}

TEST_F(ExrIoTest, NoChromaticitiesNoMetadata) {
  Image image(3, 2, {"Y"});
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = static_cast<float>(i) * 0.5f;
  const std::filesystem::path path = dir_ / "y.exr";
  writeExr(path, image, {}, std::nullopt);
  const ExrFile read = readExr(path);
  EXPECT_FALSE(read.chromaticities.has_value());
  EXPECT_TRUE(read.metadata.empty());
  ASSERT_EQ(read.image.channels, std::vector<std::string>{"Y"});
  EXPECT_EQ(read.image.pixels, image.pixels);
}

// Chromaticities no conversion can use (primaries on one point or line, a y of 0, NaN):
// refused by the reader naming the attribute (found by probing: camsim mtf got NaN luminance
// weights and blamed a "not finite" pixel of its ROI).
TEST_F(ExrIoTest, ChromaticitiesThatAreNoColourSpaceAreRefused) {
  Image image(2, 2, {"R", "G", "B"});
  const double nan = std::nan("");
  const ExrChromaticities bad[] = {
      {{0.3, 0.3}, {0.3, 0.3}, {0.3, 0.3}, {0.3127, 0.329}},
      {{0.1, 0.1}, {0.2, 0.2}, {0.3, 0.3}, {0.3127, 0.329}},
      {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.0}, {0.3127, 0.329}},
      {{nan, 0.33}, {0.30, 0.60}, {0.15, 0.06}, {0.3127, 0.329}},
  };
  // ACES AP0 (ACES2065-1), whose blue primary lies below y = 0, is a colour space.
  const ExrChromaticities ap0{{0.7347, 0.2653}, {0.0, 1.0}, {0.0001, -0.077}, {0.32168, 0.33767}};
  writeExr(dir_ / "ap0.exr", image, {}, ap0);
  EXPECT_NO_THROW((void)readExr(dir_ / "ap0.exr"));
  for (const ExrChromaticities& c : bad) {
    const std::filesystem::path path = dir_ / "bad.exr";
    writeExr(path, image, {}, c);
    try {
      (void)readExr(path);
      ADD_FAILURE() << "read";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "chromaticities");
      EXPECT_NE(e.message().find("are not a colour space"), std::string::npos) << e.what();
    }
  }
}

TEST_F(ExrIoTest, ReadingANonExrFileThrowsInputError) {
  const std::filesystem::path path = dir_ / "not_an_image.exr";
  std::ofstream(path) << "this is plain text, not OpenEXR\n";
  try {
    readExr(path);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, path.string());
  }
  EXPECT_THROW(readExr(dir_ / "missing.exr"), InputError);
}

TEST_F(ExrIoTest, ReadingATruncatedExrThrowsInputError) {
  const std::filesystem::path path = dir_ / "truncated.exr";
  writeExr(path, testImage(), {}, std::nullopt);
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size / 2);
  EXPECT_THROW(readExr(path), InputError);
}

// Raw EXR: raw.DN exact for every 16-bit value, the electrons layer bit-exact, the levels
// and the CFA name as string attributes (a caller's entry of the same name is replaced).
TEST_F(ExrIoTest, RawExrHoldsDnElectronsAndLevels) {
  RawImage raw;
  raw.width = 256;
  raw.height = 256;
  raw.cfa.width = raw.cfa.height = 2;
  raw.cfa.tile = {2, 1, 1, 0};
  raw.cfa.channels = {"R", "G", "B"};
  raw.cfa.name = "BGGR";
  raw.blackLevelDn = 64.5;
  raw.whiteLevelDn = 16383.0;
  for (int i = 0; i < raw.width * raw.height; ++i) raw.dn.push_back(static_cast<std::uint16_t>(i));
  Image electrons(raw.width, raw.height, {"expected", "variance"});
  std::mt19937 rng(99u);
  std::uniform_real_distribution<float> dist(0.0f, 50000.0f);
  for (float& v : electrons.pixels) v = dist(rng);
  const std::filesystem::path path = dir_ / "raw.exr";
  writeRawExr(path, raw, electrons, {{"camsim:sensor", "test"}, {"camsim:cfa", "stale"}});

  const ExrFile read = readExr(path);
  ASSERT_EQ(read.image.width, raw.width);
  ASSERT_EQ(read.image.height, raw.height);
  ASSERT_EQ(read.image.channelCount(), 3);
  const int dn = read.image.channelIndex("raw.DN");
  const int expected = read.image.channelIndex("electrons.expected");
  const int variance = read.image.channelIndex("electrons.variance");
  ASSERT_GE(dn, 0);
  ASSERT_GE(expected, 0);
  ASSERT_GE(variance, 0);
  for (int y = 0; y < raw.height; ++y)
    for (int x = 0; x < raw.width; ++x) {
      // Every value 0 … 65535 occurs once and comes back as exactly that integer.
      ASSERT_EQ(read.image.at(x, y, dn), static_cast<float>(raw.at(x, y))) << x << ", " << y;
      ASSERT_EQ(bits(read.image.at(x, y, expected)), bits(electrons.at(x, y, 0)));
      ASSERT_EQ(bits(read.image.at(x, y, variance)), bits(electrons.at(x, y, 1)));
    }
  EXPECT_EQ(read.image.at(255, 255, dn), 65535.0f);
  const std::map<std::string, std::string> got(read.metadata.begin(), read.metadata.end());
  const std::map<std::string, std::string> want{{"camsim:sensor", "test"},
                                                {"camsim:cfa", "BGGR"},
                                                {"camsim:black_level_dn", "64.5"},
                                                {"camsim:white_level_dn", "16383"}};
  EXPECT_EQ(got, want);
  EXPECT_EQ(read.metadata.size(), want.size());
  EXPECT_FALSE(read.chromaticities.has_value());
}

}  // namespace
}  // namespace camsim
