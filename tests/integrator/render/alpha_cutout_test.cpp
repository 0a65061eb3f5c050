// Alpha cut-outs in renders (materials' `alpha_cutout`, integrator/textures/alpha_cutout.h):
// a checker-cut black quad between the camera and an emitter lets exactly half its
// radiance through, and a checker-cut occluder between a floor and the sun (out of the
// camera's view) halves the floor's direct light: camera rays and shadow rays both see
// through the holes. The squares are sized so that each pixel's footprint holds exactly
// two checker periods in each direction (the footprint of the 8 × 8 cameraAboveOrigin
// image: 2.5 mm on the floor, 1.25 mm half-way up), so every pixel's expected value is
// exactly half; tolerances cover the sampling noise of 64 Sobol' samples.
#include <gtest/gtest.h>

#include "tests/integrator/render_test_support.h"

namespace camsim {
namespace {

using test::cameraAboveOrigin;
using test::MaxError;
using test::renderLuminance;

constexpr int kCutoutSize = 8;

// A black quad 0.1 m wide at height 0.5 m, cut by `cutout`, over an emitting floor of
// 100 cd/m². quad: the shape entries of the quad.
std::string coverageScene(const std::string& cutout, const std::string& quad) {
  return cameraAboveOrigin(kCutoutSize) +
         "render: {max_depth: 1}\n"
         "materials:\n"
         "  black: {type: diffuse, reflectance: 0, alpha_cutout: " +
         cutout +
         "}\n"
         "shapes:\n"
         "  - {type: rectangle, corner: [-10, 0, -10], edge_u: [0, 0, 20], edge_v: [20, 0, 0],\n"
         "     emission: {luminance: 100}}\n" +
         quad;
}

// The quad: 0.1 m per unit of uv, so 160 checks per unit make 0.625 mm squares (two
// periods in a pixel's 1.25 mm).
const std::string kQuad =
    "  - {type: rectangle, corner: [-0.05, 0.5, -0.05], edge_u: [0.1, 0, 0],\n"
    "     edge_v: [0, 0, 0.1], material: black}\n";
// As an instanced mesh (two instances, one in view): one triangle without texture
// coordinates, which then gets uv = (b1 + b2, b2) (integrator/geometry/triangle_mesh.h),
// here u = z/0.2 m and v = x/0.2 m: 320 checks per unit make the same 0.625 mm squares. The
// camera's view (|x|, |z| ≤ 5 mm at height 0.5 m) lies inside it.
const std::string kInstancedTriangle =
    "  - type: mesh\n"
    "    material: black\n"
    "    vertices: [[0, 0, 0], [0, 0, 0.2], [0.2, 0, 0.2]]\n"
    "    faces: [[0, 1, 2]]\n"
    "    instances: [{translate: [-0.05, 0.5, -0.1]}, {translate: [3, 0.5, 0]}]\n";

void expectHalfOfTheEmitter(const std::string& yaml) {
  SCOPED_TRACE(yaml);
  MaxError maxError;
  const test::LuminanceImage img = renderLuminance(yaml, 64);
  double mean = 0.0;
  for (int y = 0; y < kCutoutSize; ++y)
    for (int x = 0; x < kCutoutSize; ++x) {
      EXPECT_LT(maxError(img.at(x, y), 50.0), 0.03) << x << "," << y << ": " << img.at(x, y);
      mean += img.at(x, y) / (kCutoutSize * kCutoutSize);
    }
  EXPECT_NEAR(mean, 50.0, 0.5);
}

TEST(AlphaCutoutRender, CameraRaysSeeHalfTheEmitterThroughACheckerCut) {
  expectHalfOfTheEmitter(
      coverageScene("{alpha: {checkerboard: {a: 1, b: 0, checks: 160}}}", kQuad));
}

// alpha = factor · texel: 0.8 · 1 stays, 0.8 · 0.6 = 0.48 < 0.5 is cut.
TEST(AlphaCutoutRender, TheFactorScalesTheTexel) {
  expectHalfOfTheEmitter(coverageScene(
      "{alpha: {checkerboard: {a: 1, b: 0.6, checks: 160}}, factor: 0.8, cutoff: 0.5}", kQuad));
}

TEST(AlphaCutoutRender, InstancedMeshesAreCutToo) {
  expectHalfOfTheEmitter(
      coverageScene("{alpha: {checkerboard: {a: 1, b: 0, checks: 320}}}", kInstancedTriangle));
}

// Without a texture, alpha = factor everywhere: below the cutoff the whole quad is gone, and
// the image is the one without it, bit for bit; at the cutoff it stays (all black).
TEST(AlphaCutoutRender, AConstantAlphaBelowTheCutoffRemovesTheSurface) {
  // 64 spp: the emitter's spectral noise (two independent 32-point halves) well under 1 %.
  const test::LuminanceImage cut = renderLuminance(coverageScene("{factor: 0.2}", kQuad), 64);
  const test::LuminanceImage none = renderLuminance(coverageScene("{}", ""), 64);
  const test::LuminanceImage kept =
      renderLuminance(coverageScene("{factor: 0.5, cutoff: 0.5}", kQuad), 64);
  for (int y = 0; y < kCutoutSize; ++y)
    for (int x = 0; x < kCutoutSize; ++x) {
      EXPECT_EQ(cut.at(x, y), none.at(x, y)) << x << "," << y;
      EXPECT_NEAR(none.at(x, y), 100.0, 1.0) << x << "," << y;
      EXPECT_EQ(kept.at(x, y), 0.0) << x << "," << y;
    }
}

// A floor of reflectance 0.5 under a parallel sun at 45° (from +x, +y), with a black
// checker-cut occluder at height 0.5 m on the light's way to the floor the camera sees (the
// camera's own rays pass 0.3 m beside it). The shadow is the occluder's pattern moved along
// the light (horizontal plane to horizontal plane): 1.25 mm squares, two periods in a
// pixel's 2.5 mm, half the floor lit. `occluder`: the occluder's entries, or none; `checks`:
// per unit of its uv.
double floorUnderSun(const std::string& occluder, int checks = 320) {
  const std::string yaml = cameraAboveOrigin(kCutoutSize) +
                           "materials:\n"
                           "  floor: {type: diffuse, reflectance: 0.5}\n"
                           "  black: {type: diffuse, reflectance: 0,\n"
                           "          alpha_cutout: {alpha: {checkerboard: {a: 1, b: 0, checks: " +
                           std::to_string(checks) +
                           "}}}}\n"
                           "shapes:\n"
                           "  - {type: rectangle, corner: [-10, 0, -10], edge_u: [0, 0, 20],\n"
                           "     edge_v: [20, 0, 0], material: floor}\n" +
                           occluder +
                           "lights:\n"
                           "  - {type: distant, direction: [-1, -1, 0], angular_diameter: 0,\n"
                           "     illuminance: 10000}\n";
  const test::LuminanceImage img = renderLuminance(yaml, 64);
  double mean = 0.0;
  for (int y = 0; y < kCutoutSize; ++y)
    for (int x = 0; x < kCutoutSize; ++x) mean += img.at(x, y) / (kCutoutSize * kCutoutSize);
  return mean;
}

TEST(AlphaCutoutRender, ShadowRaysPassThroughTheHoles) {
  const double lit = floorUnderSun("");
  // E cos 45° · ρ/π (cd/m²)
  EXPECT_NEAR(lit, 10000.0 * std::sqrt(0.5) * 0.5 / M_PI, 1.0);
  // A 0.4 m quad (320 checks: 1.25 mm squares).
  const double plain = floorUnderSun(
      "  - {type: rectangle, corner: [0.3, 0.5, -0.2], edge_u: [0.4, 0, 0], edge_v: [0, 0, 0.4],\n"
      "     material: black}\n");
  EXPECT_NEAR(plain / lit, 0.5, 0.01);
  // One instanced triangle with 0.4 m legs and the default uv (u = z/0.4 m, v = x/0.4 m)
  // whose interior holds the shadow's way (x ≈ 0.5 m, |z| ≤ 1 cm at height 0.5 m).
  const double instanced = floorUnderSun(
      "  - type: mesh\n"
      "    material: black\n"
      "    vertices: [[0, 0, 0], [0, 0, 0.4], [0.4, 0, 0.4]]\n"
      "    faces: [[0, 1, 2]]\n"
      "    instances: [{translate: [0.4, 0.5, -0.2]}, {translate: [0.3, 5, 3]}]\n");
  EXPECT_NEAR(instanced / lit, 0.5, 0.01);
}

}  // namespace
}  // namespace camsim
