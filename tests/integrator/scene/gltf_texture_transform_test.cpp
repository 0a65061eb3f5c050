// KHR_texture_transform on glTF textures (integrator/scene/gltf_materials.cpp): the base
// colour is sampled where the extension puts it. The expected texel is worked out in glTF's
// own uv (v down the image), from the extension's text: uv' = offset + R · (uv ⊙ scale),
// R = [cos r  sin r; −sin r  cos r] (counter-clockwise as the image is seen); the test picks
// uv' at texel centres, inverts the map to the surface's uv, converts that to camsim's
// (v up) and samples the texture the factory builds, which must give that texel.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include <glm/vec2.hpp>

#include "integrator/scene/factory.h"
#include "integrator/scene/scene_loader.h"
#include "integrator/textures/uv_transform.h"
#include "sensor/io/png_io.h"
#include "tests/integrator/scene/gltf_test_support.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

constexpr int kTransformSize = 4;  // a 4 × 4 image, every texel a different colour

struct Transform {
  glm::dvec2 offset{0.0}, scale{1.0};
  double rotation = 0.0;
  std::string json() const {
    return R"({"offset":[)" + std::to_string(offset.x) + "," + std::to_string(offset.y) +
           R"(],"scale":[)" + std::to_string(scale.x) + "," + std::to_string(scale.y) +
           R"(],"rotation":)" + std::to_string(rotation) + "}";
  }
};

// The surface's glTF uv that the transform maps to uv' (its inverse).
glm::dvec2 surfaceUv(const Transform& t, glm::dvec2 target) {
  const glm::dvec2 d = target - t.offset;
  const double c = std::cos(t.rotation), s = std::sin(t.rotation);
  const glm::dvec2 unrotated(c * d.x - s * d.y, s * d.x + c * d.y);  // Rᵀ · d
  return unrotated / t.scale;
}

// A quad's glTF with the image `grid.png` as base colour under the given transform (and
// texCoord override); TEXCOORD_0 and TEXCOORD_1 differ.
void writeQuad(const std::filesystem::path& dir, const std::string& extension) {
  std::vector<std::uint8_t> rgb;
  for (int i = 0; i < kTransformSize * kTransformSize; ++i)
    for (int c = 0; c < 3; ++c) rgb.push_back(static_cast<std::uint8_t>(20 + 37 * i + 71 * c));
  writePng8(dir / "grid.png", kTransformSize, kTransformSize, rgb, false);
  test::GltfBuilder b;
  b.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
  b.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2");              // TEXCOORD_0
  b.floats({0.5f, 1, 1, 1, 1, 0.5f, 0.5f, 0.5f}, "VEC2");  // TEXCOORD_1
  const int indices = b.u16({0, 1, 2, 0, 2, 3});
  test::writeText(dir / "quad.gltf",
                  b.json(R"("images":[{"uri":"grid.png"}],"textures":[{"source":0}],)"
                         R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0,)"
                         R"("extensions":{"KHR_texture_transform":)" +
                         extension +
                         R"(}}}}],"extensionsUsed":["KHR_texture_transform"],)"
                         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1,)"
                         R"("TEXCOORD_1":2},"indices":)" +
                         std::to_string(indices) +
                         R"(,"material":0}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])"));
}

SceneDescription loadQuad(const std::filesystem::path& dir) {
  return loadSceneFromText(
      "camera: {position: [0, 0, 5], look_at: [0, 0, 0]}\ninclude:\n  - gltf: quad.gltf\n",
      "test.yaml", dir);
}

