// Tests for integrator/image_texture: decoding (sRGB 8-bit 128 → 0.2158, 16-bit, grey and
// alpha layouts, EXR channels and chromaticities), the uplift of texels, bilinear filtering,
// repeat addressing and the v orientation, errors naming the file, the load time of a
// 1024² texture, and a rendered image quad that shows the picture upright.
#include "integrator/textures/image_texture.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <random>
#include <sstream>

#include "integrator/textures/reflectance_uplift.h"
#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "sensor/spectra/color_space.h"
#include "sensor/spectra/rgb_uplift.h"
#include "tests/integrator/texture_test_support.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;
using test::TempDir;
using test::writeTestPng;

fs::path writeRgbExr(const fs::path& path, int w, int h, const std::vector<glm::vec3>& rgb,
                     const std::optional<ExrChromaticities>& chromaticities = std::nullopt) {
  Image image(w, h, {"R", "G", "B"});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = rgb[static_cast<size_t>(y * w + x)][c];
  writeExr(path, image, {}, chromaticities);
  return path;
}

// A w×h grey float texture with the given values (row 0 at the top), raw.
TextureImage greyImage(int w, int h, std::vector<float> values) {
  return TextureImage{w, h, 1, std::move(values), {}};
}

// Spectrum of texel (x, y) on the 1 nm grid and its RGB under D65.
glm::dvec3 texelRgb(const ImageSpectrumTexture& t, int x, int y) {
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i)
    s.sample(i) = t.texelValue(x, y, static_cast<float>(kLambdaMinNm + i));
  return reflectanceToRgb(s, RgbColorSpace::linearRec709());
}

TEST(ImageTexture, SrgbDecodeOf8Bit128) {
  TempDir dir;
  const fs::path png =
      writeTestPng(dir.path() / "grey.png", 3, 1, 3, 8, {128, 128, 128, 0, 0, 0, 255, 255, 255});
  const TextureImage srgb =
      loadTextureImage(png, defaultTextureEncoding(png));  // PNG default: srgb
  ASSERT_EQ(srgb.channels, 3);
  EXPECT_NEAR(srgb.values[0], 0.2158f, 1e-4f);  // ((128/255 + 0.055)/1.055)^2.4 = 0.21586
  EXPECT_FLOAT_EQ(srgb.values[3], 0.0f);
  EXPECT_FLOAT_EQ(srgb.values[8], 1.0f);
  const TextureImage linear = loadTextureImage(png, TextureEncoding::kLinear);
  EXPECT_FLOAT_EQ(linear.values[0], 128.0f / 255.0f);
}

TEST(ImageTexture, PngLayoutsAndBitDepths) {
  TempDir dir;
  // 16-bit grey + alpha: one channel, alpha ignored.
  const fs::path ga = writeTestPng(dir.path() / "ga.png", 2, 1, 2, 16, {32768, 0, 65535, 1000});
  const TextureImage g = loadTextureImage(ga, TextureEncoding::kRaw);
  ASSERT_EQ(g.channels, 1);
  EXPECT_FLOAT_EQ(g.values[0], 32768.0f / 65535.0f);
  EXPECT_FLOAT_EQ(g.values[1], 1.0f);
  // 8-bit RGBA: three channels.
  const fs::path rgba = writeTestPng(dir.path() / "rgba.png", 1, 1, 4, 8, {51, 102, 204, 7});
  const TextureImage c = loadTextureImage(rgba, TextureEncoding::kRaw);
  ASSERT_EQ(c.channels, 3);
  EXPECT_FLOAT_EQ(c.values[2], 0.8f);
}

// Grey texels are uplifted exactly (the flat spectrum); a near-grey one within the fit's
// measured RGB error (reflectance_uplift_test: ≤ 2e-5), its spectrum flat within ±0.02.
TEST(ImageTexture, LinearExrGreyUpliftsToAFlatSpectrum) {
  TempDir dir;
  const fs::path exr =
      writeRgbExr(dir.path() / "grey.exr", 2, 1, {{0.18f, 0.18f, 0.18f}, {0.18f, 0.185f, 0.175f}});
  const TextureImage image =
      loadTextureImage(exr, defaultTextureEncoding(exr));  // EXR default: linear
  const ImageSpectrumTexture t(image, glm::vec2(1.0f), glm::vec2(0.0f));
  test::MaxError flatness;
  for (float lambda = 360.0f; lambda <= 830.0f; lambda += 10.0f) {
    EXPECT_NEAR(t.texelValue(0, 0, lambda), 0.18f, 1e-6f) << lambda;
    if (lambda >= 400.0f && lambda <= 700.0f) {
      EXPECT_LT(flatness(t.texelValue(1, 0, lambda), 0.18), 0.1) << lambda;
    }
  }
  const glm::dvec3 rgb = texelRgb(t, 1, 0);
  EXPECT_NEAR(rgb.x, 0.18, 2e-5);
  EXPECT_NEAR(rgb.y, 0.185, 2e-5);
  EXPECT_NEAR(rgb.z, 0.175, 2e-5);
  EXPECT_GT(t.maxValue(), 0.18);
  EXPECT_LE(t.maxValue(), 0.2);
}

