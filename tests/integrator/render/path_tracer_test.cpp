// Path tracer against closed forms:
//  - furnace: inside a closed diffuse sphere of reflectance ρ emitting Lₑ everywhere, the
//    radiance everywhere is Lₑ/(1−ρ) (geometric series of bounces);
//  - irradiance: a Lambertian floor under a uniform polygonal emitter has radiance
//    ρ/π · E with E from Lambert's polygon formula.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include <glm/geometric.hpp>

#include "tests/integrator/render_test_support.h"

namespace camsim {
namespace {

using test::flatY;

// Each pixel's mean radiance-weighted Y (cd/m²), comparable with radiance closed forms.
Image renderY(const std::string& yaml, int spp, std::uint64_t seed = 1) {
  const test::LuminanceImage r = test::renderLuminance(yaml, spp, seed);
  EXPECT_EQ(r.stats.rejectedSamples, 0u);
  return r.y;
}

std::string furnaceScene(double rho, int resolution, int maxDepth, int rrDepth) {
  return "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [" +
         std::to_string(resolution) + ", " + std::to_string(resolution) +
         "], focal_length_mm: 50}\n"
         "render: {max_depth: " +
         std::to_string(maxDepth) + ", rr_depth: " + std::to_string(rrDepth) +
         "}\n"
         "materials: {wall: {type: diffuse, reflectance: " +
         std::to_string(rho) +
         "}}\n"
         "shapes:\n"
         "  - {type: sphere, centre: [0.1, -0.2, 0.3], radius: 1.5, material: wall,\n"
         "     emission: {scale: 0.01, spectrum: 1, two_sided: true}}\n";
}

// Without Russian roulette every path runs to max_depth, so the only noise is from the
// wavelengths and the MIS split; the truncated tail ρ^(d+1) is < 1e-7 at the depths used.
// Tolerance: the 1 % on every pixel of an 8×8 image; measured per-pixel σ at
// 256 spp is 0.18 % (5.5σ margin).
TEST(Furnace, EveryPixelReadsLeOverOneMinusRho) {
  for (double rho : {0.5, 0.9}) {
    const int maxDepth = rho < 0.6 ? 30 : 160;
    const Image img = renderY(furnaceScene(rho, 8, maxDepth, 10000), 256);
    const double expected = 0.01 * flatY() / (1.0 - rho);
    const int yc = img.channelIndex("Y");
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        EXPECT_NEAR(static_cast<double>(img.at(x, y, yc)) / expected, 1.0, 0.01)
            << "rho " << rho << " pixel " << x << "," << y;
  }
}

// With Russian roulette the estimator is still unbiased but noisier (the number of
// bounces is random; measured per-pixel σ ≈ 3 % at 1024 spp for ρ = 0.9): a 2×2 image at
// 131072 spp gives σ ≈ 0.27 %, so the 1 % tolerance is ≈ 4σ.
TEST(Furnace, RussianRouletteStaysUnbiased) {
  for (double rho : {0.5, 0.9}) {
    const Image img = renderY(furnaceScene(rho, 2, 1000, 3), 131072, 7);
    const double expected = 0.01 * flatY() / (1.0 - rho);
    const int yc = img.channelIndex("Y");
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        EXPECT_NEAR(static_cast<double>(img.at(x, y, yc)) / expected, 1.0, 0.01)
            << "rho " << rho << " pixel " << x << "," << y;
  }
}

// Roulette's survival rule and the bounce-ray count, against their closed form. In the
// furnace every bounce multiplies β by ρ exactly (cosine sampling of a constant
// reflectance) and every traced bounce ray hits the sphere, so with roulette from the first
// bounce (rr_depth 1) the survival after bounce k is s_k = √(ρ·β_k) and β_{k+1} = √(ρ·β_k)
// (β_0 = 1): a path traces bounce ray k+1 with probability Π_{i≤k} s_i, and the expected
// count per camera ray is the sum of these (ρ = 0.5: 1.60; pbrt's survival ∝ β gives
// ρ/(1−ρ) = 1.00, and counting the ray a killed path never traces adds 1). 8 × 8 pixels
// at 256 spp: σ of the mean ≈ 0.013, 0.8 % of it; tolerance 5 % (≈ 6σ).
TEST(Furnace, RouletteSurvivesWithTheRootOfTheThroughput) {
  const double rho = 0.5;
  double expected = 0.0, survive = 1.0, beta = 1.0;
  for (int k = 0; k < 200; ++k) {
    const double s = std::sqrt(rho * beta);
    survive *= s;
    beta = rho * beta / s;
    expected += survive;
  }
  EXPECT_NEAR(expected, 1.60, 0.01);
  const test::LuminanceImage r = test::renderLuminance(furnaceScene(rho, 8, 1000, 1), 256, 3);
  const double perCameraRay =
      static_cast<double>(r.stats.rays.bounce) / static_cast<double>(r.stats.rays.camera);
  std::printf("  bounce rays per camera ray %.4f (expected %.4f)\n", perCameraRay, expected);
  EXPECT_NEAR(perCameraRay / expected, 1.0, 0.05);
}

// Irradiance at x (normal n) from a uniform Lambertian polygon of unit radiance:
//   E = ½ Σᵢ βᵢ · (n · normalize(Rᵢ × Rᵢ₊₁)),  Rᵢ = vᵢ − x,  βᵢ = ∠(Rᵢ, Rᵢ₊₁).
double polygonIrradiance(const glm::dvec3& x, const glm::dvec3& n,
                         const std::vector<glm::dvec3>& poly) {
  double sum = 0.0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const glm::dvec3 a = glm::normalize(poly[i] - x),
                     b = glm::normalize(poly[(i + 1) % poly.size()] - x);
    const double beta = std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
    sum += beta * glm::dot(n, glm::normalize(glm::cross(a, b)));
  }
  return 0.5 * std::abs(sum);
}

// A 0.4 m × 0.3 m emitter 0.3 m above a floor of reflectance 0.6, seen by a camera
// looking straight down from just below the emitter. The floor's radiance at each pixel
// is ρ/π · E; the expectation per pixel averages E over the pixel footprint (16×16
// points). Tolerance 1 % on all 16 pixels of a 4×4 image: measured per-pixel σ is ≈ 2 %
// at 1024 spp, so 65536 spp gives σ ≈ 0.25 % (4σ).
TEST(Irradiance, LambertianFloorUnderRectangularEmitter) {
  const std::string yaml =
      "camera: {position: [0, 0.25, 0], look_at: [0, 0, 0], up: [0, 0, 1], sensor_width_mm: 24,\n"
      "         sensor_height_mm: 24, focal_length_mm: 24, resolution: [4, 4]}\n"
      "render: {max_depth: 4}\n"
      "materials: {floor: {type: diffuse, reflectance: 0.6}}\n"
      "shapes:\n"
      "  - {type: rectangle, corner: [-2, 0, -2], edge_u: [0, 0, 4], edge_v: [4, 0, 0], material: "
      "floor}\n"
      "  - {type: rectangle, corner: [-0.1, 0.3, -0.2], edge_u: [0.4, 0, 0], edge_v: [0, 0, 0.3],\n"
      "     emission: {scale: 0.02, spectrum: 1}}\n";
  const Image img = renderY(yaml, 65536);
  const std::vector<glm::dvec3> emitter = {
      {-0.1, 0.3, -0.2}, {0.3, 0.3, -0.2}, {0.3, 0.3, 0.1}, {-0.1, 0.3, 0.1}};
  const int yc = img.channelIndex("Y");
  // Camera looks down −y with up = +z, so right = forward × up = (0,−1,0) × (0,0,1) = −x.
  // Pixel (i, j) sees the floor at x = −(u − ½)·w·h/f, z = (½ − v)·w·h/f, h = 0.25 m.
  const double halfExtent = 0.25 * 0.5;  // (24 mm / 24 mm) · 0.25 m / 2
  // The pixel weights the floor by cos⁴θ (camera equation), so the expectation is the
  // cos⁴-weighted mean of E over the photosite.
  constexpr int kSub = 16;
  for (int j = 0; j < img.height; ++j)
    for (int i = 0; i < img.width; ++i) {
      double e = 0.0, wsum = 0.0;
      for (int sy = 0; sy < kSub; ++sy)
        for (int sx = 0; sx < kSub; ++sx) {
          const double u = (i + (sx + 0.5) / kSub) / img.width,
                       v = (j + (sy + 0.5) / kSub) / img.height;
          const double a = (u - 0.5) * 2.0, b = (0.5 - v) * 2.0;     // sensor coords / half-width
          const double cos2 = 1.0 / (1.0 + 0.25 * (a * a + b * b));  // tanθ = half-width/f · r
          const glm::dvec3 p(-a * halfExtent, 0.0, b * halfExtent);
          e += cos2 * cos2 * polygonIrradiance(p, {0.0, 1.0, 0.0}, emitter);
          wsum += cos2 * cos2;
        }
      e /= wsum;
      const double expected = 0.6 / M_PI * e * 0.02 * flatY();
      EXPECT_NEAR(static_cast<double>(img.at(i, j, yc)) / expected, 1.0, 0.01)
          << "pixel " << i << "," << j;
    }
}

}  // namespace
}  // namespace camsim