TEST(GltfTextureTransform, OffsetRotationScaleSampleTheTexelTheExtensionNames) {
  // The extension's own example (the image's lower-left quadrant, turned clockwise 90°), and
  // one with every parameter off its default, non-uniform scale and a wrap past 1.
  for (const Transform& t : {Transform{{0.0, 1.0}, {0.5, 0.5}, std::numbers::pi / 2},
                             Transform{{0.3, -0.45}, {1.7, 0.6}, 0.4}}) {
    test::TempDir dir;
    writeQuad(dir.path(), t.json());
    const SceneDescription s = loadQuad(dir.path());
    ASSERT_EQ(s.shapes.size(), 1u);
    const TextureDescription& d =
        s.materials[static_cast<size_t>(s.shapes[0].material)].reflectance;
    ASSERT_EQ(d.kind, TextureDescription::Kind::kImage);
    TextureDescription plain = d;  // the same texels without the transform
    plain.uvScale = glm::vec2(1.0f);
    plain.uvOffset = glm::vec2(0.0f);
    plain.uvRotation = 0.0f;
    const std::unique_ptr<SpectrumTexture> transformed = makeSpectrumTexture(d);
    const std::unique_ptr<SpectrumTexture> image = makeSpectrumTexture(plain);
    const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.37f);
    for (int y = 0; y < kTransformSize; ++y)
      for (int x = 0; x < kTransformSize; ++x) {
        // Texel (x, y) (row 0 at the top) has its centre at glTF uv' ((x + ½)/w, (y + ½)/h).
        const glm::dvec2 target((x + 0.5) / kTransformSize, (y + 0.5) / kTransformSize);
        const glm::dvec2 gltfUv = surfaceUv(t, target);
        const glm::vec2 camsimUv(glm::dvec2(gltfUv.x, 1.0 - gltfUv.y));
        const glm::vec2 centre(static_cast<float>(target.x), static_cast<float>(1.0 - target.y));
        const SampledSpectrum got = transformed->evaluate(camsimUv, lambda);
        const SampledSpectrum want = image->evaluate(centre, lambda);
        for (int i = 0; i < kWavelengthSamples; ++i)
          EXPECT_NEAR(got[i], want[i], 1e-4)
              << "texel " << x << "," << y << " rotation " << t.rotation;
      }
  }
}

// The example's clockwise turn, spelt out: the surface's top-left corner (glTF uv (0, 0))
// shows the image's bottom-left corner, its top-right corner (1, 0) the image's left edge
// half-way up — in camsim's uv (v up), (0, 1) reads image uv (0, 0) and (1, 1) reads (0, ½).
TEST(GltfTextureTransform, ExampleFromTheExtensionTurnsTheQuadrantClockwise) {
  test::TempDir dir;
  writeQuad(dir.path(), Transform{{0.0, 1.0}, {0.5, 0.5}, std::numbers::pi / 2}.json());
  const SceneDescription s = loadQuad(dir.path());
  const TextureDescription& d = s.materials[0].reflectance;
  EXPECT_NEAR(d.uvRotation, std::numbers::pi / 2, 1e-6);
  const UvTransform map(d.uvScale, d.uvOffset, d.uvRotation);
  const glm::vec2 a = map(glm::vec2(0.0f, 1.0f)), b = map(glm::vec2(1.0f, 1.0f));
  EXPECT_NEAR(a.x, 0.0f, 1e-6f);
  EXPECT_NEAR(a.y, 0.0f, 1e-6f);
  EXPECT_NEAR(b.x, 0.0f, 1e-6f);
  EXPECT_NEAR(b.y, 0.5f, 1e-6f);
}

// texCoord inside the extension overrides the textureInfo's: the mesh carries TEXCOORD_1.
TEST(GltfTextureTransform, TexCoordOverrideSelectsTheUvSet) {
  test::TempDir dir;
  writeQuad(dir.path(), R"({"texCoord":1})");
  const SceneDescription s = loadQuad(dir.path());
  const MeshData& m = s.shapes[0].mesh;
  ASSERT_EQ(m.uvs.size(), 4u);
  const float set1[4][2] = {{0.5f, 1}, {1, 1}, {1, 0.5f}, {0.5f, 0.5f}};
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_FLOAT_EQ(m.uvs[i].x, set1[i][0]) << i;
    EXPECT_FLOAT_EQ(m.uvs[i].y, 1.0f - set1[i][1]) << i;  // v flipped to camsim's
  }
  // Without a transform the texture keeps its identity map.
  const TextureDescription& d = s.materials[0].reflectance;
  EXPECT_EQ(d.uvScale, glm::vec2(1.0f));
  EXPECT_EQ(d.uvOffset, glm::vec2(0.0f));
  EXPECT_EQ(d.uvRotation, 0.0f);
}

}  // namespace
}  // namespace camsim
