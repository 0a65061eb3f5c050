// The camera equation in absolute units, exposure scaling, lens distortion against
// OpenCV's model, and "model only what the scene needs".
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>

#include "integrator/camera/physical_camera.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/spectra/cie.h"

namespace camsim {
namespace {

constexpr double kScale = 0.01;  // W·m⁻²·sr⁻¹·nm⁻¹, flat emitter spectrum

double emitterLuminance() {
  return kMaxLuminousEfficacy * Cie1931::get().y.sum() * kScale;
}

// A camera inside a large, black, two-sided emissive sphere: uniform radiance everywhere.
std::string uniformField(const std::string& cameraExtra) {
  return "camera: {position: [0, 0, 0], look_at: [0, 0, 1], " + cameraExtra +
         "}\n"
         "render: {max_depth: 0}\n"
         "shapes:\n"
         "  - {type: sphere, centre: [0, 0, 0], radius: 100,\n"
         "     emission: {scale: 0.01, spectrum: 1, two_sided: true}}\n";
}

RenderResult renderScene(const std::string& yaml, int spp, bool forceTime = false,
                         std::uint64_t seed = 5) {
  const Scene scene(loadSceneFromText(yaml, "test.yaml", "."));
  const SpectralResponse response = SpectralResponse::cieXyz();
  RenderOptions options;
  options.spp = spp;
  options.seed = seed;
  options.forceTime = forceTime;
  RenderResult r = render(scene, response, options);
  EXPECT_EQ(r.stats.rejectedSamples, 0u);
  return r;
}

// Exact E/L for a film point at sensor offset x (m) behind a disk stop of diameter D at
// image distance zi: ∫_disk zi² / |v|⁴ dA, v = (lens + x, zi) (projected solid angle).
double diskProjectedSolidAngle(double x, double D, double zi) {
  constexpr int kR = 300, kPhi = 360;
  const double R = 0.5 * D;
  double sum = 0.0;
  for (int i = 0; i < kR; ++i) {
    const double r = (i + 0.5) / kR * R;
    for (int j = 0; j < kPhi; ++j) {
      const double phi = (j + 0.5) / kPhi * 2.0 * M_PI;
      const double vx = r * std::cos(phi) + x, vy = r * std::sin(phi);
      const double d2 = vx * vx + vy * vy + zi * zi;
      sum += zi * zi / (d2 * d2) * r;
    }
  }
  return sum * (R / kR) * (2.0 * M_PI / kPhi);
}

// The default (aplanatic) thin lens obeys the camera equation of ISO 12232 and of light
// meters: on axis E = π L T / (4 N_w²), N_w = N (1 + m). Its weight does not depend on the
// lens point, so a uniform field has no lens noise: the only error is float rounding and the
// cos⁴ of the 20 µm pixel (< 1e-7). Tolerance 0.1 %, for a circular and a bladed stop.
// Diffraction off: its per-wavelength weights would add noise (the next test has it on).
TEST(CameraEquation, AplanaticOnAxisIrradianceIsTheCameraEquation) {
  struct Case {
    double N;
    double focus;  // m, 0 = infinity
    int blades;
  };
  for (const Case c : {Case{1.4, 0.0, 0}, Case{3.7, 0.0, 0}, Case{16.0, 0.0, 6}, Case{1.4, 0.55, 0},
                       Case{2.8, 0.55, 5}}) {
    const std::string extra =
        "sensor_width_mm: 0.02, sensor_height_mm: 0.02, resolution: [1, 1], "
        "focal_length_mm: 50, f_number: " +
        std::to_string(c.N) +
        (c.focus > 0 ? ", focus_distance_m: " + std::to_string(c.focus) : "") +
        ", aperture: {blades: " + std::to_string(c.blades) +
        ", diffraction: false}, shutter: {open: 0, close: 0.01}";
    const RenderResult r = renderScene(uniformField(extra), 64);
    const double f = 0.05;
    const double zi = c.focus > 0 ? f * c.focus / (c.focus - f) : f;
    const double Nw = c.N * zi / f;  // = N (1 + m)
    const double expected =
        M_PI * emitterLuminance() / (4.0 * Nw * Nw) * (0.02e-3 * 0.02e-3) * 0.01;
    const double ratio = static_cast<double>(r.image.at(0, 0, 1)) / expected;
    std::printf("[measured] aplanatic N %.1f focus %.2f blades %d: E / (pi L / 4 Nw^2) = %.6f\n",
                c.N, c.focus, c.blades, ratio);
    EXPECT_NEAR(ratio, 1.0, 1e-3) << "N " << c.N << " focus " << c.focus;
  }
}

// Diffraction moves light, it does not remove it: with it on (the default) the same on-axis
// pixel in the same uniform field measures the camera equation within the noise of the
// per-wavelength MIS weights (16384 spp; tolerance 0.5 %), for a circular and a bladed stop.
TEST(CameraEquation, DiffractionKeepsTheOnAxisIrradiance) {
  for (const int blades : {0, 6}) {
    const std::string extra =
        "sensor_width_mm: 0.02, sensor_height_mm: 0.02, resolution: [1, 1], "
        "focal_length_mm: 50, f_number: 2.8, aperture: {blades: " +
        std::to_string(blades) + "}, shutter: {open: 0, close: 0.01}";
    const RenderResult r = renderScene(uniformField(extra), 16384);
    EXPECT_TRUE(r.stats.modelled.diffraction);
    const double Nw = 2.8;
    const double expected =
        M_PI * emitterLuminance() / (4.0 * Nw * Nw) * (0.02e-3 * 0.02e-3) * 0.01;
    const double ratio = static_cast<double>(r.image.at(0, 0, 1)) / expected;
    std::printf("[measured] diffraction, %d blades: E / (pi L / 4 Nw^2) = %.6f\n", blades, ratio);
    EXPECT_NEAR(ratio, 1.0, 5e-3) << blades << " blades";
  }
}

// The flat pupil (`pupil: flat`): on axis E = π L T / (1 + 4 N_w²), N_w = N (1 + m). A
// 20 µm pixel on the axis; tolerance 1 % (measured noise σ ≈ 0.1 % at 16384 spp).
TEST(CameraEquation, FlatPupilOnAxisIrradianceIsExact) {
  struct Case {
    double N;
    double focus;  // m, 0 = infinity
  };
  for (const Case c : {Case{1.4, 0.0}, Case{2.8, 0.0}, Case{16.0, 0.0}, Case{2.8, 0.55}}) {
    const std::string extra =
        "sensor_width_mm: 0.02, sensor_height_mm: 0.02, resolution: [1, 1], "
        "focal_length_mm: 50, f_number: " +
        std::to_string(c.N) +
        (c.focus > 0 ? ", focus_distance_m: " + std::to_string(c.focus) : "") +
        ", aperture: {blades: 0, pupil: flat}, shutter: {open: 0, close: 0.01}";
    const RenderResult r = renderScene(uniformField(extra), 16384);
    const double f = 0.05;
    const double zi = c.focus > 0 ? f * c.focus / (c.focus - f) : f;
    const double Nw = c.N * zi / f;  // = N (1 + m)
    const double expected =
        M_PI * emitterLuminance() / (1.0 + 4.0 * Nw * Nw) * (0.02e-3 * 0.02e-3) * 0.01;
    EXPECT_NEAR(static_cast<double>(r.image.at(0, 0, 1)) / expected, 1.0, 0.01)
        << "N " << c.N << " focus " << c.focus;
  }
}

// Off axis a flat pupil is seen under a smaller projected solid angle. A row of
// 0.5 mm × 20 µm pixels behind a 25 mm lens (up to 22° off axis); expectation integrated
// numerically over the aperture and across each pixel. Tolerance 1 %.
TEST(CameraEquation, FlatPupilOffAxisFollowsApertureSolidAngleAndCos4AtF16) {
  for (double N : {2.0, 16.0}) {
    const std::string extra =
        "sensor_width_mm: 20.5, sensor_height_mm: 0.02, resolution: [41, 1], "
        "focal_length_mm: 25, f_number: " +
        std::to_string(N) + ", aperture: {blades: 0, pupil: flat}, shutter: {open: 0, close: 0.01}";
    const RenderResult r = renderScene(uniformField(extra), 8192);
    const double f = 0.025, D = f / N, pitch = 0.5e-3, area = pitch * 0.02e-3;
    double centre = 0.0;
    for (int px : {20, 30, 35, 40}) {
      double expected = 0.0, cos4 = 0.0;
      constexpr int kSub = 8;
      for (int k = 0; k < kSub; ++k) {
        const double x = (px + (k + 0.5) / kSub - 20.5) * pitch;
        expected += diskProjectedSolidAngle(x, D, f) / kSub;
        const double c2 = f * f / (x * x + f * f);
        cos4 += c2 * c2 / kSub;
      }
      const double measured =
          static_cast<double>(r.image.at(px, 0, 1)) / (emitterLuminance() * area * 0.01);
      EXPECT_NEAR(measured / expected, 1.0, 0.01) << "N " << N << " pixel " << px;
      if (px == 20) centre = measured;
      if (N == 16.0) {
        EXPECT_NEAR(measured / centre / cos4, 1.0, 0.01) << "cos^4 at pixel " << px;
      }
    }
  }
}

// Off axis the aplanatic lens keeps the chief ray's cos⁴θ (natural vignetting), whatever
// the aperture: E = π L / (4 N²) · cos⁴θ, averaged across each 0.5 mm pixel. No lens
// noise (the weight is the same for every lens point; diffraction off): tolerance 0.1 %.
TEST(CameraEquation, AplanaticOffAxisIsCos4OfTheChiefRay) {
  const double f = 0.025, N = 2.0, pitch = 0.5e-3, area = pitch * 0.02e-3;
  const RenderResult r = renderScene(
      uniformField("sensor_width_mm: 20.5, sensor_height_mm: 0.02, resolution: [41, 1], "
                   "focal_length_mm: 25, f_number: 2, aperture: {blades: 0, diffraction: false}, "
                   "shutter: {open: 0, close: 0.01}"),
      256);
  for (int px : {20, 30, 35, 40}) {
    double cos4 = 0.0;
    constexpr int kSub = 64;
    for (int k = 0; k < kSub; ++k) {
      const double x = (px + (k + 0.5) / kSub - 20.5) * pitch;
      const double c2 = f * f / (x * x + f * f);
      cos4 += c2 * c2 / kSub;
    }
    const double expected = M_PI / (4.0 * N * N) * cos4;
    const double measured =
        static_cast<double>(r.image.at(px, 0, 1)) / (emitterLuminance() * area * 0.01);
    EXPECT_NEAR(measured / expected, 1.0, 1e-3) << "pixel " << px;
  }
}

// Same seed and a static scene: the samples are identical, so the exposure scales exactly
// (to float rounding) with the shutter time and the fill factor; with the f-number it
// scales as 1/N² for the aplanatic lens (to float rounding) and as the flat pupil's
// projected solid angle 1/(1 + 4N²) within noise (1 %).
TEST(Exposure, ScalesWithShutterTimeFillFactorAndAperture) {
  auto centreY = [](const std::string& extra, int spp) {
    const std::string base =
        "sensor_width_mm: 0.02, sensor_height_mm: 0.02, resolution: [1, 1], focal_length_mm: 50, ";
    return static_cast<double>(renderScene(uniformField(base + extra), spp).image.at(0, 0, 1));
  };
  const double t1 = centreY("f_number: 4, shutter: {open: 0, close: 0.01}", 64);
  const double t2 = centreY("f_number: 4, shutter: {open: 0, close: 0.02}", 64);
  EXPECT_NEAR(t2 / t1, 2.0, 2e-6);
  const double trapezoid = centreY(
      "f_number: 4, shutter: {open: 0, close: 0.02, ramp_open: 0.004, ramp_close: 0.002}", 64);
  EXPECT_NEAR(trapezoid / t1, (0.02 - 0.003) / 0.01, 2e-6);  // T_eff = T − (ramps)/2
  const double half = centreY("f_number: 4, fill_factor: 0.5, shutter: {open: 0, close: 0.01}", 64);
  EXPECT_NEAR(half / t1, 0.5, 1e-4);  // the pixel's cos⁴ varies < 1e-7 over 20 µm
  // Diffraction off: its weights integrate the PSF over the photosite, a box that is a
  // different size in units of λN_w at f/2 and f/4, so the same samples would weigh
  // differently (its mean level: CameraEquation.DiffractionKeepsTheOnAxisIrradiance).
  const double a2 =
      centreY("f_number: 2, aperture: {diffraction: false}, shutter: {open: 0, close: 0.01}", 64);
  const double a4 =
      centreY("f_number: 4, aperture: {diffraction: false}, shutter: {open: 0, close: 0.01}", 64);
  EXPECT_NEAR(a2 / a4, 4.0, 4e-6);
  const double f2 = centreY(
      "f_number: 2, aperture: {blades: 0, pupil: flat}, shutter: {open: 0, close: 0.01}", 16384);
  const double f4 = centreY(
      "f_number: 4, aperture: {blades: 0, pupil: flat}, shutter: {open: 0, close: 0.01}", 16384);
  EXPECT_NEAR(f2 / f4, (1.0 + 4.0 * 16.0) / (1.0 + 4.0 * 4.0), 0.01 * (65.0 / 17.0));
}

// OpenCV's projectPoints model, reimplemented: camera coordinates (x right, y down, z
// forward) → pixel (u, v) with pixel centres at integers.
struct BrownConrady {
  double k1, k2, k3, p1, p2;
};
glm::dvec2 projectPoints(glm::dvec3 P, const BrownConrady& d, glm::dvec4 K) {
  const double x = P.x / P.z, y = P.y / P.z, r2 = x * x + y * y;
  const double radial = 1.0 + d.k1 * r2 + d.k2 * r2 * r2 + d.k3 * r2 * r2 * r2;
  const double xd = x * radial + 2.0 * d.p1 * x * y + d.p2 * (r2 + 2.0 * x * x);
  const double yd = y * radial + d.p1 * (r2 + 2.0 * y * y) + 2.0 * d.p2 * x * y;
  return {K.x * xd + K.z, K.y * yd + K.w};
}

// A grid of points projected with OpenCV's formula; the camera's ray through that pixel
// must pass through the point: miss distance converted to pixels < 0.05 px.
TEST(Distortion, MatchesOpenCvProjectPoints) {
  PhysicalCameraParams p;
  p.sensorSize = {6.4e-3, 4.8e-3};
  p.resolution = {640, 480};
  p.focalLength = 4e-3;
  const BrownConrady brown{-0.25, 0.08, -0.01, 0.001, -0.0015};
  p.projection.k1 = brown.k1;
  p.projection.k2 = brown.k2;
  p.projection.k3 = brown.k3;
  p.projection.p1 = brown.p1;
  p.projection.p2 = brown.p2;
  const PhysicalCamera camera(p);
  const glm::dvec4 K = camera.intrinsics();
  EXPECT_DOUBLE_EQ(K.z, 319.5);
  double worst = 0.0;
  for (int gy = -4; gy <= 4; ++gy)
    for (int gx = -5; gx <= 5; ++gx) {
      const glm::dvec3 Pcv(gx * 0.14, gy * 0.13, 2.0);  // OpenCV camera coordinates, m
      const glm::dvec2 uv = projectPoints(Pcv, brown, K);
      CameraSample cs;
      cs.pFilm = glm::vec2(glm::dvec2(uv.x + 0.5, uv.y + 0.5));
      const auto cr = camera.generateRay(cs, SampledWavelengths::sampleUniform(0.5f));
      ASSERT_TRUE(cr.has_value());
      // Camera space (y up) = world here (identity pose): P = (x, −y_cv, z).
      const glm::dvec3 P(Pcv.x, -Pcv.y, Pcv.z);
      const glm::dvec3 o(cr->ray.o), d = glm::normalize(glm::dvec3(cr->ray.d));
      const glm::dvec3 closest = o + glm::dot(P - o, d) * d;
      worst = std::max(worst, glm::length(P - closest) / P.z * K.x);
    }
  EXPECT_LT(worst, 0.05) << "worst miss in pixels";
}

// A static scene gives the identical image with time sampling forced on and off, and the
// analysis reports no time dimension (and no aperture for a pinhole).
TEST(ModelledDimensions, StaticSceneNeedsNoTime) {
  const std::string yaml =
      uniformField("resolution: [8, 8], shutter: {open: 0, close: 0.02, ramp_open: 0.005}") +
      "  - {type: sphere, centre: [0.3, 0, 3], radius: 0.5, emission: {luminance: 500}}\n";
  const RenderResult off = renderScene(yaml, 16, false);
  const RenderResult on = renderScene(yaml, 16, true);
  EXPECT_FALSE(off.stats.modelled.time);
  EXPECT_TRUE(on.stats.modelled.time);
  EXPECT_FALSE(off.stats.modelled.aperture);
  EXPECT_EQ(off.stats.modelled.describe(), "pinhole, static (no time sampling), " +
                                               std::to_string(kWavelengthSamples) +
                                               " wavelengths with the spectral control variate");
  ASSERT_EQ(off.image.pixels.size(), on.image.pixels.size());
  EXPECT_EQ(0, std::memcmp(off.image.pixels.data(), on.image.pixels.data(),
                           off.image.pixels.size() * sizeof(float)));
}

TEST(ModelledDimensions, DescribesApertureTimeAndRollingShutter) {
  const std::string yaml =
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [4, 4], aperture: {blades: "
      "6},\n"
      "         shutter: {open: 0, close: 0.01, type: rolling, row_time: 0.001}}\n"
      "shapes:\n"
      "  - {type: sphere, centre: [0, 0, 3], radius: 0.5, emission: {luminance: 500},\n"
      "     motion: [{time: 0, translate: [0, 0, 0]}, {time: 0.02, translate: [0.1, 0, 0]}]}\n"
      "  - {type: sphere, centre: [1, 0, 3], radius: 0.5, emission: {luminance: 500}}\n";
  const RenderResult r = renderScene(yaml, 1);
  EXPECT_TRUE(r.stats.modelled.aperture);
  EXPECT_TRUE(r.stats.modelled.time);
  EXPECT_EQ(r.stats.modelled.movingObjects, 1);
  EXPECT_TRUE(r.stats.modelled.rollingShutter);
  EXPECT_TRUE(r.stats.modelled.diffraction);  // aperture.diffraction's default
  EXPECT_EQ(r.stats.modelled.describe().substr(0, 71),
            "aperture (6 blades, diffraction), time (1 moving object, rolling shutte");
}

// A traced lens says so, with its file, its surfaces and whether it disperses.
TEST(PhysicalCamera, ModelledLineNamesATracedLens) {
  ModelledDimensions m;
  m.aperture = true;
  m.tracedLens = "dgauss.50mm.abbe.dat";
  m.lensSurfaces = 11;
  m.lensDisperses = true;
  m.diffraction = true;
  EXPECT_EQ(m.describe(),
            "traced lens dgauss.50mm.abbe.dat (11 surfaces, dispersion; circular stop, "
            "diffraction), static (no time sampling), 4 wavelengths");
  m.lensDisperses = false;
  m.diffraction = false;
  m.blades = 6;
  EXPECT_EQ(m.describe().substr(0, 63),
            "traced lens dgauss.50mm.abbe.dat (11 surfaces; 6-blade stop), s");
}

// The static distortion-free pinhole generates rays in float from constants (the fast
// path); any other camera goes through the double-precision general path. A keyframe list
// holding only the rest pose moves nothing but takes the general path, so the two must
// agree on every ray: directions within 2e-6 rad, origins within 1e-6 m, weights within
// 1e-5 relative (float rounding of the same formulas is ≈ 1e-7). A tilted, off-origin
// camera with non-square pixels, over the whole film including its corners.
TEST(PinholeFastPath, AgreesWithTheGeneralPath) {
  const std::string yaml =
      "camera: {position: [1, 2, 3], look_at: [2.5, 1.2, 5], up: [0.1, 1, 0], resolution: [64, "
      "40],\n"
      "         sensor_width_mm: 36, sensor_height_mm: 24, focal_length_mm: 28,\n"
      "         shutter: {open: 0, close: 0.01, ramp_open: 0.002}}\n"
      "shapes: [{type: sphere, centre: [0, 0, 9], radius: 1, emission: {luminance: 1}}]\n";
  PhysicalCameraParams params = loadSceneFromText(yaml, "test.yaml", ".").camera;
  // The fast path's conditions (physical_camera.cpp): else both cameras take the general one.
  ASSERT_TRUE(params.motion.empty() && !params.aperture && PhysicalCamera(params).idealPinhole());
  // The loader puts the camera at the render origin; move it off so origins are compared.
  params.worldFromCamera[3] = glm::dvec4(0.3, -0.2, 1.7, 1.0);
  const PhysicalCamera fast(params);
  PhysicalCameraParams still = params;
  still.motion = RigidMotion({Keyframe{}});
  const PhysicalCamera general(still);
  const SampledWavelengths lambda = SampledWavelengths::sampleVisible(0.3f);
  double worstAngle = 0.0, worstOrigin = 0.0, worstWeight = 0.0;
  for (int y = 0; y <= 40; ++y)
    for (int x = 0; x <= 64; ++x) {
      CameraSample sample;
      sample.pFilm = {static_cast<float>(x), static_cast<float>(y)};
      sample.time = 0.004;
      const std::optional<CameraRay> a = fast.generateRay(sample, lambda);
      const std::optional<CameraRay> b = general.generateRay(sample, lambda);
      ASSERT_TRUE(a && b);
      const glm::dvec3 da(a->ray.d), db(b->ray.d);
      worstAngle =
          std::max(worstAngle, std::atan2(glm::length(glm::cross(da, db)), glm::dot(da, db)));
      worstOrigin = std::max(worstOrigin, static_cast<double>(glm::length(a->ray.o - b->ray.o)));
      worstWeight = std::max(
          worstWeight,
          std::abs(static_cast<double>(a->weight[0]) / static_cast<double>(b->weight[0]) - 1.0));
      EXPECT_EQ(a->ray.time, b->ray.time);
    }
  EXPECT_LT(worstAngle, 2e-6);
  EXPECT_LT(worstOrigin, 1e-6);
  EXPECT_LT(worstWeight, 1e-5);
  char text[64];
  std::snprintf(text, sizeof text, "%.2e rad, %.2e m, %.2e", worstAngle, worstOrigin, worstWeight);
  RecordProperty("worst_direction_origin_weight", text);
}

}  // namespace
}  // namespace camsim
