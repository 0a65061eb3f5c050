// Normal maps in the path tracer (integrator/render/path_tracer.cpp): the shading normal is
// bent before the shading frame is built, for any material.
//  - a flat map (EXR texels (0.5, 0.5, 1)) renders the same bytes as no map (image and AOVs),
//    on a rectangle, a sphere and a mesh;
//  - a constant map tilted by θ towards +u on a rectangle facing the camera: the normal AOV
//    is (0, sin θ, −cos θ) (∂p/∂u = edge_u = +y, front −z) and a diffuse surface lit along
//    its geometric normal by a parallel light is darker by exactly cos θ;
//  - a mesh's per-vertex tangents reach the frame through the Scene: w = −1 bends the
//    normal to the other side of the tangent than w = +1.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/io/exr_io.h"
#include "tests/support/scene_text.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

using test::num;

constexpr int kNormalMapRes = 16;

// A 1×1 EXR normal map encoding the tangent-space normal n.
void writeMap(const std::filesystem::path& file, const glm::dvec3& n) {
  Image im(1, 1, {"R", "G", "B"});
  for (int c = 0; c < 3; ++c) im.at(0, 0, c) = static_cast<float>(0.5 * (n[c] + 1.0));
  writeExr(file, im, {}, std::nullopt);
}

// The camera at the origin looking along +z at a rectangle z = 2 facing it (edge_u = +y,
// edge_v = +x, front −z), optionally a sphere and a mesh behind it, all of material m; a
// parallel light travelling along +z (so along the rectangle's −normal).
std::string sceneText(const std::string& material, bool extraShapes = false) {
  std::string text =
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], up: [0, 1, 0], "
      "resolution: [" +
      std::to_string(kNormalMapRes) + ", " + std::to_string(kNormalMapRes) +
      "], sensor_width_mm: 24, sensor_height_mm: 24, focal_length_mm: 20}\n"
      "render: {spp: 4, max_depth: 3, aovs: [normal]}\n"
      "materials: {m: " +
      material + "}\nshapes:\n";
  if (extraShapes)
    text +=
        "  - {type: rectangle, corner: [-5, -5, 2], edge_u: [0, 5, 0], edge_v: [10, 0, 0], "
        "material: m}\n"
        "  - {type: sphere, centre: [0, 0.6, 3], radius: 0.5, material: m}\n"
        "  - {type: mesh, vertices: [[-1, 0, 2.5], [1, 0, 2.5], [1, 1, 2.8], [-1, 1, 2.8]], faces: "
        "[[0, 1, 2, 3]], material: m}\n";
  else
    text +=
        "  - {type: rectangle, corner: [-5, -5, 2], edge_u: [0, 10, 0], edge_v: [10, 0, 0], "
        "material: m}\n";
  return text +
         "lights:\n  - {type: distant, direction: [0, 0, 1], angular_diameter: 0, "
         "illuminance: 1000}\n";
}

RenderResult renderDescription(const SceneDescription& d) {
  RenderOptions o;
  o.spp = d.render.spp;
  o.threads = 1;
  return render(Scene(d), SpectralResponse::cieXyz(), o);
}

RenderResult renderText(const std::string& text, const std::filesystem::path& dir) {
  return renderDescription(loadSceneFromText(text, "nm.yaml", dir));
}

float normalMapAt(const Image& im, int x, int y, const char* channel) {
  return im.at(x, y, im.channelIndex(channel));
}

TEST(PathTracerNormalMap, FlatMapChangesNothingBitForBit) {
  test::TempDir dir;
  writeMap(dir.path() / "flat.exr", {0.0, 0.0, 1.0});
  for (const std::string base :
       {"type: diffuse, reflectance: 0.5", "type: plastic, reflectance: 0.4, roughness: 0.3",
        "type: metallic_roughness, base_color: 0.8, metallic: 0.5, roughness: 0.4"}) {
    const RenderResult plain = renderText(sceneText("{" + base + "}", true), dir.path());
    const RenderResult mapped =
        renderText(sceneText("{" + base + ", normal_map: {texture: flat.exr}}", true), dir.path());
    ASSERT_EQ(plain.image.pixels.size(), mapped.image.pixels.size());
    EXPECT_EQ(plain.image.pixels, mapped.image.pixels) << base;
    EXPECT_EQ(plain.aovs.pixels, mapped.aovs.pixels) << base;
    double sum = 0.0;
    for (float v : plain.image.pixels) sum += static_cast<double>(v);
    EXPECT_GT(sum, 0.0) << base;  // something was lit
  }
}

