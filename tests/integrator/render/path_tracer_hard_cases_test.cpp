// The path tracer on hard cases, each against a stated reference, each asserting finite
// output and zero rejected (NaN/Inf) samples:
//  - a uniform furnace (closed emitting sphere of radiance Lₑ, reflectance ρ: L = Lₑ/(1−ρ)
//    everywhere) seen at grazing incidence (cos θ ≈ 1e-6) and through bent shading normals;
//  - the same scene 10⁶ m from the origin and scaled to 10⁻³ m (radiance is invariant);
//  - degenerate and needle triangles in a floor (no light leaks through the seams);
//  - microfacet roughness 0, 1e-4 and 1 in a uniform field of radiance Lₑ (F = 1):
//    L = Lₑ for a mirror, ≤ Lₑ otherwise;
//  - a mirror reflects an emitter at exactly k·Lₑ; a smooth glass slab transmits
//    Lₑ(1−R)/(1+R) (two interfaces, all internal reflections);
//  - a light inside glass, seen from outside at normal incidence: L = (1−R)·Lₑ/η²;
//  - the camera inside a glass sphere at its centre in a uniform field: L = η²·Lₑ (the
//    invariance of L/n²), and with a dispersive glass L(λ) = η(λ)²·Lₑ(λ).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "integrator/scene/scene_loader.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/spectral_data.h"
#include "tests/integrator/render_test_support.h"
#include "tests/support/scene_text.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

using test::num;

using test::flatY;
using test::LuminanceImage;
using test::meanOf;
using test::renderLuminance;

void expectClean(const LuminanceImage& img) {
  EXPECT_EQ(img.stats.rejectedSamples, 0u);
  for (int y = 0; y < img.y.height; ++y)
    for (int x = 0; x < img.y.width; ++x) ASSERT_TRUE(std::isfinite(img.at(x, y))) << x << "," << y;
}

// A closed sphere of radius 2 m (centre c), emitting Lₑ = 0.01 on both sides with
// reflectance ρ = 0.5, and a 1 m square plate through c in the plane z = c.z, also
// emitting and reflecting the same: the whole enclosure is uniform, L = 0.02 everywhere.
// The camera sits `height` above the plate's plane looking along it (grazing), scaled by s.
std::string grazingFurnace(glm::dvec3 c, double s, double height) {
  auto p = [&](double x, double y, double z) {
    return "[" + num(c.x + s * x) + ", " + num(c.y + s * y) + ", " + num(c.z + s * z) + "]";
  };
  return "camera: {position: " + p(-0.4, 0.0, height) + ", look_at: " + p(0.4, 0.0, height) +
         ", up: [0, 0, 1], sensor_width_mm: 2, sensor_height_mm: 2, focal_length_mm: 50,\n"
         "         resolution: [4, 4]}\n"
         "render: {max_depth: 60, rr_depth: 10000}\n"
         "materials: {wall: {type: diffuse, reflectance: 0.5}}\n"
         "shapes:\n"
         "  - {type: sphere, centre: " +
         p(0, 0, 0) + ", radius: " + num(2.0 * s) +
         ", material: wall, emission: {scale: 0.01, spectrum: 1, two_sided: true}}\n"
         "  - {type: rectangle, corner: " +
         p(-0.5, -0.5, 0) + ", edge_u: [" + num(s) + ", 0, 0], edge_v: [0, " + num(s) +
         ", 0], material: wall, emission: {scale: 0.01, spectrum: 1, two_sided: true}}\n";
}

// Tolerance: per-pixel σ at 1024 spp measured ≈ 0.6 %; 2 % on each of 16 pixels.
TEST(HardCases, GrazingIncidenceInAUniformFurnace) {
  for (double height : {1e-3, 1e-6}) {
    const LuminanceImage img = renderLuminance(grazingFurnace({0, 0, 0}, 1.0, height), 1024);
    expectClean(img);
    const double expected = 0.02 * flatY();
    std::printf("[measured] grazing height %g m: mean L / reference = %.4f\n", height,
                meanOf(img) / expected);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        EXPECT_NEAR(img.at(x, y) / expected, 1.0, 0.02) << "height " << height;
  }
}

