// Tests for integrator/scene/scene_loader_materials.cpp's metallic_roughness material and
// the normal-map keys of every material, and the `channel` key of scalar image textures
// (scene_loader_textures.cpp): what loads into the MaterialDescription, what the factory
// builds from it, and every bad input an InputError at its key (file, line, column).
#include <gtest/gtest.h>

#include <string>

#include "integrator/scene/factory.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "integrator/textures/image_texture.h"
#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "tests/integrator/texture_test_support.h"
#include "tests/support/scene_text.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

using test::TempDir;

class MaterialScene : public ::testing::Test {
 protected:
  void SetUp() override {
    // RGBA 8-bit: R 51, G 102, B 204, A 255 → raw 0.2, 0.4, 0.8, 1.
    test::writeTestPng(dir_.path() / "mr.png", 1, 1, 4, 8, {51, 102, 204, 255});
    test::writeTestPng(dir_.path() / "grey.png", 1, 1, 1, 8, {128});
    Image normal(1, 1, {"R", "G", "B"});
    normal.at(0, 0, 0) = 0.75f;
    normal.at(0, 0, 1) = 0.5f;
    normal.at(0, 0, 2) = 1.0f;
    writeExr(dir_.path() / "normal.exr", normal, {}, std::nullopt);
  }
  MaterialDescription load(const std::string& material) {
    return loadSceneFromText(test::materialScene(material), "test.yaml", dir_.path())
        .materials.at(0);
  }
  void expectError(const std::string& material, int column, const std::string& key,
                   const std::string& message) {
    SCOPED_TRACE(material);
    try {
      load(material);
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, "test.yaml") << e.what();
      EXPECT_EQ(e.where().line, 3) << e.what();
      EXPECT_EQ(e.where().column, column) << e.what();
      EXPECT_EQ(e.key(), key) << e.what();
      EXPECT_NE(e.message().find(message), std::string::npos) << e.what();
    }
  }
  TempDir dir_;
};

TEST_F(MaterialScene, MetallicRoughnessKeys) {
  const MaterialDescription d = load("{type: metallic_roughness}");
  EXPECT_EQ(d.type, MaterialDescription::Type::kMetallicRoughness);
  EXPECT_FLOAT_EQ(d.reflectance.value(550.0f), 0.5f);  // documented defaults
  EXPECT_FLOAT_EQ(d.metallic.value(550.0f), 0.0f);
  EXPECT_FLOAT_EQ(d.roughness.value(550.0f), 0.0f);
  EXPECT_FALSE(d.normalMap.has_value());

  const MaterialDescription c = load(
      "{type: metallic_roughness, base_color: {rgb: [0.8, 0.2, 0.1]}, metallic: 0.7, roughness: "
      "0.3}");
  EXPECT_GT(c.reflectance.value(650.0f), c.reflectance.value(450.0f));
  EXPECT_FLOAT_EQ(c.metallic.value(550.0f), 0.7f);
  EXPECT_FLOAT_EQ(c.roughness.value(550.0f), 0.3f);

  // glTF's packing: roughness in G, metalness in B of one image; the base colour sRGB.
  const MaterialDescription t = load(
      "{type: metallic_roughness, base_color: {texture: mr.png}, metallic: {texture: mr.png, "
      "channel: 2}, roughness: {texture: mr.png, channel: 1}, normal_map: {texture: normal.exr, "
      "scale: 2}, normal_scale: 0.5}");
  EXPECT_EQ(t.reflectance.encoding, TextureEncoding::kSrgb);
  EXPECT_EQ(t.metallic.encoding, TextureEncoding::kRaw);
  EXPECT_EQ(t.metallic.channel, 2);
  EXPECT_EQ(t.roughness.channel, 1);
  ASSERT_TRUE(t.normalMap.has_value());
  EXPECT_EQ(t.normalMap->encoding, TextureEncoding::kRaw);
  EXPECT_EQ(t.normalMap->uvScale, glm::vec2(2.0f));
  EXPECT_FLOAT_EQ(t.normalScale, 0.5f);
  // What the factory makes of it: α = 0.4² from G, m = 0.8 from B, the normal map halved.
  const std::unique_ptr<Material> m = makeMaterial(t);
  ASSERT_NE(m->normalMap(), nullptr);
  EXPECT_FLOAT_EQ(m->normalMap()->strength(), 0.5f);
  const glm::vec3 nt = m->normalMap()->tangentSpaceNormal({0.5f, 0.5f});
  EXPECT_NEAR(nt.x / nt.z, 0.25f, 1e-6f);  // (2·0.75 − 1) · 0.5
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.5f);
  EXPECT_NEAR(m->aov(lambda, BsdfContext{}).roughness, 0.16f, 1e-6f);
  EXPECT_EQ(makeFloatTexture(t.metallic)->evaluate({0.5f, 0.5f}), 0.8f);

  // Normal maps on the other materials too.
  const MaterialDescription dn =
      load("{type: diffuse, reflectance: 0.3, normal_map: {texture: normal.exr}}");
  ASSERT_TRUE(dn.normalMap.has_value());
  EXPECT_FLOAT_EQ(dn.normalScale, 1.0f);
  EXPECT_NE(makeMaterial(dn)->normalMap(), nullptr);
  EXPECT_EQ(makeMaterial(load("{type: diffuse}"))->normalMap(), nullptr);

  // Released images are read again from the files (and the scene still builds).
  SceneDescription released = loadSceneFromText(
      test::materialScene(
          "{type: metallic_roughness, metallic: {texture: mr.png, channel: 2}, normal_map: "
          "{texture: normal.exr}}"),
      "test.yaml", dir_.path());
  released.releaseDecodedImages();
  EXPECT_FALSE(released.materials.at(0).metallic.image);
  EXPECT_FALSE(released.materials.at(0).normalMap->image);
  EXPECT_NO_THROW(Scene{released});
}