TEST(PathTracerNormalMap, TiltedMapTiltsTheNormalAndTheShading) {
  test::TempDir dir;
  for (double degrees : {20.0, 45.0}) {
    const double th = degrees * M_PI / 180.0;
    writeMap(dir.path() / "tilt.exr", {std::sin(th), 0.0, std::cos(th)});
    const std::string diffuse = "type: diffuse, reflectance: 0.5";
    const RenderResult plain = renderText(sceneText("{" + diffuse + "}"), dir.path());
    const RenderResult tilted =
        renderText(sceneText("{" + diffuse + ", normal_map: {texture: tilt.exr}}"), dir.path());
    const int y = plain.image.channelIndex("Y");
    for (int py = 0; py < kNormalMapRes; ++py)
      for (int px = 0; px < kNormalMapRes; ++px) {
        // N' = sin θ ∂p/∂u + cos θ N = (0, sin θ, −cos θ); the texel's rounding to half
        // precision in the EXR is ≈ 5e-4.
        EXPECT_NEAR(normalMapAt(tilted.aovs, px, py, "N.X"), 0.0, 1e-6) << degrees;
        EXPECT_NEAR(normalMapAt(tilted.aovs, px, py, "N.Y"), std::sin(th), 1e-3) << degrees;
        EXPECT_NEAR(normalMapAt(tilted.aovs, px, py, "N.Z"), -std::cos(th), 1e-3) << degrees;
        EXPECT_EQ(normalMapAt(tilted.aovs, px, py, "Ng.Z"), -1.0f);  // the geometry is unchanged
        // Lambert with the light along −N: E cos θ' with θ' = θ, same samples otherwise.
        const double ratio = static_cast<double>(tilted.image.at(px, py, y)) /
                             static_cast<double>(plain.image.at(px, py, y));
        const double cosMapped = -static_cast<double>(normalMapAt(tilted.aovs, px, py, "N.Z"));
        EXPECT_NEAR(ratio, cosMapped, 1e-5) << degrees << " at " << px << "," << py;
        EXPECT_NEAR(ratio, std::cos(th), 1e-3) << degrees;
      }
  }
}

TEST(PathTracerNormalMap, MeshTangentsReachTheFrame) {
  test::TempDir dir;
  const double th = 30.0 * M_PI / 180.0;
  writeMap(dir.path() / "up.exr", {0.0, std::sin(th), std::cos(th)});  // towards the bitangent
  // A quad z = 2 facing the camera (clockwise seen from it: front −z), tangent +y.
  const std::string text =
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], up: [0, 1, 0], resolution: [4, 4], "
      "sensor_width_mm: 24, sensor_height_mm: 24, focal_length_mm: 20}\n"
      "render: {spp: 2, max_depth: 1, aovs: [normal]}\n"
      "materials: {m: {type: diffuse, reflectance: 0.5, normal_map: {texture: up.exr}}}\n"
      "shapes:\n  - {type: mesh, vertices: [[-5, -5, 2], [-5, 5, 2], [5, 5, 2], [5, -5, 2]], "
      "faces: [[0, 1, 2, 3]], material: m}\n"
      "lights:\n  - {type: distant, direction: [0, 0, 1], illuminance: 1000}\n";
  SceneDescription d = loadSceneFromText(text, "nm.yaml", dir.path());
  ASSERT_EQ(d.shapes.size(), 1u);
  for (float w : {1.0f, -1.0f}) {
    d.shapes[0].mesh.tangents.assign(d.shapes[0].mesh.positions.size(),
                                     glm::vec4(0.0f, 1.0f, 0.0f, w));
    const RenderResult r = renderDescription(d);
    // ns = −z, t = +y: bitangent w (ns × t) = w (+x); N' = sin θ · w x̂ − cos θ ẑ.
    for (int py = 0; py < 4; ++py)
      for (int px = 0; px < 4; ++px) {
        EXPECT_NEAR(normalMapAt(r.aovs, px, py, "N.X"), static_cast<double>(w) * std::sin(th), 1e-3)
            << w;
        EXPECT_NEAR(normalMapAt(r.aovs, px, py, "N.Y"), 0.0, 1e-6) << w;
        EXPECT_NEAR(normalMapAt(r.aovs, px, py, "N.Z"), -std::cos(th), 1e-3) << w;
      }
  }
}

}  // namespace
}  // namespace camsim
