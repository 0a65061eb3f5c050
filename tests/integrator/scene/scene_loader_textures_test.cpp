// Tests for integrator/scene/scene_loader_textures.cpp: reflectance and roughness given as
// constants, image textures and checkerboards load into the right TextureDescription, and
// every bad texture input is an InputError at the offending scene key (file, line, column);
// the decoded texels travel with the description (the file is read once).
#include <gtest/gtest.h>

#include <fstream>
#include <string>

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

namespace fs = std::filesystem;
using test::TempDir;

// The texture files live in the scene's directory.
class TextureScene : public ::testing::Test {
 protected:
  void SetUp() override {
    test::writeTestPng(dir_.path() / "albedo.png", 2, 2, 3, 8, std::vector<std::uint16_t>(12, 100));
    Image rough(2, 2, {"Y"});
    writeExr(dir_.path() / "rough.exr", rough, {}, std::nullopt);
    Image xz(1, 1, {"X", "Z"});
    writeExr(dir_.path() / "xz.exr", xz, {}, std::nullopt);
    std::ofstream(dir_.path() / "text.png") << "not a png";
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

TEST_F(TextureScene, ConstantsImagesAndCheckerboards) {
  const MaterialDescription c = load("{type: diffuse, reflectance: 0.3}");
  EXPECT_EQ(c.reflectance.kind, TextureDescription::Kind::kConstant);
  EXPECT_FLOAT_EQ(c.reflectance.value(500.0f), 0.3f);

  const MaterialDescription img =
      load("{type: diffuse, reflectance: {texture: albedo.png, scale: [2, 3], offset: 0.5}}");
  EXPECT_EQ(img.reflectance.kind, TextureDescription::Kind::kImage);
  EXPECT_EQ(img.reflectance.file, dir_.path() / "albedo.png");
  EXPECT_EQ(img.reflectance.encoding, TextureEncoding::kSrgb);  // the PNG default
  EXPECT_EQ(img.reflectance.uvScale, glm::vec2(2.0f, 3.0f));
  EXPECT_EQ(img.reflectance.uvOffset, glm::vec2(0.5f, 0.5f));

  const MaterialDescription board = load(
      "{type: diffuse, reflectance: {checkerboard: {a: {rgb: [0.9, 0.1, 0.1]}, b: 0.1, checks: "
      "3}}}");
  EXPECT_EQ(board.reflectance.kind, TextureDescription::Kind::kCheckerboard);
  EXPECT_FLOAT_EQ(board.reflectance.checkerB(600.0f), 0.1f);
  EXPECT_GT(board.reflectance.checkerA(650.0f), 0.5f);
  EXPECT_EQ(board.reflectance.checks, 3.0f);

  const MaterialDescription rough = load("{type: dielectric, roughness: {texture: rough.exr}}");
  EXPECT_EQ(rough.roughness.kind, TextureDescription::Kind::kImage);
  EXPECT_EQ(rough.roughness.encoding, TextureEncoding::kRaw);  // scalar maps default to raw
  EXPECT_EQ(load("{type: dielectric, roughness: 0.25}").roughness.value(550.0f), 0.25f);
  const MaterialDescription roughBoard =
      load("{type: dielectric, roughness: {checkerboard: {a: 0.05, b: 0.4}}}");
  EXPECT_FLOAT_EQ(roughBoard.roughness.checkerB(550.0f), 0.4f);
  EXPECT_EQ(roughBoard.roughness.checks, 8.0f);
}

// The loader reads each texture once and hands the decoded texels on: the scene is built
// from them even after the file is gone.
TEST_F(TextureScene, TheSceneIsBuiltFromTheTexelsTheLoaderRead) {
  const SceneDescription d = loadSceneFromText(
      test::materialScene(
          "{type: plastic, reflectance: {texture: albedo.png}, roughness: {texture: rough.exr}}"),
      "test.yaml", dir_.path());
  const MaterialDescription& m = d.materials.at(0);
  ASSERT_TRUE(m.reflectance.image);
  EXPECT_EQ(m.reflectance.image->width, 2);
  EXPECT_EQ(m.reflectance.image->channels, 3);
  ASSERT_TRUE(m.roughness.image);
  EXPECT_EQ(m.roughness.image->channels, 1);
  SceneDescription released = d;
  released.releaseDecodedImages();
  EXPECT_FALSE(released.materials.at(0).reflectance.image);
  EXPECT_FALSE(released.materials.at(0).roughness.image);
  EXPECT_NO_THROW(Scene{released});  // the files are read again
  fs::remove(dir_.path() / "albedo.png");
  fs::remove(dir_.path() / "rough.exr");
  EXPECT_NO_THROW(Scene{d});
  EXPECT_THROW(Scene{released}, InputError);  // …and are gone now
}

// Columns count from the line's start: the material's value begins at column 6, so
// "reflectance: {" opens at 35 and its first key's value ("{texture: X") starts at 45.
TEST_F(TextureScene, BadInputsAreRejectedAtTheirKey) {
  expectError("{type: diffuse, reflectance: {texture: nope.png}}", 45,
              "materials.m.reflectance.texture", "not found");
  expectError("{type: diffuse, reflectance: {texture: albedo.jpg}}", 45,
              "materials.m.reflectance.texture", "unsupported texture file type '.jpg'");
  expectError("{type: diffuse, reflectance: {texture: text.png}}", 45,
              "materials.m.reflectance.texture", "not a PNG");
  expectError("{type: diffuse, reflectance: {texture: xz.exr}}", 45,
              "materials.m.reflectance.texture", "unsupported EXR channels (X, Z)");
  expectError("{type: diffuse, reflectance: {texture: albedo.png, encoding: gamma}}", 67,
              "materials.m.reflectance.encoding", "unknown encoding 'gamma'");
  expectError("{type: diffuse, reflectance: {texture: albedo.png, scale: [1]}}", 64,
              "materials.m.reflectance.scale", "two numbers");
  expectError("{type: diffuse, reflectance: {texture: albedo.png, wrap: clamp}}", 57,
              "materials.m.reflectance.wrap", "unknown key");
  expectError("{type: diffuse, reflectance: {checkerboard: {checks: 0}}}", 59,
              "materials.m.reflectance.checkerboard.checks", "out of range");
  expectError("{type: diffuse, reflectance: {checkerboard: {a: 1.5}}}", 54,
              "materials.m.reflectance.checkerboard.a", "out of range");
  expectError("{type: diffuse, reflectance: {checkerboard: {a: 0.5, c: 1}}}", 59,
              "materials.m.reflectance.checkerboard.c", "unknown key");
  expectError("{type: diffuse, reflectance: {image: albedo.png}}", 35, "materials.m.reflectance",
              "{texture: FILE, …}");
  expectError("{type: dielectric, roughness: -0.1}", 36, "materials.m.roughness", "out of range");
  expectError("{type: dielectric, roughness: [0.1]}", 36, "materials.m.roughness",
              "expected a number ≥ 0");
  expectError("{type: dielectric, roughness: {checkerboard: {a: {rgb: [1, 0, 0]}}}}", 55,
              "materials.m.roughness.checkerboard.a", "expected a number");
}

}  // namespace
}  // namespace camsim