// The same furnace 10⁶ m from the origin and shrunk to 10⁻³ m: the image must not change
// beyond noise (render space is camera-relative; ray origins are offset by error bounds,
// so there is no self-intersection acne at any scale).
TEST(HardCases, FarFromOriginAndMillimetreScale) {
  const double expected = 0.02 * flatY();
  for (auto [centre, scale] :
       {std::pair{glm::dvec3(1e6, -1e6, 1e6), 1.0}, std::pair{glm::dvec3(0.0), 1e-3},
        std::pair{glm::dvec3(1e6, 2e6, -3e6), 1e-3}}) {
    const LuminanceImage img = renderLuminance(grazingFurnace(centre, scale, 0.05), 1024);
    expectClean(img);
    std::printf("[measured] centre (%g, %g, %g) scale %g: mean L / reference = %.4f\n", centre.x,
                centre.y, centre.z, scale, meanOf(img) / expected);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        EXPECT_NEAR(img.at(x, y) / expected, 1.0, 0.02)
            << "centre " << centre.x << " scale " << scale;
  }
}

// A 4 m floor of reflectance 0.6 built from 400 needle triangles (1 cm × 4 m, aspect 400)
// plus zero-area triangles (repeated and collinear vertices), under a 0.4 × 0.3 m emitter:
// the image must match the same floor made of two triangles (seams must not leak; the
// degenerate triangles must neither be hit nor sampled). Same seed, so the difference is
// only where paths diverge; tolerance 1 % on the image mean (σ ≈ 0.3 % at 4096 spp).
std::string needleFloor(bool needles) {
  std::string vertices, faces;
  int n = 0;
  auto v = [&](double x, double z) {
    vertices += "[" + num(x) + ", 0, " + num(z) + "], ";
    return n++;
  };
  if (needles) {
    for (int i = 0; i < 400; ++i) {
      const double x0 = -2.0 + 0.01 * i, x1 = x0 + 0.01;
      const int a = v(x0, -2), b = v(x1, -2), c = v(x1, 2), d = v(x0, 2);
      faces += "[" + std::to_string(a) + ", " + std::to_string(d) + ", " + std::to_string(c) +
               "], [" + std::to_string(a) + ", " + std::to_string(c) + ", " + std::to_string(b) +
               "], ";
      // Degenerate: a repeated vertex and a collinear triple.
      faces +=
          "[" + std::to_string(a) + ", " + std::to_string(a) + ", " + std::to_string(c) + "], ";
      const int m = v(x0, 0.0);
      faces +=
          "[" + std::to_string(a) + ", " + std::to_string(m) + ", " + std::to_string(d) + "], ";
    }
  } else {
    const int a = v(-2, -2), b = v(2, -2), c = v(2, 2), d = v(-2, 2);
    faces = "[" + std::to_string(a) + ", " + std::to_string(d) + ", " + std::to_string(c) + ", " +
            std::to_string(b) + "], ";
  }
  vertices.resize(vertices.size() - 2);
  faces.resize(faces.size() - 2);
  return "camera: {position: [0, 0.25, 0], look_at: [0, 0, 0], up: [0, 0, 1], sensor_width_mm: "
         "24,\n"
         "         sensor_height_mm: 24, focal_length_mm: 24, resolution: [8, 8]}\n"
         "render: {max_depth: 4}\n"
         "materials: {floor: {type: diffuse, reflectance: 0.6}}\n"
         "shapes:\n"
         "  - {type: mesh, material: floor, vertices: [" +
         vertices + "], faces: [" + faces +
         "]}\n"
         "  - {type: rectangle, corner: [-0.1, 0.3, -0.2], edge_u: [0.4, 0, 0], edge_v: [0, 0, "
         "0.3],\n"
         "     emission: {scale: 0.02, spectrum: 1}}\n";
}

TEST(HardCases, NeedleAndDegenerateTrianglesChangeNothing) {
  const LuminanceImage reference = renderLuminance(needleFloor(false), 4096);
  const LuminanceImage needles = renderLuminance(needleFloor(true), 4096);
  expectClean(reference);
  expectClean(needles);
  std::printf("[measured] needle floor / two-triangle floor: %.4f\n",
              meanOf(needles) / meanOf(reference));
  EXPECT_NEAR(meanOf(needles) / meanOf(reference), 1.0, 0.01);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      EXPECT_NEAR(needles.at(x, y) / reference.at(x, y), 1.0, 0.05) << x << "," << y;
}

