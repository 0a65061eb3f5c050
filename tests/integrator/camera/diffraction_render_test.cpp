// Diffraction in a render: a stripe pattern in focus at f/8 on a 5 µm pixel loses contrast at
// its frequency by the diffraction-limited MTF, weighted over the spectrum as the film's Y
// integrates it.
//
// A plane at z_o = 2 m, focused exactly (no geometric blur), carries vertical stripes of
// period 4 px on the film, lit head-on by parallel light of flat spectrum. Diffraction
// convolves the film's irradiance with the PSF, so the amplitude of the stripes' fundamental
// (the image's DFT along x at 16 cycles over 64 px, rows averaged) is multiplied by the OTF
// at f₀ = 1/(4 px) — the photosite box and the pattern's harmonics are the same in both
// renders and cancel in the ratio:
//
//   A_on / A_off = Σ_λ ȳ(λ) MTF(f₀ λ N_w) / Σ_λ ȳ(λ),   MTF(ν) = (2/π)(acos ν − ν√(1 − ν²))
//
// with N_w = z_i / D = N z_i / f. Both renders use the same seed and the same numbers for
// everything but the jitter (its sample dimensions are apart from the rest).
//
// And the MTF of an in-focus slanted edge at f/8 and 550 nm alone, measured by the e-SFR
// (sensor/measure/slanted_edge.h), against the circular pupil's diffraction-limited MTF
// times the photosite's aperture and ISO's ¼-px bins, up to the cut-off 1/(λN_w) (issue 39).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <string>

#include "integrator/camera/physical_camera.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/measure/slanted_edge.h"
#include "sensor/spectra/cie.h"
#include "tests/integrator/edge_render_support.h"
#include "tests/support/scene_text.h"
#include "tests/support/slanted_edge_image.h"