TEST(ImageTexture, ExrGreyChannelsAndChromaticities) {
  TempDir dir;
  Image y(1, 1, {"Y"});
  y.at(0, 0, 0) = 0.25f;
  writeExr(dir.path() / "y.exr", y, {}, std::nullopt);
  EXPECT_EQ(loadTextureImage(dir.path() / "y.exr", TextureEncoding::kRaw).channels, 1);
  Image one(1, 1, {"roughness"});
  one.at(0, 0, 0) = 0.3f;
  writeExr(dir.path() / "r.exr", one, {}, std::nullopt);
  EXPECT_FLOAT_EQ(loadTextureImage(dir.path() / "r.exr", TextureEncoding::kRaw).values[0], 0.3f);
  // ACEScg primaries: white stays white, AP1 red becomes Rec.709 (1.705, −0.130, −0.024).
  const RgbColorSpace& ap1 = RgbColorSpace::acesCg();
  const ExrChromaticities chroma{ap1.red(), ap1.green(), ap1.blue(), ap1.white()};
  const fs::path exr =
      writeRgbExr(dir.path() / "ap1.exr", 2, 1, {{0.5f, 0.5f, 0.5f}, {1.0f, 0.0f, 0.0f}}, chroma);
  const TextureImage lin = loadTextureImage(exr, TextureEncoding::kLinear);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(lin.values[static_cast<size_t>(c)], 0.5f, 1e-3f);
  EXPECT_NEAR(lin.values[3], 1.705f, 3e-3f);
  EXPECT_NEAR(lin.values[4], -0.130f, 3e-3f);
  EXPECT_NEAR(lin.values[5], -0.024f, 3e-3f);
  EXPECT_FLOAT_EQ(loadTextureImage(exr, TextureEncoding::kRaw).values[3], 1.0f);  // raw: untouched
}

// Texel centres of a 2×1 image at u = 1/4 and 3/4.
TEST(ImageTexture, BilinearHalfwayAndAtCentres) {
  const ImageFloatTexture f(greyImage(2, 1, {0.2f, 0.6f}), glm::vec2(1.0f), glm::vec2(0.0f));
  EXPECT_NEAR(f.evaluate({0.25f, 0.5f}), 0.2f, 1e-6f);
  EXPECT_NEAR(f.evaluate({0.75f, 0.5f}), 0.6f, 1e-6f);
  EXPECT_NEAR(f.evaluate({0.5f, 0.5f}), 0.4f, 1e-6f);
  EXPECT_NEAR(f.evaluate({0.375f, 0.9f}), 0.3f, 1e-6f);  // a quarter of the way
  const ImageSpectrumTexture s(greyImage(2, 1, {0.2f, 0.6f}), glm::vec2(1.0f), glm::vec2(0.0f));
  const SampledSpectrum v = s.evaluate({0.5f, 0.5f}, SampledWavelengths::sampleUniform(0.4f));
  for (int i = 0; i < kWavelengthSamples; ++i) EXPECT_NEAR(v[i], 0.4f, 1e-6f);
  EXPECT_NEAR(s.maxValue(), 0.6, 1e-6);
}

TEST(ImageTexture, RepeatAddressingAndUvTransform) {
  const ImageFloatTexture f(greyImage(2, 1, {0.2f, 0.6f}), glm::vec2(1.0f), glm::vec2(0.0f));
  EXPECT_NEAR(f.evaluate({0.0f, 0.5f}), 0.4f, 1e-6f);  // between the last and first column
  EXPECT_NEAR(f.evaluate({1.0f, 0.5f}), 0.4f, 1e-6f);
  EXPECT_NEAR(f.evaluate({1.25f, 0.5f}), 0.2f, 1e-6f);
  EXPECT_NEAR(f.evaluate({-0.75f, 3.0f}), 0.2f, 1e-6f);
  EXPECT_NEAR(f.evaluate({-0.25f, -7.5f}), 0.6f, 1e-6f);
  EXPECT_NEAR(f.evaluate({-0.125f, 0.5f}), 0.5f,
              1e-6f);  // ≡ 0.875: between 0.6 and the wrapped 0.2
  EXPECT_TRUE(std::isfinite(f.evaluate({1e30f, std::numeric_limits<float>::quiet_NaN()})));
  const ImageFloatTexture shifted(greyImage(2, 1, {0.2f, 0.6f}), {2.0f, 1.0f}, {0.5f, 0.0f});
  EXPECT_NEAR(shifted.evaluate({0.125f, 0.5f}), 0.6f, 1e-6f);  // u' = 0.75
}