// A uniform field: the camera and a sphere of `material` inside a closed, purely emitting
// sphere (Lₑ = 0.01, black, two-sided). What the sphere reflects is albedo(ωo)·Lₑ. Without
// the inner sphere (material empty) the camera sees the field itself: the same seed gives
// the same wavelengths per pixel sample, so ratios to that render carry no wavelength noise
// (the spectral control variate is off: it would make the field's colour exact per sample
// and the conductor's, which it does not write as bins, not).
std::string hardUniformField(const std::string& material) {
  return "camera: {position: [0, 0, -3], look_at: [0, 0, 0], sensor_width_mm: 8, sensor_height_mm: "
         "8,\n"
         "         focal_length_mm: 50, resolution: [6, 6]}\n"
         "render: {max_depth: 40, rr_depth: 10000, spectral_control_variate: false}\n"
         "materials: {m: " +
         (material.empty() ? std::string("{type: diffuse}") : material) +
         "}\n"
         "shapes:\n"
         "  - {type: sphere, centre: [0, 0, 0], radius: 10, emission: {scale: 0.01, spectrum: 1, "
         "two_sided: true}}\n" +
         (material.empty() ? std::string()
                           : "  - {type: sphere, centre: [0, 0, 0], radius: 0.5, material: m}\n");
}

// Roughness 0 (delta), 1e-4 (the sharpest microfacet lobe) and 1, with F = 1: α = 0
// returns the field exactly (ratio 1 to 1e-5: float rounding only); α = 1e-4 within 1 % per
// pixel; α = 1 loses the multiple-scattering energy: darker, never brighter (≤ 1 + 1 %),
// and above 0.25 (the single-scattering albedo at normal incidence, the lowest over the
// sphere, is 0.307 for GGX and 0.46 for Beckmann by quadrature).
TEST(HardCases, ConductorRoughnessExtremesInAUniformField) {
  const LuminanceImage field = renderLuminance(hardUniformField(""), 256);
  for (const char* distribution : {"ggx", "beckmann"}) {
    for (double alpha : {0.0, 1e-4, 1.0}) {
      const std::string material =
          std::string("{type: conductor, fresnel: schlick, reflectance: 1, roughness: ") +
          num(alpha) + ", distribution: " + distribution + "}";
      const LuminanceImage img = renderLuminance(hardUniformField(material), 256);
      expectClean(img);
      std::printf("[measured] %s α %g, F = 1: mean L / Le = %.5f\n", distribution, alpha,
                  meanOf(img) / meanOf(field));
      for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 6; ++x) {
          const double r = img.at(x, y) / field.at(x, y);
          if (alpha < 0.5) {
            EXPECT_NEAR(r, 1.0, alpha == 0.0 ? 1e-5 : 0.01) << distribution << " α " << alpha;
          } else {
            EXPECT_LE(r, 1.01) << distribution;
            EXPECT_GE(r, 0.25) << distribution;
          }
        }
    }
  }
}

// Shading normals bent up to 80° away from the geometric normal (one vertex normal even
// points below the surface): in the uniform field the Lambertian sphere-replacement must
// stay finite and never exceed the field (it may lose energy where the shading and
// geometric hemispheres disagree).
TEST(HardCases, ShadingNormalsFacingAwayFromTheGeometry) {
  const std::string scene =
      "camera: {position: [0, 0, -3], look_at: [0, 0, 0], sensor_width_mm: 8, sensor_height_mm: "
      "8,\n"
      "         focal_length_mm: 50, resolution: [6, 6]}\n"
      "render: {max_depth: 40, rr_depth: 10000}\n"
      "materials: {m: {type: diffuse, reflectance: 1}}\n"
      "shapes:\n"
      "  - {type: sphere, centre: [0, 0, 0], radius: 10, emission: {scale: 0.01, spectrum: 1, "
      "two_sided: true}}\n"
      "  - {type: mesh, material: m, file: bent.obj}\n";
  const test::TempDir dir;  // this run's own, removed whatever happens
  // A quad facing the camera (−z), vertex normals tilted 80°, 60°, −80° and flipped.
  test::writeFile(dir.path() / "bent.obj",
                  "v -0.5 -0.5 0\nv 0.5 -0.5 0\nv 0.5 0.5 0\nv -0.5 0.5 0\n"
                  "vn 0.985 0 -0.174\nvn 0 0.866 -0.5\nvn -0.985 0 -0.174\nvn 0 0 1\n"
                  "f 1//1 4//4 3//3\nf 1//1 3//3 2//2\n");
  const LuminanceImage img = renderLuminance(scene, 512, 1, dir.path());
  expectClean(img);
  const double le = 0.01 * flatY();
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x) {
      EXPECT_LE(img.at(x, y) / le, 1.02) << x << "," << y;
      EXPECT_GE(img.at(x, y) / le, 0.0) << x << "," << y;
    }
}

