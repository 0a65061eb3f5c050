// Path guiding (integrator/render/path_guide.h) in the renderer: the guided estimator is
// unbiased (an analytic furnace; a room lit indirectly, guided and unguided means agree),
// deterministic for any thread count, and the scene setting is parsed and range-checked.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>

#include "integrator/render/path_guide.h"
#include "sensor/base/input_error.h"
#include "tests/integrator/render_test_support.h"

namespace camsim::path_guide_test {
namespace {

using test::flatY;
using test::LuminanceImage;
using test::meanOf;
using test::renderLuminance;

// A 2 m room of reflectance 0.6 lit by a 5 cm sphere under a 60 cm square baffle: the
// floor the camera sees is lit mostly by the ceiling's pool (the indirect light guiding
// learns). 32 × 32 px.
std::string room(bool guiding) {
  return std::string("render: {max_depth: 8, guiding: ") + (guiding ? "true" : "false") +
         "}\n"
         "camera: {position: [1, 1.2, 0.1], look_at: [1, 0.2, 1.6], up: [0, 1, 0],\n"
         "         sensor_width_mm: 36, sensor_height_mm: 36, focal_length_mm: 24,\n"
         "         resolution: [32, 32]}\n"
         "materials: {wall: {type: diffuse, reflectance: 0.6}}\n"
         "shapes:\n"
         "  - {type: sphere, centre: [1, 1.7, 1], radius: 0.05,\n"
         "     emission: {scale: 100, spectrum: 1}}\n"
         "  - {type: rectangle, material: wall, corner: [0.7, 1.6, 0.7], edge_u: [0.6, 0, 0],"
         " edge_v: [0, 0, 0.6]}\n"
         "  - {type: rectangle, material: wall, corner: [0, 0, 0], edge_u: [0, 0, 2], edge_v: [2, "
         "0, 0]}\n"
         "  - {type: rectangle, material: wall, corner: [0, 2, 0], edge_u: [2, 0, 0], edge_v: [0, "
         "0, 2]}\n"
         "  - {type: rectangle, material: wall, corner: [0, 0, 0], edge_u: [2, 0, 0], edge_v: [0, "
         "2, 0]}\n"
         "  - {type: rectangle, material: wall, corner: [0, 0, 2], edge_u: [2, 0, 0], edge_v: [0, "
         "2, 0]}\n"
         "  - {type: rectangle, material: wall, corner: [0, 0, 0], edge_u: [0, 2, 0], edge_v: [0, "
         "0, 2]}\n"
         "  - {type: rectangle, material: wall, corner: [2, 0, 0], edge_u: [0, 2, 0], edge_v: [0, "
         "0, 2]}\n";
}

// A closed sphere emitting Lₑ = 0.01 with reflectance 0.5: L = Lₑ/(1 − ρ) = 0.02 everywhere.
// Guided, 1024 spp (the guide trains on 255 more): each of 16 pixels within 2 % (per-pixel
// σ ≈ 0.6 %: the learnt density is noisier than the BSDF's here), the mean within 0.5 %.
TEST(PathGuide, FurnaceIsUnbiased) {
  const std::string scene =
      "render: {max_depth: 60, rr_depth: 10000, guiding: true}\n"
      "camera: {position: [0, 0, 0], look_at: [1, 0.2, 0.1], up: [0, 0, 1], sensor_width_mm: "
      "36,\n"
      "         sensor_height_mm: 36, focal_length_mm: 20, resolution: [4, 4]}\n"
      "materials: {wall: {type: diffuse, reflectance: 0.5}}\n"
      "shapes:\n"
      "  - {type: sphere, centre: [0, 0, 0], radius: 2, material: wall,\n"
      "     emission: {scale: 0.01, spectrum: 1, two_sided: true}}\n";
  const LuminanceImage img = renderLuminance(scene, 1024);
  ASSERT_TRUE(img.stats.guide.has_value());
  EXPECT_GT(img.stats.guide->records, 0u);
  EXPECT_EQ(img.stats.guide->trainSpp, 255);  // 1 + 2 + … + 128 ≤ 1024 / 4
  const double expected = 0.02 * flatY();
  std::printf("[measured] guided furnace: mean / reference = %.4f\n", meanOf(img) / expected);
  EXPECT_NEAR(meanOf(img) / expected, 1.0, 0.005);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_NEAR(img.at(x, y) / expected, 1.0, 0.02);
}

// The room, guided and unguided at 1024 spp, fixed seeds: the image means agree within 2 %
// (the mean's own noise, from the half-sample estimate, measured < 0.5 % each).
TEST(PathGuide, GuidedAndUnguidedMeansAgree) {
  const LuminanceImage plain = renderLuminance(room(false), 1024, 3);
  const LuminanceImage guided = renderLuminance(room(true), 1024, 3);
  EXPECT_FALSE(plain.stats.guide.has_value());
  ASSERT_TRUE(guided.stats.guide.has_value());
  EXPECT_GT(guided.stats.guide->leaves, 1u);
  const double ratio = meanOf(guided) / meanOf(plain);
  std::printf("[measured] room: guided / unguided mean = %.4f; guide %zu leaves, %zu bytes\n",
              ratio, guided.stats.guide->leaves, guided.stats.guide->bytes);
  EXPECT_NEAR(ratio, 1.0, 0.02);
}

// Same scene and seed → same bytes with 1 and 2 threads (the guide's records are inserted
// in tile order).
TEST(PathGuide, DeterministicForAnyThreadCount) {
  const Scene scene(loadSceneFromText(room(true), "test.yaml", "."));
  const SpectralResponse response = SpectralResponse::cieXyz();
  RenderOptions options;
  options.spp = 16;
  options.seed = 5;
  options.threads = 1;
  const RenderResult one = render(scene, response, options);
  options.threads = 2;
  const RenderResult two = render(scene, response, options);
  ASSERT_TRUE(one.stats.guide && two.stats.guide);
  EXPECT_EQ(one.stats.guide->records, two.stats.guide->records);
  EXPECT_EQ(one.stats.guide->bytes, two.stats.guide->bytes);
  ASSERT_EQ(one.image.pixels.size(), two.image.pixels.size());
  EXPECT_EQ(0, std::memcmp(one.image.pixels.data(), two.image.pixels.data(),
                           one.image.pixels.size() * sizeof(float)));
  // The option overrides the scene: off, no guide.
  options.guiding = false;
  EXPECT_FALSE(render(scene, response, options).stats.guide.has_value());
}

// Found by probing: Ctrl-C waited for the whole training (a 16 × 16 render at 131072 spp
// exited 14 s after SIGINT; at 10⁶ spp minutes), as training took no cancel flag. Now a
// cancel set before the render stops training before its first chunk: no record, and
// the render cancelled. (Its records of one iteration are also held in chunks of 32 spp:
// that 16384-spp render peaked at 99.7 MB resident, now 19 MB, as unguided.)
TEST(PathGuide, TrainingStopsOnCancel) {
  const Scene scene(loadSceneFromText(room(true), "test.yaml", "."));
  const std::atomic<bool> cancel{true};
  const PathGuide guide = PathGuide::train(scene, 1 << 20, 1, 1, &cancel);
  EXPECT_EQ(guide.stats().records, 0u);
  EXPECT_EQ(guide.stats().iterations, 0);
  RenderOptions options;
  options.spp = 1 << 20;
  options.threads = 1;
  options.cancel = &cancel;
  const RenderResult r = render(scene, SpectralResponse::cieXyz(), options);
  EXPECT_TRUE(r.stats.cancelled);
  ASSERT_TRUE(r.stats.guide.has_value());
  EXPECT_EQ(r.stats.guide->records, 0u);
}

// The room's trained guide: at the floor, in front of the baffle, the source lobe looks up
// at the ceiling the sphere lights directly (its centroid in the room's top 0.5 m, the
// brightest light the floor gets); the lobe is sharp (κ ≥ 4) and it is that leaf's lobe.
TEST(PathGuide, SourceLobeLooksAtTheDirectlyLitCeiling) {
  const Scene scene(loadSceneFromText(room(true), "test.yaml", "."));
  const PathGuide guide = PathGuide::train(scene, 256, 1, 2);
  const glm::vec3 origin(scene.renderOrigin());
  const glm::vec3 floor = glm::vec3(1.0f, 0.01f, 0.3f) - origin;  // world → render space
  const GuideQuery q = guide.at(floor);
  ASSERT_NE(q.density, nullptr);
  const SourceLobe& lobe = guide.tree().leaf(guide.tree().leafAt(floor)).lobe;
  const glm::vec3 c = lobe.centre + origin;
  std::printf(
      "[measured] floor's source lobe: centre (%.2f, %.2f, %.2f) m, sigma %.2f m, "
      "kappa %.1f, mu.y %.2f\n",
      static_cast<double>(c.x), static_cast<double>(c.y), static_cast<double>(c.z),
      std::sqrt(static_cast<double>(lobe.spread2)), static_cast<double>(q.lobe.kappa),
      static_cast<double>(q.lobe.mu.y));
  EXPECT_GT(c.y, 1.5f);
  EXPECT_EQ(q.lobe.kappa, lobe.at(floor).kappa);
  EXPECT_GE(q.lobe.kappa, SourceLobe::kMinKappa);
  EXPECT_GT(q.lobe.mu.y, 0.7f);
}

// Direct light with the source lobe in the mixture: a 40 cm square emitting Lₑ = 1 (flat
// spectrum, both sides) 1.2 m above a floor of reflectance 0.5, max_depth 1, so each path
// is next-event estimation plus one guided bounce that may hit the square, weighed by MIS
// against the mixture pdf. The floor under the square's centre has L = ρ·Lₑ·F, F the view
// factor (four corner rectangles: F = 4·(1/2π)·2·X/√(1+X²)·atan(X/√(1+X²)), X = 0.2/1.2).
// The floor's lobe looks at the square (κ > 100: the uniform square alone would give
// 3·1.2²/(2·0.4²/12) ≈ 160; weighted by L_d²/p the cloud is tighter, κ ≈ 1300), so a lobe
// pdf that were not the density its samples follow would bias the image (a pdf 1.3× too
// large read 0.983). 4 × 4 px (2 cm of floor:
// L varies by < 10⁻³ over it), 4096 spp: the mean within 0.5 % (its noise ≈ 0.1 %).
TEST(PathGuide, DirectLightThroughTheSourceLobeIsUnbiased) {
  const std::string yaml = std::string("render: {max_depth: 1, guiding: true}\n") +
                           test::cameraAboveOrigin(4) + test::floorOf(0.5) +
                           "  - {type: rectangle, corner: [-0.2, 1.2, -0.2], edge_u: [0.4, 0, 0],"
                           " edge_v: [0, 0, 0.4],\n"
                           "     emission: {scale: 1, spectrum: 1, two_sided: true}}\n";
  const Scene scene(loadSceneFromText(yaml, "test.yaml", "."));
  // The render's own guide: the same spp and seed (training does not depend on threads).
  const PathGuide guide = PathGuide::train(scene, 4096, 2, 2);
  const GuideQuery q = guide.at(-glm::vec3(scene.renderOrigin()));  // the floor's origin
  ASSERT_NE(q.density, nullptr);
  EXPECT_GT(q.lobe.kappa, 100.0f);
  EXPECT_GT(q.lobe.mu.y, 0.99f);
  const LuminanceImage img = renderLuminance(yaml, 4096, /*seed=*/2);
  const double x = 0.2 / 1.2, r = std::sqrt(1.0 + x * x);
  const double F = 4.0 / (2.0 * std::numbers::pi) * 2.0 * (x / r) * std::atan(x / r);
  const double expected = 0.5 * F * flatY();
  std::printf("[measured] floor under the square: mean / (rho Le F) = %.5f (lobe kappa %.0f)\n",
              meanOf(img) / expected, static_cast<double>(q.lobe.kappa));
  EXPECT_NEAR(meanOf(img) / expected, 1.0, 0.005);
}

TEST(PathGuide, SettingIsParsedAndChecked) {
  EXPECT_TRUE(loadSceneFromText(room(true), "test.yaml", ".").render.guiding);
  EXPECT_FALSE(loadSceneFromText(room(false), "test.yaml", ".").render.guiding);
  std::string one = room(true);  // the override's form, 0 or 1, also reads
  one.replace(one.find("guiding: true"), 13, "guiding: 1");
  EXPECT_TRUE(loadSceneFromText(one, "test.yaml", ".").render.guiding);
  std::string bad = room(true);
  bad.replace(bad.find("guiding: true"), 13, "guiding: 3");
  try {
    loadSceneFromText(bad, "test.yaml", ".");
    FAIL() << "guiding: 3 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("test.yaml"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace camsim::path_guide_test
