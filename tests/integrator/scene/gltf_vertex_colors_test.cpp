// glTF COLOR_0 (integrator/scene/gltf_accessors.cpp, integrator/textures/vertex_colors.h):
// vertex colours multiply the base colour. Read as stored (normalized unsigned bytes,
// floats clamped to [0, 1]); at a hit the three vertices' uplifted reflectances blended by
// the hit's barycentrics; in a render the albedo AOV shows the colour.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "integrator/textures/reflectance_uplift.h"
#include "tests/integrator/scene/gltf_test_support.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

// A unit quad in z = 0 (triangles (0, 1, 2), (0, 2, 3)) with COLOR_0 as normalized
// unsigned bytes (VEC4), and a triangle beside it with float colours (VEC3), one above 1.
std::string quadAndTriangle(const std::vector<std::uint8_t>& quadColours) {
  test::GltfBuilder b;
  b.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
  b.u8(quadColours, "VEC4", true);
  b.u16({0, 1, 2, 0, 2, 3});
  b.floats({2, 0, 0, 3, 0, 0, 2, 1, 0}, "VEC3");
  b.floats({0.25f, 0.5f, 1.5f, 1, 1, 1, 0, 0, 0}, "VEC3");
  return b.json(
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"COLOR_0":1},"indices":2}]},)"
      R"({"primitives":[{"attributes":{"POSITION":3,"COLOR_0":4}}]}],)"
      R"("nodes":[{"mesh":0},{"mesh":1}],"scenes":[{"nodes":[0,1]}])");
}

const std::vector<std::uint8_t> kColours = {255, 0, 0,   255, 0,   255, 0,  255,
                                            0,   0, 255, 255, 204, 51,  26, 255};

SceneDescription loadColoured(const std::filesystem::path& dir, const std::string& camera) {
  return loadSceneFromText(
      "camera: {" + camera + "}\ninclude:\n  - gltf: colours.gltf\n" +
          "lights:\n  - {type: point, position: [0.5, 0.5, 3], intensity: 1}\n",
      "test.yaml", dir);
}

TEST(GltfVertexColors, ReadAsStoredAndClamped) {
  test::TempDir dir;
  test::writeText(dir.path() / "colours.gltf", quadAndTriangle(kColours));
  const SceneDescription s = loadColoured(dir.path(), "position: [0, 0, 5], look_at: [0, 0, 0]");
  ASSERT_EQ(s.shapes.size(), 2u);
  const std::vector<glm::vec3>& quad = s.shapes[0].mesh.colors;
  ASSERT_EQ(quad.size(), 4u);
  EXPECT_EQ(quad[0], glm::vec3(1, 0, 0));
  EXPECT_EQ(quad[2], glm::vec3(0, 0, 1));
  EXPECT_NEAR(quad[3].x, 204.0f / 255.0f, 1e-7f);
  EXPECT_NEAR(quad[3].z, 26.0f / 255.0f, 1e-7f);
  const std::vector<glm::vec3>& tri = s.shapes[1].mesh.colors;
  ASSERT_EQ(tri.size(), 3u);
  EXPECT_EQ(tri[0], glm::vec3(0.25f, 0.5f, 1.0f));  // 1.5 clamped: a reflectance
  // Opaque colours: no note about their alpha; the old "ignored" note is gone.
  for (const std::string& n : s.notes) EXPECT_EQ(n.find("COLOR_0"), std::string::npos) << n;
}

