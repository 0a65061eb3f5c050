// The traced lens in the camera (integrator/camera/lens_camera.h): a thin, weak singlet at
// f/8 gives the thin-lens camera's on-axis exposure; the double-Gauss's relative
// illumination across the field matches an independent integration over its rear plane;
// a scene renders through it; the loader's errors for camera.lens. The singlet at f/16 blurs a
// defocused slanted edge as the thin lens of its EFL, f-number and focus does (e-SFR).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <glm/geometric.hpp>

#include "integrator/camera/lens_camera.h"
#include "integrator/camera/physical_camera.h"
#include "integrator/render/render.h"
#include "integrator/scene/overrides.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "sensor/measure/slanted_edge.h"
#include "tests/integrator/edge_render_support.h"
#include "tests/integrator/lens_test_support.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace lens_camera_test {

// A plano-convex BK7-index singlet, f = R/(n − 1) = 100 mm, the stop 1 mm in front (mm).
const char* const kSinglet =
    "0      1.0  0       16\n"
    "51.68  3.0  1.5168  30\n"
    "0      95   1       30\n";

LensSpec specFile(const std::string& name, double fNumber) {
  LensSpec spec;
  spec.prescription = readLensPrescription(test::lensPath(name));
  spec.fNumber = fNumber;
  return spec;
}

// The mean measurement weight at the film centre over a stratified n × n pupil grid (lost
// rays count 0), for a camera with a 36 × 24 mm sensor at 360 × 240 px.
double meanCentreWeight(const PhysicalCamera& camera, int n) {
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.5f);
  CameraSample cs;
  cs.pFilm = glm::vec2(camera.resolution()) * 0.5f;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      cs.pLens = glm::vec2((i + 0.5f) / n, (j + 0.5f) / n);
      if (auto r = camera.generateRay(cs, lambda)) sum += static_cast<double>(r->weight[0]);
    }
  return sum / (double(n) * n);
}

PhysicalCameraParams baseParams() {
  PhysicalCameraParams p;
  p.sensorSize = {0.036, 0.024};
  p.resolution = {360, 240};
  return p;
}

TEST(LensCamera, ThinSingletGivesTheThinLensOnAxisExposureAtF11) {
  LensSpec spec;
  spec.prescription = parseLensPrescription(kSinglet, "singlet");
  spec.fNumber = 11.0;
  PhysicalCameraParams lensParams = baseParams();
  lensParams.lens = spec;
  lensParams.aperture = ApertureShape{0, 0.0, false};  // geometric optics: no diffraction
  const PhysicalCamera lensCamera(lensParams);
  // The thin lens at the same focal length (the singlet's EFL) and f-number, aplanatic.
  PhysicalCameraParams thinParams = baseParams();
  thinParams.focalLength = lensCamera.lensCamera()->paraxial().effectiveFocalLength;
  thinParams.fNumber = 11.0;
  thinParams.aperture = ApertureShape{0, 0.0, false};
  const PhysicalCamera thin(thinParams);
  const double traced = meanCentreWeight(lensCamera, 256);
  const double expected = meanCentreWeight(thin, 4);  // the same for every lens point
  std::printf("singlet f/11 on axis: traced %.6g, thin lens %.6g (ratio %.5f), EFL %.4f mm\n",
              traced, expected, traced / expected, thinParams.focalLength * 1e3);
  EXPECT_NEAR(traced / expected, 1.0, 0.01);
}

// ∫ cosθ_film cosθ_rear / d² over the rear-plane points whose rays pass, by a dense grid
// over a square twice the rear element (the independent reference).
double gridIntegral(const LensSystem& lens, double s, glm::dvec2 film, int n) {
  const double e = 2.0 * lens.rearClearRadius();
  const double cell = 2.0 * e / n;
  const LensSystem::Indices idx = lens.indicesAt(kLambdaDNm);
  const glm::dvec3 o(film, -s);
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const glm::dvec3 p(-e + (i + 0.5) * cell, -e + (j + 0.5) * cell, 0.0);
      const glm::dvec3 v = p - o;
      const double d2 = glm::dot(v, v);
      if (lens.traceFromFilm({o, v / std::sqrt(d2)}, idx)) sum += v.z * v.z / (d2 * d2);
    }
  return sum * cell * cell;
}

