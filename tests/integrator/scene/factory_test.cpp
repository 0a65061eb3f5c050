// Tests for integrator/scene/factory.cpp: a TextureCache uplifts a reflectance image once per
// (file, encoding), so that materials and uv transforms naming the same texture share its
// texels; another encoding of the same file is another uplift; without a cache each texture
// uplifts its own, to the same values; texels that differ under one name are not shared.
#include "integrator/scene/factory.h"

#include <gtest/gtest.h>

#include "integrator/textures/image_texture.h"
#include "tests/integrator/texture_test_support.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

const ImageSpectrumTexture* asImage(const std::unique_ptr<SpectrumTexture>& t) {
  return dynamic_cast<const ImageSpectrumTexture*>(t.get());
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
  const ImageSpectrumTexture *ia = asImage(a), *ib = asImage(b), *ic = asImage(c);
  ASSERT_TRUE(ia && ib && ic);
  EXPECT_EQ(ia->texels(), ib->texels());
  EXPECT_NE(ia->texels(), ic->texels());
  EXPECT_EQ(cache.size(), 2u);

  // Through a material too; and without a cache, an uplift of its own with equal values.
  MaterialDescription m;
  m.type = MaterialDescription::Type::kDiffuse;
  m.reflectance = d;
  EXPECT_NE(makeMaterial(m, &cache), nullptr);
  EXPECT_EQ(cache.size(), 2u);
  const auto own = makeSpectrumTexture(d);
  ASSERT_TRUE(asImage(own));
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x)
      for (float lambda : {400.0f, 550.0f, 700.0f})
        EXPECT_EQ(asImage(own)->texelValue(x, y, lambda), ia->texelValue(x, y, lambda));
  // sRGB and linear decodings of the same file are different reflectances.
  EXPECT_NE(ia->texelValue(0, 0, 650.0f), ic->texelValue(0, 0, 650.0f));
}

// Descriptions built in code: decoded texels under the name of a cached texture share it
// only if they are the same texels; without a name nothing is shared.
TEST(TextureCache, SharesOnlyEqualTexels) {
  const auto image = [](float red) {
    TextureImage t;
    t.width = 1;
    t.height = 1;
    t.channels = 3;
    t.values = {red, 0.2f, 0.2f};
    return std::make_shared<const TextureImage>(t);
  };
  TextureDescription d;
  d.kind = TextureDescription::Kind::kImage;
  d.file = "in_code.png";
  d.encoding = TextureEncoding::kLinear;
  d.image = image(0.8f);
  TextureDescription sameTexels = d;
  sameTexels.image = image(0.8f);  // another decoding of the same file
  TextureDescription otherTexels = d;
  otherTexels.image = image(0.1f);
  TextureDescription unnamed = d;
  unnamed.file.clear();

  TextureCache cache;
  const auto a = cache.uplifted(d);
  EXPECT_EQ(cache.uplifted(sameTexels), a);
  const auto other = cache.uplifted(otherTexels);
  EXPECT_NE(other, a);
  EXPECT_LT(other->coefficients[0](650.0f), a->coefficients[0](650.0f));  // less red
  EXPECT_NE(cache.uplifted(unnamed), a);
  EXPECT_EQ(cache.size(), 1u);
}

}  // namespace
}  // namespace camsim
