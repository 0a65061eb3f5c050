// Radiometry that follows the camera model (issue 36): a camera inside a uniform emissive
// sphere, rendered through each model, against the solid angle each pixel's film area maps
// to by the model's own closed form from its paper — not the library's functions:
//
//   Y(pixel) = L · T_eff · A · c · ∫_pixel dΩ/dA du dv,
//   radial models  dΩ/dA = sin θ / (ρ(θ) · dρ/dθ) / (fx · fy)   (dΩ = sin θ dθ dφ, dA = ρ dρ dφ)
//   equirectangular dΩ/dA = cos(latitude) / (fx · fy)
//
// with c = cos θ of the chief ray for the opencv model's fixed pupil and c = 1 for the pupil
// that turns with the field (every other model), A the pupil's area and L the luminance.
// The row of pixels runs from the optical axis out past each model's image edge (> 90° for
// the fisheyes: rays behind the camera). The expected integral uses a 24 × 24 grid per
// pixel and θ(ρ) by bisection on ρ(θ); the render samples each pixel 1024 times, with
// stratified wavelengths and a spectrally flat field (no wavelength noise in Y), so the
// remaining error is the pixel-sampling noise of the density's variation across a pixel:
// tolerance 0.5 % at every field angle, as the issue asks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "integrator/camera/physical_camera.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/spectra/cie.h"