TEST(LensCamera, RelativeIlluminationMatchesAGridOverTheRearPlane) {
  const LensCamera camera(specFile("dgauss.50mm.dat", 0.0), {0.036, 0.024});
  const double s = camera.sensorDistance();
  double centreSampled = 0.0, centreGrid = 0.0;
  for (double h : {0.0, 0.008, 0.014, 0.020}) {
    const glm::dvec2 film(h, 0.0);  // upright; LensCamera inverts it
    const int n = 300;
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        if (auto r = camera.generate(film, {(i + 0.5) / n, (j + 0.5) / n}, kLambdaDNm))
          sum += r->geometric;
    const double sampled = sum / (double(n) * n);
    const double grid = gridIntegral(camera.lens(), s, -film, 600);
    if (h == 0.0) {
      centreSampled = sampled;
      centreGrid = grid;
    }
    std::printf("dgauss f/2.03 at %2.0f mm: sampled %.6g sr, grid %.6g sr (ratio %.5f), RI %.4f\n",
                h * 1e3, sampled, grid, sampled / grid, grid / centreGrid);
    EXPECT_NEAR(sampled / grid, 1.0, 0.02) << h;
    EXPECT_NEAR((sampled / centreSampled) / (grid / centreGrid), 1.0, 0.02) << h;
  }
  // On axis the cone's projected solid angle is about π/(4 N_w²) (the lens nearly obeys the
  // sine condition); at 20 mm the double-Gauss vignettes.
  const double nw = camera.paraxial().workingFNumber;
  EXPECT_NEAR(centreGrid / (M_PI / (4.0 * nw * nw)), 1.0, 0.05);
  EXPECT_LT(gridIntegral(camera.lens(), s, {-0.020, 0.0}, 300) / centreGrid, 0.8);
}

TEST(LensCamera, ASceneRendersThroughTheDoubleGauss) {
  const std::string text = R"(format: camsim-scene/1
render: {spp: 16, max_depth: 1}
camera:
  position: [0, 0, 0]
  look_at: [0, 0, 1]
  resolution: [36, 24]
  lens: {file: dgauss.50mm.dat}
shapes:
  - name: dome
    type: sphere
    centre: [0, 0, 0]
    radius: 50
    emission: {luminance: 1000, two_sided: true}
)";
  const Scene scene(loadSceneFromText(text, "lens.yaml", CAMSIM_SOURCE_DIR));
  ASSERT_NE(scene.camera().lensCamera(), nullptr);
  RenderOptions options;
  options.spp = 16;
  options.seed = 3;
  options.threads = 2;
  const RenderResult r = render(scene, SpectralResponse::cieXyz(), options);
  double centre = 0.0, corner = 0.0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 36; ++x) {
      const float v = r.image.at(x, y, 1);
      ASSERT_TRUE(std::isfinite(v));
      ASSERT_GE(v, 0.0f);
    }
  for (int y = 10; y < 14; ++y)
    for (int x = 16; x < 20; ++x) centre += static_cast<double>(r.image.at(x, y, 1));
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) corner += static_cast<double>(r.image.at(x, y, 1));
  std::printf("dome through dgauss f/2: centre %.4g, corner %.4g (ratio %.3f)\n", centre, corner,
              corner / centre);
  EXPECT_GT(centre, 0.0);
  EXPECT_LT(corner, 0.8 * centre);
}

// Defocus blur, traced against thin (issue 39: a one-surface ideal lens reproduces the thin
// lens's blur). The singlet above (one refracting surface and a plane) at f/16, focused at 2 m,
// and the thin lens of its EFL at f/16 focused at 2 m (both distances from the entrance pupil,
// the camera's origin), image a backlit edge at 1.5 m, tilted 5°, on 14 µm photosites, rays
// at λ_d (the singlet does not disperse), no diffraction. The thin lens's blur disc is
// c = A·f·|s − s_f|/(s·(s_f − f)) = 0.110 mm = 7.8 px (A = f/N). Both e-SFRs must agree within
// 0.02 over the disc MTF's main lobe, f ≤ 1.25/c (its first zero is at 1.22/c: the lobe's
// width is the disc's diameter; past it the side lobes are under 0.13 and 256 rays per pixel
// leave them 0.02 of noise). What the two may differ by: the singlet's spherical aberration —
// its rim rays land 6.5 % inside its paraxial disc, which is 4 % larger than the thin lens's
// (focus is the best-RMS plane) — and the noise, 0.003–0.009 between seeds. A 5 % error in
// the traced camera's f-number changes the disc's diameter by 5 %, one in its focus distance
// (2.1 m) by 15 % (d ln c / d ln s_f = s_f/(s_f − s) − s_f/(s_f − f)): the test checks that
// both move the MTF by more than 0.02.
struct BlurCase {
  double fNumber = 16.0;
  double focus = 2.0;  // m
};

