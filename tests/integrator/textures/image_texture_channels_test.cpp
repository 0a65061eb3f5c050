// Channel selection of scalar image textures (ImageFloatTexture, TextureDescription::channel)
// and the alpha channel that decoding keeps apart (integrator/textures/image_texture.h):
//  - an RGBA PNG read raw: channel 0, 1, 2, 3 give R, G, B, A; −1 the mean of R, G, B;
//  - sRGB decoding applies to R, G, B, never to alpha;
//  - grey images give their grey for channels 0–2; no alpha reads 1 (as a GPU samples);
//  - an EXR's A channel is kept; the factory passes the description's channel on.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "integrator/scene/factory.h"
#include "integrator/textures/image_texture.h"
#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "tests/integrator/texture_test_support.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

float channelValue(const TextureImage& image, int channel) {
  return ImageFloatTexture(image, glm::vec2(1.0f), glm::vec2(0.0f), channel).evaluate({0.5f, 0.5f});
}

TEST(ImageTextureChannels, RgbaPngChannels) {
  test::TempDir dir;
  // 16-bit so that the values are exact to 1e-5: R 0.2, G 0.4, B 0.8, A 0.6.
  const auto q = [](double v) { return static_cast<std::uint16_t>(std::lround(v * 65535.0)); };
  const auto png =
      test::writeTestPng(dir.path() / "rgba.png", 1, 1, 4, 16, {q(0.2), q(0.4), q(0.8), q(0.6)});
  const TextureImage raw = loadTextureImage(png, TextureEncoding::kRaw);
  EXPECT_EQ(raw.channels, 3);
  ASSERT_EQ(raw.alpha.size(), 1u);
  EXPECT_NEAR(channelValue(raw, 0), 0.2f, 1e-5f);
  EXPECT_NEAR(channelValue(raw, 1), 0.4f, 1e-5f);
  EXPECT_NEAR(channelValue(raw, 2), 0.8f, 1e-5f);
  EXPECT_NEAR(channelValue(raw, 3), 0.6f, 1e-5f);
  EXPECT_NEAR(channelValue(raw, -1), (0.2f + 0.4f + 0.8f) / 3.0f, 1e-5f);
  // sRGB: the colour decoded, the alpha as stored.
  const TextureImage srgb = loadTextureImage(png, TextureEncoding::kSrgb);
  EXPECT_NEAR(srgb.values[1], std::pow((0.4 + 0.055) / 1.055, 2.4), 1e-5);
  EXPECT_NEAR(srgb.alpha[0], 0.6f, 1e-5f);
  // Without alpha: channel 3 reads 1, and the image has no alpha to carry.
  const auto rgb = test::writeTestPng(dir.path() / "rgb.png", 1, 1, 3, 8, {0, 255, 51});
  const TextureImage noAlpha = loadTextureImage(rgb, TextureEncoding::kRaw);
  EXPECT_TRUE(noAlpha.alpha.empty());
  EXPECT_EQ(channelValue(noAlpha, 3), 1.0f);
  EXPECT_EQ(channelValue(noAlpha, 1), 1.0f);
  EXPECT_FLOAT_EQ(channelValue(noAlpha, 2), 0.2f);
}

TEST(ImageTextureChannels, GreyImagesAndExrAlpha) {
  test::TempDir dir;
  const auto ga = test::writeTestPng(dir.path() / "ga.png", 1, 1, 2, 8, {51, 102});
  const TextureImage grey = loadTextureImage(ga, TextureEncoding::kRaw);
  EXPECT_EQ(grey.channels, 1);
  for (int c : {-1, 0, 1, 2}) EXPECT_FLOAT_EQ(channelValue(grey, c), 0.2f) << c;
  EXPECT_FLOAT_EQ(channelValue(grey, 3), 0.4f);

  Image im(2, 1, {"R", "G", "B", "A"});
  for (int x = 0; x < 2; ++x)
    for (int c = 0; c < 4; ++c) im.at(x, 0, c) = 0.125f * static_cast<float>(c + 1 + 4 * x);
  writeExr(dir.path() / "rgba.exr", im, {}, std::nullopt);
  TextureDescription d;
  d.kind = TextureDescription::Kind::kImage;
  d.file = dir.path() / "rgba.exr";
  d.encoding = TextureEncoding::kRaw;
  const TextureImage exr = loadTextureImage(d.file, d.encoding);
  ASSERT_EQ(exr.alpha.size(), 2u);
  EXPECT_EQ(exr.alpha[1], 1.0f);
  // Through the factory: texel x = 0 at u = 0.25 (bilinear weights 1, 0).
  for (int c = 0; c < 4; ++c) {
    d.channel = c;
    EXPECT_FLOAT_EQ(makeFloatTexture(d)->evaluate({0.25f, 0.5f}),
                    0.125f * static_cast<float>(c + 1))
        << c;
  }
  d.channel = -1;
  EXPECT_FLOAT_EQ(makeFloatTexture(d)->evaluate({0.25f, 0.5f}), 0.25f);  // mean of R, G, B
}

// Found by probing: a NaN texel read as 0 (a black surface, a mirror's roughness), +inf as a
// reflectance of 1 or an infinite roughness, silently. Refused, named by texel and channel.
TEST(ImageTextureChannels, NonFiniteExrTexelsAreRefused) {
  test::TempDir dir;
  const float inf = std::numeric_limits<float>::infinity();
  const struct {
    std::vector<std::string> channels;
    int x, c;
    float value;
    const char* says;
  } cases[] = {
      {{"R", "G", "B"}, 1, 2, std::nanf(""), "texel (1, 0) of channel B is NaN"},
      {{"R", "G", "B"}, 0, 0, inf, "texel (0, 0) of channel R is infinite"},
      {{"Y"}, 1, 0, -inf, "texel (1, 0) of channel Y is infinite"},
      {{"R", "G", "B", "A"}, 1, 3, std::nanf(""), "texel (1, 0) of channel A is NaN"},
  };
  for (const auto& k : cases) {
    Image im(2, 1, k.channels);
    im.at(k.x, 0, k.c) = k.value;
    const auto file = dir.path() / "bad.exr";
    writeExr(file, im, {}, std::nullopt);
    try {
      loadTextureImage(file, TextureEncoding::kRaw);
      ADD_FAILURE() << k.says << ": loaded";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, file.string());
      EXPECT_NE(e.message().find(k.says), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace camsim