// At (0.3, 0.2) on the quad, triangle (0, 1, 2) with barycentrics (0.7, 0.1, 0.2): the
// base colour (white factor: reflectance 1) times 0.7 ρ_red + 0.1 ρ_green + 0.2 ρ_blue.
TEST(GltfVertexColors, HitBlendsTheVerticesUpliftedColours) {
  test::TempDir dir;
  test::writeText(dir.path() / "colours.gltf", quadAndTriangle(kColours));
  const SceneDescription d = loadColoured(dir.path(), "position: [0, 0, 5], look_at: [0, 0, 0]");
  const Scene scene(d);
  Ray ray{glm::vec3(0.3f, 0.2f, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f),
          std::numeric_limits<float>::infinity(), 0.0f};  // render space: the camera at 0
  Hit hit;
  ASSERT_TRUE(scene.geometry().intersect(ray, hit));
  EXPECT_EQ(hit.shape, 0);
  const SurfaceInteraction si = scene.shape(hit.shape).interaction(hit, ray);
  const BsdfContext ctx = scene.bsdfContext(hit, si);
  ASSERT_NE(ctx.vertexColors, nullptr);
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.61f);
  const SampledSpectrum albedo = scene.material(hit.shape).aov(lambda, ctx).albedo;
  const ReflectanceUplift& uplift = ReflectanceUplift::linearRec709();
  const SigmoidCoefficients red = SigmoidCoefficients::from(uplift.fit({1, 0, 0}));
  const SigmoidCoefficients green = SigmoidCoefficients::from(uplift.fit({0, 1, 0}));
  const SigmoidCoefficients blue = SigmoidCoefficients::from(uplift.fit({0, 0, 1}));
  for (int i = 0; i < kWavelengthSamples; ++i) {
    const float expected = 0.7f * red(lambda[i]) + 0.1f * green(lambda[i]) + 0.2f * blue(lambda[i]);
    EXPECT_NEAR(albedo[i], expected, 1e-5f) << lambda[i] << " nm";
  }
}

// A quad of one colour filling the view: the albedo AOV (the path tracer's first hit) reads
// that colour, within the uplift's round trip and the AOV's spectral estimate (0.01).
TEST(GltfVertexColors, AlbedoAovShowsTheColour) {
  test::TempDir dir;
  std::vector<std::uint8_t> one;
  for (int v = 0; v < 4; ++v) one.insert(one.end(), {204, 77, 26, 255});
  test::writeText(dir.path() / "colours.gltf", quadAndTriangle(one));
  SceneDescription d =
      loadColoured(dir.path(),
                   "position: [0.5, 0.5, 3], look_at: [0.5, 0.5, 0], sensor_width_mm: 24, "
                   "sensor_height_mm: 24, focal_length_mm: 120, resolution: [8, 8]");
  d.render.spp = 256;
  d.render.maxDepth = 1;
  d.render.aovs = {Aov::kAlbedo};
  RenderOptions o;
  o.spp = d.render.spp;
  o.threads = 2;
  const RenderResult r = render(Scene(d), SpectralResponse::cieXyz(), o);
  const char* names[3] = {"albedo.R", "albedo.G", "albedo.B"};
  const double expected[3] = {204.0 / 255.0, 77.0 / 255.0, 26.0 / 255.0};
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(r.aovs.at(x, y, r.aovs.channelIndex(names[c])), expected[c], 0.01)
            << x << "," << y << " " << names[c];
}

// A mesh without colours costs nothing: the scene has no colour table at all.
TEST(GltfVertexColors, MeshWithoutColoursHasNone) {
  test::TempDir dir;
  test::GltfBuilder b;
  b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  test::writeText(dir.path() / "colours.gltf",
                  b.json(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
                         R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])"));
  const Scene scene(loadColoured(dir.path(), "position: [0, 0, 5], look_at: [0, 0, 0]"));
  Ray ray{glm::vec3(0.2f, 0.2f, 0.0f), glm::vec3(0.0f, 0.0f, -1.0f),
          std::numeric_limits<float>::infinity(), 0.0f};
  Hit hit;
  ASSERT_TRUE(scene.geometry().intersect(ray, hit));
  EXPECT_EQ(scene.bsdfContext(hit, scene.shape(hit.shape).interaction(hit, ray)).vertexColors,
            nullptr);
}

}  // namespace
}  // namespace camsim
