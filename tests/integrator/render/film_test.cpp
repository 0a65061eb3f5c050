// Film with a sensor response: a mosaic stores only each photosite's CFA channel, in
// expected photo-electrons = energy · QE · λ/(hc), filled in the same pass as CIE XYZ.
#include <gtest/gtest.h>

#include <string>

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/spectra/cie.h"

namespace camsim {
namespace {

// A uniform field of flat spectral radiance 0.01 W·m⁻²·sr⁻¹·nm⁻¹ seen through a 20 µm
// on-axis pixel block at f/4, 10 ms (pinhole: E = π L / (4 N²) on axis, cos⁴ ≈ 1 here).
const char* kUniform =
    "camera: {position: [0, 0, 0], look_at: [0, 0, 1], sensor_width_mm: 0.04, sensor_height_mm: "
    "0.04,\n"
    "         resolution: [2, 2], focal_length_mm: 50, f_number: 4, shutter: {open: 0, close: "
    "0.01}}\n"
    "render: {max_depth: 0}\n"
    "shapes:\n"
    "  - {type: sphere, centre: [0, 0, 0], radius: 100, emission: {scale: 0.01, spectrum: 1, "
    "two_sided: true}}\n";

TEST(Film, MosaicStoresEachPhotositesChannelInElectrons) {
  const Scene scene(loadSceneFromText(kUniform, "test.yaml", "."));
  const CfaLayout rggb{2, 2, {0, 1, 1, 2}, {"R", "G", "B"}, "RGGB"};
  // Band QE over 400–700 nm (real sensors: an IR cut; flat QE out to 830 nm would weight
  // the visible pdf's thin tails and add noise, not bias).
  const std::vector<double> nm = {399.0, 400.0, 700.0, 701.0}, band = {0.0, 1.0, 1.0, 0.0};
  const Spectrum window = Spectrum::fromSamples(nm, band, Extrapolation::kZero);
  const std::vector<Spectrum> qe = {window * 0.2, window * 0.5, window * 0.8};
  const SpectralResponse sensor = SpectralResponse::electrons({"R", "G", "B"}, qe, &rggb);
  const SpectralResponse xyz = SpectralResponse::cieXyz();
  RenderOptions options;
  options.spp = 4096;
  const RenderResult r = render(scene, {&xyz, &sensor}, options);
  ASSERT_EQ(r.images.size(), 2u);
  EXPECT_EQ(r.images[0].channelCount(), 3);
  ASSERT_EQ(r.images[1].channelCount(), 1);
  // Expected electrons: A_pixel · T · π L / (4N²) · QE · Σ λ/(hc) Δλ (1 nm grid).
  constexpr double h = 6.62607015e-34, c = 299792458.0;
  double photonsPerJoule = 0.0;  // Σ over the grid of λ/(hc), per W/nm flat spectrum
  for (int i = 0; i < kSpectrumSamples; ++i)
    photonsPerJoule += static_cast<double>(window.sample(i)) * (kLambdaMinNm + i) * 1e-9 / (h * c);
  const double energyPerNm = (20e-6 * 20e-6) * 0.01 * M_PI * 0.01 / (4.0 * 16.0);  // J/nm
  const double base = energyPerNm * photonsPerJoule;
  const double expected[2][2] = {{0.2 * base, 0.5 * base}, {0.5 * base, 0.8 * base}};
  // Tolerance 1 %: the only noise is the wavelength sampling of QE·λ/p(λ).
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x)
      EXPECT_NEAR(static_cast<double>(r.images[1].at(x, y, 0)) / expected[y][x], 1.0, 0.01)
          << x << "," << y;
  // The XYZ film of the same pass is unchanged by the extra response.
  const RenderResult xyzOnly = render(scene, xyz, options);
  EXPECT_EQ(xyzOnly.image.pixels, r.images[0].pixels);
}

}  // namespace
}  // namespace camsim