// v = 0 is the bottom of the picture: a 1×2 image with 0.2 in its top row, 0.6 below.
TEST(ImageTexture, VZeroIsTheBottomRow) {
  const ImageFloatTexture f(greyImage(1, 2, {0.2f, 0.6f}), glm::vec2(1.0f), glm::vec2(0.0f));
  EXPECT_NEAR(f.evaluate({0.5f, 0.25f}), 0.6f, 1e-6f);
  EXPECT_NEAR(f.evaluate({0.5f, 0.75f}), 0.2f, 1e-6f);
  const ImageFloatTexture rgb(TextureImage{1, 1, 3, {0.1f, 0.2f, 0.6f}, {}}, glm::vec2(1.0f),
                              glm::vec2(0.0f));
  EXPECT_NEAR(rgb.evaluate({0.3f, 0.3f}), 0.3f, 1e-6f);  // the mean of R, G, B
  const ImageFloatTexture negative(greyImage(1, 1, {-0.5f}), glm::vec2(1.0f), glm::vec2(0.0f));
  EXPECT_EQ(negative.evaluate({0.3f, 0.3f}), 0.0f);
}

void expectFileError(const fs::path& file, const std::string& text) {
  try {
    loadTextureImage(file, defaultTextureEncoding(file));
    ADD_FAILURE() << "no InputError for " << file;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, file.string());
    EXPECT_NE(e.message().find(text), std::string::npos) << e.what();
  }
}

TEST(ImageTexture, BadFilesAreInputErrorsNamingTheFile) {
  TempDir dir;
  expectFileError(dir.path() / "missing.png", "does not exist");
  std::ofstream(dir.path() / "text.png") << "not a png at all";
  expectFileError(dir.path() / "text.png", "not a PNG");
  std::ofstream(dir.path() / "text.exr") << "not an exr";
  expectFileError(dir.path() / "text.exr", "cannot read EXR");
  std::ofstream(dir.path() / "a.jpg") << "jpeg";
  expectFileError(dir.path() / "a.jpg", "unsupported texture file type '.jpg'");
  const fs::path png = writeTestPng(dir.path() / "ok.png", 1, 1, 1, 8, {1});
  Image xz(1, 1, {"X", "Z"});
  writeExr(dir.path() / "xz.exr", xz, {}, std::nullopt);
  expectFileError(dir.path() / "xz.exr", "unsupported EXR channels (X, Z)");
  std::ostringstream bytes;
  bytes << std::ifstream(png, std::ios::binary).rdbuf();
  const std::string truncated = bytes.str();
  std::ofstream(dir.path() / "cut.png", std::ios::binary)
      << truncated.substr(0, truncated.size() / 2);
  expectFileError(dir.path() / "cut.png", "cannot read PNG");
}

// A 256² 8-bit sRGB PNG of random colours (every texel a new colour): every texel uplifted,
// 20 spot checks of the round trip. (Its speed is measured by `camsim bench`, texture load.)
TEST(ImageTexture, RandomColourTextureRoundTripsEveryTexel) {
  TempDir dir;
  constexpr int kSize = 256;
  std::mt19937 rng(5);
  std::vector<std::uint16_t> samples(kSize * kSize * 3);
  for (auto& s : samples) s = static_cast<std::uint16_t>(rng() & 0xff);
  const fs::path png = writeTestPng(dir.path() / "noise.png", kSize, kSize, 3, 8, samples);
  const TextureImage image = loadTextureImage(png, TextureEncoding::kSrgb);
  const ImageSpectrumTexture t(image, glm::vec2(1.0f), glm::vec2(0.0f));
  for (int k = 0; k < 20; ++k) {
    const int x = static_cast<int>(rng() % kSize), y = static_cast<int>(rng() % kSize);
    const size_t i = (static_cast<size_t>(y) * kSize + static_cast<size_t>(x)) * 3;
    const glm::dvec3 rgb = texelRgb(t, x, y);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(rgb[c], image.values[i + static_cast<size_t>(c)], 5e-5) << x << "," << y;
  }
}

// The quad of texture_test_support.h with a 4×4 PNG of four 2×2 blocks (linear codes 51,
// 102, 153, 204 = 0.2, 0.4, 0.6, 0.8; top-left, top-right, bottom-left, bottom-right).
// Pixels 1–2 and 5–6 of each row/column see one block only (texel centres 1/8 … 3/8 and
// 5/8 … 7/8 of the same value): the picture must appear upright and unmirrored.
// Tolerance 1 % (Monte Carlo noise, see the checkerboard render test).
TEST(ImageTexture, RenderedQuadShowsThePictureUpright) {
  TempDir dir;
  const std::uint16_t tl = 51, tr = 102, bl = 153, br = 204;
  std::vector<std::uint16_t> grey = {tl, tl, tr, tr, tl, tl, tr, tr,
                                     bl, bl, br, br, bl, bl, br, br};
  writeTestPng(dir.path() / "blocks.png", 4, 4, 1, 8, grey);
  const test::LuminanceImage img = test::renderLuminance(
      test::texturedQuadScene("{texture: blocks.png, encoding: linear}"), 1024, 3, dir.path());
  test::MaxError worst;
  for (int py : {1, 2, 5, 6})
    for (int px : {1, 2, 5, 6}) {
      const std::uint16_t code = py < 4 ? (px < 4 ? tl : tr) : (px < 4 ? bl : br);
      const double expected = code / 255.0 * 0.01 * test::flatRadianceY();
      EXPECT_LT(worst(img.at(px, py), expected), 0.01) << px << "," << py;
    }
}

}  // namespace
}  // namespace camsim