// Camera → mirror (k = 0.8, 45°) → emitter: L = k·Lₑ exactly. The reference is the same
// emitter seen directly (same seed, so the same wavelengths): the ratio is k to float
// rounding (the spectral control variate off, as in hardUniformField).
TEST(HardCases, MirrorReflectsAnEmitterAtKTimesLe) {
  const std::string camera =
      "camera: {position: [0, 0, -2], look_at: [0, 0, 0], sensor_width_mm: 2, sensor_height_mm: "
      "2,\n"
      "         focal_length_mm: 50, resolution: [4, 4]}\n"
      "render: {spectral_control_variate: false}\n";
  const std::string viaMirror = camera +
                                "materials: {m: {type: mirror, reflectance: 0.8}}\n"
                                "shapes:\n"
                                "  - {type: mesh, material: m, vertices: [[-1, -1, 1], [1, -1, "
                                "-1], [1, 1, -1], [-1, 1, 1]], faces: [[0, 3, 2, 1]]}\n"
                                "  - {type: rectangle, corner: [-3, -2, -2], edge_u: [0, 4, 0], "
                                "edge_v: [0, 0, 4], emission: {scale: 0.01, spectrum: 1}}\n";
  const std::string direct = camera +
                             "shapes:\n"
                             "  - {type: rectangle, corner: [-2, -2, 3], edge_u: [0, 4, 0], "
                             "edge_v: [4, 0, 0], emission: {scale: 0.01, spectrum: 1}}\n";
  const LuminanceImage img = renderLuminance(viaMirror, 16);
  const LuminanceImage reference = renderLuminance(direct, 16);
  expectClean(img);
  expectClean(reference);
  std::printf("[measured] mirror k = 0.8: L / Le = %.6f\n", meanOf(img) / meanOf(reference));
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      EXPECT_NEAR(img.at(x, y) / reference.at(x, y), 0.8, 1e-5) << x << "," << y;
}

// A 10 m × 10 m glass block between z = −h and z = +h, faces outward (the camera looks
// along +z from z = −2 at normal incidence).
std::string glassBox(double h) {
  const std::string a = num(-h), b = num(h);
  return "  - {type: mesh, material: glass, vertices: [[-5, -5, " + a + "], [5, -5, " + a +
         "], [5, 5, " + a + "], [-5, 5, " + a + "],\n     [-5, -5, " + b + "], [5, -5, " + b +
         "], [5, 5, " + b + "], [-5, 5, " + b +
         "]],\n     faces: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], "
         "[3, 0, 4, 7]]}\n";
}

// A smooth glass slab (η = 1.5, 0.2 m thick) in front of an emitter, at normal incidence:
// the transmitted radiance summed over all internal reflections is Lₑ(1−R)²/(1−R²) =
// Lₑ(1−R)/(1+R), R = ((η−1)/(η+1))² = 0.04 → 0.923077 Lₑ. The field of view is ±0.6°,
// where R changes by < 1e-5. Tolerance 0.5 % (paths choose R/T at random: σ ≈ 0.2 % at 1024 spp).
TEST(HardCases, GlassSlabTransmitsTheFresnelPredictedRadiance) {
  std::string scene =
      "camera: {position: [0, 0, -2], look_at: [0, 0, 0], sensor_width_mm: 1, sensor_height_mm: "
      "1,\n"
      "         focal_length_mm: 50, resolution: [4, 4]}\n"
      "render: {max_depth: 40, rr_depth: 10000}\n"
      "materials: {glass: {type: dielectric, ior: 1.5}}\n"
      "shapes:\n" +
      glassBox(0.1) +
      "  - {type: rectangle, corner: [-10, -10, 1], edge_u: [0, 20, 0], edge_v: [20, 0, 0], "
      "emission: {scale: 0.01, spectrum: 1}}\n";
  const LuminanceImage img = renderLuminance(scene, 1024);
  expectClean(img);
  const double r = 0.04;
  std::printf("[measured] glass slab: L / (Le (1-R)/(1+R)) = %.4f\n",
              meanOf(img) / (0.01 * flatY() * (1.0 - r) / (1.0 + r)));
  EXPECT_NEAR(meanOf(img) / (0.01 * flatY() * (1.0 - r) / (1.0 + r)), 1.0, 0.005);
}