namespace camsim {
namespace diffraction_render_test {

using test::num;

constexpr double kFocal = 0.050, kFNumber = 8.0, kPitch = 5e-6, kDistance = 2.0;  // m, —, m, m
constexpr int kWidth = 64, kHeight = 16, kPeriodPx = 4;

double imageDistance() {
  return kFocal * kDistance / (kDistance - kFocal);
}

Image renderStripes(bool diffraction) {
  // Stripe period on the plane; the plane's v runs along world x over 2 m.
  const double periodOnPlane = kPeriodPx * kPitch * kDistance / imageDistance();
  const double checksPerV = 2.0 * 2.0 / periodOnPlane;
  const std::string yaml =
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], sensor_width_mm: " +
      num(kWidth * kPitch * 1e3) + ", sensor_height_mm: " + num(kHeight * kPitch * 1e3) +
      ",\n  resolution: [" + std::to_string(kWidth) + ", " + std::to_string(kHeight) +
      "], focal_length_mm: " + num(kFocal * 1e3) + ", f_number: " + num(kFNumber) +
      ", focus_distance_m: " + num(kDistance) +
      ",\n  aperture: {diffraction: " + (diffraction ? "true" : "false") +
      "}}\n"
      "render: {max_depth: 1}\n"
      "materials:\n"
      "  stripes: {type: diffuse, reflectance: {checkerboard: {a: 1, b: 0, checks: " +
      num(checksPerV) +
      "}, scale: [0, 1]}}\n"
      "shapes:\n"
      "  - {type: rectangle, corner: [-1, -1, " +
      num(kDistance) +
      "], edge_u: [0, 2, 0], edge_v: [2, 0, 0], material: stripes}\n"
      "lights: [{type: distant, direction: [0, 0, 1], angular_diameter: 0, illuminance: 1000,"
      " spectrum: 1}]\n";
  const Scene scene(loadSceneFromText(yaml, "stripes.yaml", "."));
  EXPECT_EQ(scene.modelled().diffraction, diffraction);
  RenderOptions options;
  options.spp = 256;
  options.seed = 7;
  return render(scene, SpectralResponse::cieXyz(), options).image;
}

// |DFT of the row-averaged Y at k cycles over the width|.
double fundamental(const Image& img, int cycles) {
  const int c = img.channelIndex("Y");
  std::complex<double> sum = 0.0;
  for (int x = 0; x < img.width; ++x) {
    double column = 0.0;
    for (int y = 0; y < img.height; ++y) column += static_cast<double>(img.at(x, y, c));
    const double phase = -2.0 * M_PI * cycles * (x + 0.5) / img.width;
    sum += column * std::complex<double>(std::cos(phase), std::sin(phase));
  }
  return std::abs(sum);
}

// Tolerance 0.03: the MTF of the tabulated PSF is within 0.02 of the analytic one
// (Diffraction.OtfOfTheCircularStopIsTheDiffractionLimitedMtf) and the two renders' noise in
// the ratio is below 0.01 at 256 spp.
TEST(DiffractionRender, StripesLoseContrastByTheDiffractionMtf) {
  const Image sharp = renderStripes(false);
  const Image blurred = renderStripes(true);
  const int cycles = kWidth / kPeriodPx;
  const double measured = fundamental(blurred, cycles) / fundamental(sharp, cycles);
  const double f0 = 1.0 / (kPeriodPx * kPitch);  // cycles per m on the film
  const double nw = kFNumber * imageDistance() / kFocal;
  const Spectrum& ybar = Cie1931::get().y;
  double weighted = 0.0, total = 0.0;
  for (int lambda = 360; lambda <= 830; ++lambda) {
    const double nu = f0 * lambda * 1e-9 * nw;
    const double mtf =
        nu >= 1.0 ? 0.0 : 2.0 / M_PI * (std::acos(nu) - nu * std::sqrt(1.0 - nu * nu));
    const double y = static_cast<double>(ybar(static_cast<float>(lambda)));
    weighted += y * mtf;
    total += y;
  }
  const double expected = weighted / total;
  std::printf("[measured] stripes at f/8, 4 px: contrast on/off %.4f, expected %.4f\n", measured,
              expected);
  EXPECT_NEAR(measured, expected, 0.03) << "measured " << measured << ", expected " << expected;
  // The mean level is kept: diffraction moves light, it does not remove it.
  EXPECT_NEAR(fundamental(blurred, 0) / fundamental(sharp, 0), 1.0, 0.01);
}

// The diffraction-limited MTF of a circular pupil at ν = f·λ·N_w (f in cycles/m on the film,
// λ in m; cut off at ν = 1).
double circularPupilMtf(double nu) {
  if (nu >= 1.0) return 0.0;
  return 2.0 / M_PI * (std::acos(nu) - nu * std::sqrt(1.0 - nu * nu));
}

// A 6 mm f/8 thin lens focused at 1 m on a backlit edge at 1 m, tilted 5°, rays at 550 nm
// only, traced by the camera itself (test::renderEdgeAtOneWavelength: the renderer's paths
// carry wavelengths drawn over the visible, and a 545–555 nm emitter left the e-SFR ±0.1 of
// noise at 256 spp). Photosites of 2 µm: the cut-off 1/(λN_w) = 0.452 cycles/px lies below
// Nyquist. The ROI is 160 px wide (72 λN_w) because the Airy pattern's line spread falls only
// as 1/x²: the e-SFR's ROI and Hamming window cut its tail off and read the MTF high at low
// frequency — by 0.044 with a 64 px ROI on 1 µm photosites (14.5 λN_w), by 0.0096 with this
// one (the e-SFR of the analytic ESF: scripts/esfr_diffraction_bias.py, docs/mtf.md).
// Tolerance 0.02: that truncation, and the e-SFR's noise at 1024 rays per pixel (at 256 it
// reached 0.034 near the cut-off, where the MTF is nearly 0 and the noise's magnitude shows).
TEST(DiffractionRender, EdgeMtfAtF8And550NmIsTheDiffractionLimitedMtf) {
  constexpr double kF = 0.006, kN = 8.0, kS = 1.0, kP = 2e-6, kLambda = 550e-9;  // m, —, m, m, m
  PhysicalCameraParams p;
  p.resolution = {176, 72};
  p.sensorSize = {176 * kP, 72 * kP};
  p.focalLength = kF;
  p.fNumber = kN;
  p.focusDistance = kS;
  p.aperture = ApertureShape{0, 0.0, true};  // circular, diffraction on
  const PhysicalCamera camera(p);
  const double nw = kN * (kF * kS / (kS - kF)) / kF;  // N_w = N·z_i/f
  ASSERT_NE(camera.diffraction(), nullptr);
  ASSERT_NEAR(camera.diffraction()->workingFNumber(), nw, 1e-9);
  const Image img = test::renderEdgeAtOneWavelength(camera, {kS, 5.0}, 1024, 550.0f, 11);
  const SfrResult r = measureSfr(img, EdgeRoi{8, 4, 160, 64});
  EXPECT_NEAR(r.angleDeg, 5.0, 0.05);
  const double cutoff = kP / (kLambda * nw);  // cycles/px
  const double t = 5.0 * M_PI / 180.0;
  double worst = 0.0, worstAt = 0.0;
  for (size_t k = 0; k < r.frequency.size() && r.frequency[k] <= cutoff; ++k) {
    const double f = r.frequency[k];
    const double expected = circularPupilMtf(f * kLambda * nw / kP) *
                            test::sincPi(f * std::cos(t)) * test::sincPi(f * std::sin(t)) *
                            test::sincPi(f / 4.0);
    const double err = std::abs(r.mtf[k] - expected);
    if (err > worst) {
      worst = err;
      worstAt = f;
    }
  }
  std::printf(
      "[measured] edge at f/8 (N_w %.4f), 550 nm, 2 um pixels: max |MTF error| to the "
      "cut-off %.3f cy/px: %.4f at %.3f cy/px\n",
      nw, cutoff, worst, worstAt);
  EXPECT_LT(worst, 0.02);
}

}  // namespace diffraction_render_test
}  // namespace camsim
