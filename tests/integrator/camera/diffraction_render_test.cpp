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
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <string>

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/spectra/cie.h"
#include "tests/support/scene_text.h"

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

}  // namespace diffraction_render_test
}  // namespace camsim