namespace camsim::model_radiometry_test {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The flat emitter of spectral radiance 0.01 W·m⁻²·sr⁻¹·nm⁻¹ as a luminance (cd/m²).
double uniformLuminance() {
  return kMaxLuminousEfficacy * Cie1931::get().y.sum() * 0.01;
}

RenderResult renderInsideSphere(const std::string& camera, int spp) {
  const std::string yaml = "camera: {position: [0, 0, 0], look_at: [0, 0, 1], " + camera +
                           ", shutter: {open: 0, close: 0.01}}\n"
                           "render: {max_depth: 0}\n"
                           "shapes:\n"
                           "  - {type: sphere, centre: [0, 0, 0], radius: 100,\n"
                           "     emission: {scale: 0.01, spectrum: 1, two_sided: true}}\n";
  const Scene scene(loadSceneFromText(yaml, "test.yaml", "."));
  RenderOptions options;
  options.spp = spp;
  options.seed = 11;
  return render(scene, SpectralResponse::cieXyz(), options);
}

struct RadialCase {
  const char* name;
  std::string projection;             // the scene's camera.projection block
  std::function<double(double)> rho;  // ρ(θ), film units (fx = 1)
  double maxTheta;                    // rad, the field imaged
  bool fixedPupil;                    // opencv: c = cos θ
};

// θ(ρ) by bisection on the increasing ρ(θ) over [0, maxTheta].
double fieldAngleOf(const RadialCase& c, double rho) {
  double lo = 0.0, hi = c.maxTheta;
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (lo + hi);
    (c.rho(mid) < rho ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// ∫ dΩ/dA · c over the pixel [u0, u0 + 1] × [−½, ½] (film units × fx), or −1 when part of the
// pixel lies outside the image circle.
double expectedPixel(const RadialCase& c, double fx, double u0) {
  constexpr int kSub = 24;
  const double edge = c.rho(c.maxTheta);
  double sum = 0.0;
  for (int j = 0; j < kSub; ++j)
    for (int i = 0; i < kSub; ++i) {
      const double u = (u0 + (i + 0.5) / kSub) / fx, v = ((j + 0.5) / kSub - 0.5) / fx;
      const double rho = std::hypot(u, v);
      if (rho >= edge) return -1.0;
      const double theta = fieldAngleOf(c, rho);
      const double h = 1e-6;
      const double drho = (c.rho(theta + h) - c.rho(theta - h)) / (2.0 * h);
      const double density = rho > 0.0 ? std::sin(theta) / (rho * drho) : 1.0 / (drho * drho);
      sum += density * (c.fixedPupil ? std::cos(theta) : 1.0);
    }
  return sum / (kSub * kSub) / (fx * fx);
}

TEST(ModelRadiometry, UniformSphereGivesEachPixelItsSolidAngle) {
  const double xi = 0.8, alpha = 0.6, dsXi = -0.2;
  const auto kb = [](double t) {
    const double t2 = t * t;
    return t * (1.0 + t2 * (0.02 + t2 * (-0.003 + t2 * (0.0005 + t2 * -0.00005))));
  };
  const RadialCase cases[] = {
      {"pinhole (opencv)", "{model: opencv}", [](double t) { return std::tan(t); }, 60 * kDeg,
       true},
      {"opencv k1 k2", "{model: opencv, k1: -0.12, k2: 0.01}",
       [](double t) {
         const double r = std::tan(t), r2 = r * r;
         return r * (1.0 + r2 * (-0.12 + r2 * 0.01));
       },
       55 * kDeg, true},
      {"kannala_brandt",
       "{model: kannala_brandt, k1: 0.02, k2: -0.003, k3: 0.0005, k4: -0.00005, "
       "max_field_angle_deg: 100}",
       kb, 100 * kDeg, false},
      {"equidistant", "{model: equidistant, max_field_angle_deg: 100}", [](double t) { return t; },
       100 * kDeg, false},
      {"equisolid", "{model: equisolid, max_field_angle_deg: 100}",
       [](double t) { return 2.0 * std::sin(0.5 * t); }, 100 * kDeg, false},
      {"stereographic", "{model: stereographic, max_field_angle_deg: 100}",
       [](double t) { return 2.0 * std::tan(0.5 * t); }, 100 * kDeg, false},
      {"orthographic", "{model: orthographic, max_field_angle_deg: 85}",
       [](double t) { return std::sin(t); }, 85 * kDeg, false},
      {"ftheta", "{model: ftheta, k1: 0.01, k2: -0.02, k3: 0.001, max_field_angle_deg: 100}",
       [](double t) { return t + 0.01 * t * t - 0.02 * t * t * t + 0.001 * t * t * t * t; },
       100 * kDeg, false},
      // Mei: a unit direction (sin θ, 0, cos θ) maps to ρ = sin θ / (cos θ + ξ).
      {"unified", "{model: unified, xi: 0.8, max_field_angle_deg: 110}",
       [xi](double t) { return std::sin(t) / (std::cos(t) + xi); }, 110 * kDeg, false},
      // Usenko et al. (2018): d2 = √(sin²θ + (ξ + cos θ)²), ρ = sin θ / (α d2 + (1 − α)(ξ + cos θ)).
      {"double_sphere", "{model: double_sphere, xi: -0.2, alpha: 0.6, max_field_angle_deg: 100}",
       [dsXi, alpha](double t) {
         const double d2 = std::hypot(std::sin(t), dsXi + std::cos(t));
         return std::sin(t) / (alpha * d2 + (1.0 - alpha) * (dsXi + std::cos(t)));
       },
       100 * kDeg, false},
  };
  // 48 pixels from the axis outwards: column 24 is centred on the axis (cx = 23.5 + ½).
  constexpr int kWidth = 48;
  const double f = 0.001, N = 2.0;
  const double A = M_PI * 0.25 * (f / N) * (f / N), T = 0.01;
  for (const RadialCase& c : cases) {
    // The image edge ρ(θ_max)·fx at 23.4 px: the row's last pixel lies wholly outside it.
    const double fx = 23.4 / c.rho(c.maxTheta);
    const double pitch = f / fx;
    const std::string camera = "sensor_width_mm: " + std::to_string(kWidth * pitch * 1e3) +
                               ", sensor_height_mm: " + std::to_string(pitch * 1e3) +
                               ", resolution: [" + std::to_string(kWidth) +
                               ", 1], focal_length_mm: 1, f_number: 2, projection: " + c.projection;
    const RenderResult r = renderInsideSphere(camera, 1024);
    double worst = 0.0, worstTheta = 0.0, widest = 0.0;
    int checked = 0;
    for (int px = kWidth / 2; px < kWidth; ++px) {
      const double u0 = px - 0.5 - (0.5 * kWidth - 0.5);  // pixel's left edge from cx, px
      const double expected = expectedPixel(c, fx, u0);
      if (expected < 0.0) {
        // Wholly outside the image: black.
        if (u0 / fx > c.rho(c.maxTheta)) {
          EXPECT_EQ(r.image.at(px, 0, 1), 0.0f) << c.name << px;
        }
        continue;
      }
      const double measured = double(r.image.at(px, 0, 1)) / (uniformLuminance() * T * A);
      const double err = measured / expected - 1.0;
      if (std::abs(err) > std::abs(worst)) {
        worst = err;
        worstTheta = fieldAngleOf(c, (u0 + 0.5) / fx);
      }
      widest = fieldAngleOf(c, (u0 + 1.0) / fx);
      ++checked;
      EXPECT_NEAR(measured / expected, 1.0, 5e-3) << c.name << " pixel " << px;
    }
    std::printf("[measured] %-16s %2d pixels up to %.1f deg: worst %+.4f %% at %.1f deg\n", c.name,
                checked, widest / kDeg, 100.0 * worst, worstTheta / kDeg);
    EXPECT_GE(checked, 20) << c.name;
  }
}

// Equirectangular: fx = W/2π, fy = H/π; a pixel spans Δλ in longitude and [φ1, φ2] in
// latitude, so its solid angle is Δλ (sin φ2 − sin φ1) exactly; the pupil turns (c = 1).
TEST(ModelRadiometry, EquirectangularPixelsSubtendTheirLatitudeBand) {
  constexpr int kW = 16, kH = 24;
  const double f = 0.001, A = M_PI * 0.25 * (f / 2.0) * (f / 2.0), T = 0.01;
  const RenderResult r = renderInsideSphere(
      "sensor_width_mm: 1.6, sensor_height_mm: 2.4, resolution: [16, 24], "
      "focal_length_mm: 1, f_number: 2, projection: {model: equirectangular}",
      1024);
  double worst = 0.0;
  for (int y = 0; y < kH; ++y) {
    const double lat1 = (y / double(kH) - 0.5) * M_PI, lat2 = ((y + 1) / double(kH) - 0.5) * M_PI;
    const double expected = 2.0 * M_PI / kW * (std::sin(lat2) - std::sin(lat1));
    for (int x : {0, 7, 15}) {
      const double measured = double(r.image.at(x, y, 1)) / (uniformLuminance() * T * A);
      worst = std::max(worst, std::abs(measured / expected - 1.0));
      EXPECT_NEAR(measured / expected, 1.0, 5e-3) << "pixel " << x << ", " << y;
    }
  }
  std::printf("[measured] equirectangular: worst %.4f %% over 24 latitude bands\n", 100.0 * worst);
}

}  // namespace
}  // namespace camsim::model_radiometry_test
