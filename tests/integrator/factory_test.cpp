// Tests for integrator/factory.cpp: a TextureCache uplifts a reflectance image once per
// (file, encoding), so that materials and uv transforms naming the same texture share its
// texels; another encoding of the same file is another uplift; without a cache each texture
// uplifts its own, to the same values.
#include "integrator/factory.h"

#include <gtest/gtest.h>

#include "integrator/image_texture.h"
#include "tests/integrator/texture_test_support.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

const ImageSpectrumTexture& asImage(const std::unique_ptr<SpectrumTexture>& t) {
  const auto* image = dynamic_cast<const ImageSpectrumTexture*>(t.get());
  EXPECT_NE(image, nullptr);
  return *image;
}

TEST(TextureCache, OneUpliftPerFileAndEncoding) {
  test::TempDir dir;
  // 2 × 2 RGB, 8 bit: four colours.
  const auto png = test::writeTestPng(dir.path() / "albedo.png", 2, 2, 3, 8,
                                      {200, 30, 30, 30, 200, 30, 30, 30, 200, 128, 128, 128});
  TextureDescription d;
  d.kind = TextureDescription::Kind::kImage;
  d.file = png;
  d.encoding = TextureEncoding::kSrgb;
  TextureDescription scaled = d;
  scaled.uvScale = glm::vec2(4.0f);
  TextureDescription linear = d;
  linear.encoding = TextureEncoding::kLinear;

  TextureCache cache;
  const auto a = makeSpectrumTexture(d, &cache);
  const auto b = makeSpectrumTexture(scaled, &cache);
  const auto c = makeSpectrumTexture(linear, &cache);
  EXPECT_EQ(asImage(a).texels(), asImage(b).texels());
  EXPECT_NE(asImage(a).texels(), asImage(c).texels());
  EXPECT_EQ(cache.size(), 2u);

  // Through a material too; and without a cache, an uplift of its own with equal values.
  MaterialDescription m;
  m.type = MaterialDescription::Type::kDiffuse;
  m.reflectance = d;
  EXPECT_NE(makeMaterial(m, &cache), nullptr);
  EXPECT_EQ(cache.size(), 2u);
  const auto own = makeSpectrumTexture(d);
  EXPECT_NE(asImage(own).texels(), asImage(a).texels());
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x)
      for (float lambda : {400.0f, 550.0f, 700.0f})
        EXPECT_EQ(asImage(own).texelValue(x, y, lambda), asImage(a).texelValue(x, y, lambda));
  // sRGB and linear decodings of the same file are different reflectances.
  EXPECT_NE(asImage(a).texelValue(0, 0, 650.0f), asImage(c).texelValue(0, 0, 650.0f));
}

}  // namespace
}  // namespace camsim