constexpr double kBlurPitch = 14e-6;  // m
constexpr int kBlurWidth = 80, kBlurHeight = 96;

PhysicalCameraParams blurParams() {
  PhysicalCameraParams p;
  p.resolution = {kBlurWidth, kBlurHeight};
  p.sensorSize = {kBlurWidth * kBlurPitch, kBlurHeight * kBlurPitch};
  p.aperture = ApertureShape{0, 0.0, false};  // geometric optics
  return p;
}

SfrResult measureBlur(const PhysicalCamera& camera) {
  const Image img =
      test::renderEdgeAtOneWavelength(camera, {1.5, 5.0}, 256, static_cast<float>(kLambdaDNm), 5);
  return measureSfr(img, EdgeRoi{8, 8, 64, 80});
}

PhysicalCameraParams singletParams(const BlurCase& c) {
  PhysicalCameraParams p = blurParams();
  LensSpec spec;
  spec.prescription = parseLensPrescription(kSinglet, "singlet");
  spec.fNumber = c.fNumber;
  spec.focusDistance = c.focus;
  p.lens = spec;
  return p;
}

// The traced camera's blur-disc diameter (px) for an axial point at `distance` (m from the
// entrance pupil): twice the height on the sensor of a ray from it through the entrance
// pupil at `fraction` of its radius, scaled back by 1/fraction (so a small fraction gives
// the paraxial disc, 1 the rim rays' — the spherical aberration is their difference).
double tracedDiscPx(const LensCamera& lc, double distance, double fraction) {
  const ParaxialData& pa = lc.paraxial();
  const glm::dvec3 object(0.0, 0.0, pa.entrancePupilZ + distance);
  const glm::dvec3 pupil(fraction * 0.5 * pa.entrancePupilDiameter, 0.0, pa.entrancePupilZ);
  const auto out = lc.lens().traceFromObject({object, glm::normalize(pupil - object)}, kLambdaDNm);
  if (!out) return -1.0;
  const double t = (-lc.sensorDistance() - out->origin.z) / out->direction.z;
  return 2.0 * std::abs(out->origin.x + t * out->direction.x) / fraction / kBlurPitch;
}

// max |a − b| for frequencies up to fMax (cycles/px).
double mtfDistance(const SfrResult& a, const SfrResult& b, double fMax) {
  double worst = 0.0;
  for (size_t k = 0; k < a.frequency.size() && a.frequency[k] <= fMax; ++k)
    worst = std::max(worst, std::abs(a.mtf[k] - b.mtf[k]));
  return worst;
}

TEST(LensCamera, SingletBlursADefocusedEdgeAsTheThinLens) {
  const PhysicalCamera singlet(singletParams({}));
  PhysicalCameraParams thinParams = blurParams();
  thinParams.focalLength = singlet.lensCamera()->paraxial().effectiveFocalLength;
  thinParams.fNumber = 16.0;
  thinParams.focusDistance = 2.0;
  const SfrResult thin = measureBlur(PhysicalCamera(thinParams));
  const SfrResult traced = measureBlur(singlet);
  const double f = thinParams.focalLength;
  const double c = f / 16.0 * f * (2.0 - 1.5) / (1.5 * (2.0 - f)) / kBlurPitch;  // px
  std::printf(
      "[measured] singlet f/16 blur disc of a point at 1.5 m: paraxial rays %.3f px, "
      "rim rays %.3f px; thin lens %.3f px\n",
      tracedDiscPx(*singlet.lensCamera(), 1.5, 0.01),
      tracedDiscPx(*singlet.lensCamera(), 1.5, 0.999), c);
  const double lobe = 1.25 / c;  // cycles/px
  const double d = mtfDistance(traced, thin, lobe);
  const double slowerBy5 =
      mtfDistance(measureBlur(PhysicalCamera(singletParams({16.8, 2.0}))), thin, lobe);
  const double focusFarBy5 =
      mtfDistance(measureBlur(PhysicalCamera(singletParams({16.0, 2.1}))), thin, lobe);
  std::printf(
      "[measured] singlet f/16 vs thin lens (EFL %.3f mm, disc %.2f px): max |dMTF| to %.3f "
      "cy/px %.4f; "
      "f/16.8: %.4f; focus 2.1 m: %.4f; MTF50 %.4f vs %.4f cy/px\n",
      f * 1e3, c, lobe, d, slowerBy5, focusFarBy5, traced.mtf50.value_or(-1.0),
      thin.mtf50.value_or(-1.0));
  EXPECT_LT(d, 0.02);
  EXPECT_GT(slowerBy5, 0.02);
  EXPECT_GT(focusFarBy5, 0.02);
}