// Columns: the material's value starts at column 6 of line 3.
TEST_F(MaterialScene, BadInputsAreRejectedAtTheirKey) {
  expectError("{type: metallic_roughness, metallic: 1.5}", 43, "materials.m.metallic",
              "out of range");
  expectError("{type: metallic_roughness, roughness: 2}", 44, "materials.m.roughness",
              "out of range");
  expectError("{type: metallic_roughness, roughness: [0.5]}", 44, "materials.m.roughness",
              "expected a number in [0, 1]");
  expectError("{type: metallic_roughness, metallic: {checkerboard: {a: 2}}}", 62,
              "materials.m.metallic.checkerboard.a", "out of range");
  expectError("{type: metallic_roughness, reflectance: 0.5}", 33, "materials.m.reflectance",
              "unknown key");
  expectError("{type: metallic_roughness, anisotropy: 0.5}", 33, "materials.m.anisotropy",
              "unknown key");
  expectError("{type: metallic_roughness, metallic: {texture: mr.png, channel: 4}}", 70,
              "materials.m.metallic.channel", "out of range");
  expectError("{type: metallic_roughness, base_color: {texture: mr.png, channel: 1}}", 72,
              "materials.m.base_color.channel", "not of a colour texture");
  expectError("{type: diffuse, normal_map: {texture: normal.exr, channel: 0}}", 65,
              "materials.m.normal_map.channel", "not of a normal map");
  expectError("{type: diffuse, normal_map: {texture: normal.exr, encoding: srgb}}", 56,
              "materials.m.normal_map.encoding", "unknown key");
  expectError("{type: diffuse, normal_map: {texture: grey.png}}", 44,
              "materials.m.normal_map.texture", "needs R, G and B");
  expectError("{type: diffuse, normal_map: 0.5}", 34, "materials.m.normal_map",
              "an RGB normal map");
  expectError("{type: diffuse, normal_map: {checkerboard: {a: 0.5}}}", 34, "materials.m.normal_map",
              "an RGB normal map");
  expectError("{type: diffuse, normal_scale: 2}", 36, "materials.m.normal_scale",
              "needs a 'normal_map'");
  expectError("{type: diffuse, normal_map: {texture: normal.exr}, normal_scale: 1000}", 71,
              "materials.m.normal_scale", "out of range");
  expectError("{type: metallic_rough}", 13, "materials.m.type", "metallic_roughness");
}

}  // namespace
}  // namespace camsim