// An emitter inside a glass block (η = 1.5), facing the camera outside at normal
// incidence: radiance leaving the glass is (1−R)·Lₑ/η² = 0.96/2.25 Lₑ (Lₑ is the radiance
// the emitter sends into the glass). Light sampling cannot reach the emitter through the
// smooth interface; only BSDF-sampled paths do. Tolerance 0.5 %.
TEST(HardCases, LightInsideGlass) {
  std::string scene =
      "camera: {position: [0, 0, -2], look_at: [0, 0, 0], sensor_width_mm: 1, sensor_height_mm: "
      "1,\n"
      "         focal_length_mm: 50, resolution: [4, 4]}\n"
      "render: {max_depth: 40, rr_depth: 10000}\n"
      "materials: {glass: {type: dielectric, ior: 1.5}}\n"
      "shapes:\n" +
      glassBox(0.5) +
      "  - {type: rectangle, corner: [-1, -1, 0], edge_u: [0, 2, 0], edge_v: [2, 0, 0], emission: "
      "{scale: 0.01, spectrum: 1}}\n";
  const LuminanceImage img = renderLuminance(scene, 256);
  expectClean(img);
  std::printf("[measured] light inside glass: L / ((1-R) Le / eta^2) = %.4f\n",
              meanOf(img) / (0.01 * flatY() * 0.96 / 2.25));
  EXPECT_NEAR(meanOf(img) / (0.01 * flatY() * 0.96 / 2.25), 1.0, 0.005);
}

// The camera at the centre of a glass sphere in a uniform field Lₑ: every camera ray
// meets the surface at normal incidence, and L = T η² Lₑ / (1 − R) = η² Lₑ. With BK7 the
// same holds per wavelength (dispersion: secondary wavelengths are terminated at the
// glass), Y = K_m ∫ η(λ)² Lₑ ȳ dλ. Tolerance 1 %.
TEST(HardCases, CameraInsideGlassSeesEtaSquaredTimesTheField) {
  auto scene = [](const std::string& glass) {
    return "camera: {position: [0, 0, 0], look_at: [0, 0, 1], sensor_width_mm: 1, "
           "sensor_height_mm: 1,\n"
           "         focal_length_mm: 50, resolution: [4, 4]}\n"
           "render: {max_depth: 40, rr_depth: 10000}\n"
           "materials: {glass: {type: dielectric, " +
           glass +
           "}}\n"
           "shapes:\n"
           "  - {type: sphere, centre: [0, 0, 0], radius: 10, emission: {scale: 0.01, spectrum: 1, "
           "two_sided: true}}\n"
           "  - {type: sphere, centre: [0, 0, 0], radius: 1, material: glass}\n";
  };
  const LuminanceImage constant = renderLuminance(scene("ior: 1.5"), 256);
  expectClean(constant);
  std::printf("[measured] camera inside glass (eta 1.5): L / (eta^2 Le) = %.4f\n",
              meanOf(constant) / (0.01 * flatY() * 2.25));
  EXPECT_NEAR(meanOf(constant) / (0.01 * flatY() * 2.25), 1.0, 0.01);

  const LuminanceImage bk7 = renderLuminance(scene("glass: BK7"), 1024);
  expectClean(bk7);
  const SpectralTable table = readSpectralCsv(lutsDirectory() / "spectra/glasses/BK7.csv");
  const Spectrum eta = table.spectrum(table.columnIndex("eta"), Extrapolation::kClamp);
  double y = 0.0;
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const double lambda = kLambdaMinNm + i;
    const double e = static_cast<double>(eta(static_cast<float>(lambda)));
    y += e * e * 0.01 * static_cast<double>(Cie1931::get().y.sample(i));
  }
  std::printf("[measured] camera inside BK7: Y / (Km ∫ eta² Le ybar) = %.4f\n",
              meanOf(bk7) / (kMaxLuminousEfficacy * y));
  EXPECT_NEAR(meanOf(bk7) / (kMaxLuminousEfficacy * y), 1.0, 0.01);
}

}  // namespace
}  // namespace camsim