void expectLoadError(const std::string& lens, const std::string& extra, const std::string& what) {
  const std::string text =
      "format: camsim-scene/1\ncamera:\n  position: [0, 0, 0]\n"
      "  look_at: [0, 0, 1]\n" +
      extra + "  lens: " + lens + "\nshapes: []\n";
  try {
    loadSceneFromText(text, "bad.yaml", CAMSIM_SOURCE_DIR);
    ADD_FAILURE() << "no error for " << lens << " / " << extra;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos) << e.what();
  }
}

TEST(LensCamera, LoaderErrors) {
  expectLoadError("{file: dgauss.50mm.dat, f_number: 1.4}", "", "faster than the lens");
  expectLoadError("{file: dgauss.50mm.dat, f_number: 129}", "",
                  "key 'camera.lens.f_number': f_number 129 is slower than a traced lens is "
                  "stopped to, f/128");
  expectLoadError("{file: no_such_lens.dat}", "", "no_such_lens");
  expectLoadError("{file: dgauss.50mm.dat, focus: 2}", "", "focus");
  expectLoadError("{file: dgauss.50mm.dat, focus_distance_m: 0.04}", "", "focus distance");
  expectLoadError("{file: dgauss.50mm.dat}", "  focal_length_mm: 50\n", "focal_length_mm");
  expectLoadError("{f_number: 2}", "", "file");
  // Found by probing, both beyond the front focal point: the fisheye's entrance pupil lies
  // 11.5 mm inside it, so 10.1 mm put the plane of focus inside the glass (rendered, exit
  // 0); the telephoto's real bundle from 0.349 m leaves the rear group diverging (a check
  // aborted the render, exit 134). 0.35 m images (best focus 17.9 m behind it).
  expectLoadError("{file: fisheye.10mm.dat, focus_distance_m: 0.0101}", "",
                  "key 'camera.lens.focus_distance_m': focus distance 0.0101 m (from the "
                  "entrance pupil) puts the plane of focus 1.442 mm behind the lens's front "
                  "vertex, inside the lens");
  expectLoadError("{file: telephoto.250mm.dat, focus_distance_m: 0.349}", "",
                  "key 'camera.lens.focus_distance_m': the lens forms no real image of a plane "
                  "at 0.349 m");
  // Found by probing: a singlet whose aspheric term bends the real rays from infinity
  // outwards was refused focused at 1000 m but, focused at infinity (the default), aborted
  // the render on an internal check (exit 134).
  const test::TempDir dir;
  const std::filesystem::path singlet = dir.path() / "diverging.dat";
  test::writeFile(singlet, "0 5 0 10\n50 3 1.5 20 a4=-1e-3\n-50 0 1 20\n");
  expectLoadError("{file: " + singlet.string() + "}", "",
                  "key 'camera.lens': the lens forms no real image of a distant object "
                  "(focus_distance_m unset: focused at infinity)");
  // The best focus depends on the stop: the telephoto at 0.3495 m images at f/5.6 but not
  // wide open (f/5.42); an --f-number override opening it aborted the render (exit 134;
  // found in review). The override is refused as the loader refuses the file.
  SceneDescription tele = loadSceneFromText(
      "format: camsim-scene/1\ncamera: {position: [0, 0, 0], look_at: [0, 0, 1], lens: {file: "
      "telephoto.250mm.dat, focus_distance_m: 0.3495, f_number: 5.6}}\nshapes: [{type: sphere, "
      "centre: [0, 0, 3], radius: 1, emission: {luminance: 1}}]\n",
      "tele.yaml", CAMSIM_SOURCE_DIR);
  Overrides wide;
  wide.fNumber = 5.4235;
  try {
    applyOverrides(tele, wide, {"<command line>", 0, 0});
    ADD_FAILURE() << "f/5.4235 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "camera.lens.f_number");
    EXPECT_NE(e.message().find("at f/5.4235 the lens forms no real image of a plane at 0.3495 m"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(loadSceneFromText(
      "format: camsim-scene/1\ncamera: {position: [0, 0, 0], look_at: [0, 0, 1], lens: {file: "
      "telephoto.250mm.dat, focus_distance_m: 0.35}}\nshapes: [{type: sphere, centre: [0, 0, "
      "3], radius: 1, emission: {luminance: 1}}]\n",
      "ok.yaml", CAMSIM_SOURCE_DIR));
}

}  // namespace lens_camera_test
}  // namespace camsim
