// The spectral control variate (integrator/render/spectral_control_variate.h): the film's
// term is exact, the estimate keeps its expectation, and the colour noise of white light
// on white walls is gone.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "integrator/render/film.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/spectral_bins.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

// A sample whose q is exactly B[bin(λ)]·E(λ) adds Σ_b B_b ∫_bin r_c E dλ whatever
// wavelengths were drawn: its lanes cancel and the film adds the integrals alone.
TEST(SpectralControlVariate, FilmAddsTheExactIntegralsOfTheBinnedSpectrum) {
  const SpectralResponse xyz = SpectralResponse::cieXyz();
  const Spectrum reference = Spectrum::blackbody(3200.0) * 1e-6;
  SpectralBins bins;
  for (int b = 0; b < kSpectralBins; ++b) bins[b] = 0.1f + 0.05f * static_cast<float>(b % 5);
  std::vector<double> expected(3, 0.0);
  for (int c = 0; c < 3; ++c) {
    const std::array<double, kSpectralBins> m = binIntegrals(xyz.channel(c).curve, reference);
    for (int b = 0; b < kSpectralBins; ++b)
      expected[static_cast<std::size_t>(c)] +=
          m[static_cast<std::size_t>(b)] * static_cast<double>(bins[b]);
  }
  for (float u : {0.0f, 0.123f, 0.5f, 0.999f}) {
    Film film({1, 1}, {&xyz});
    film.setSpectralReference(reference);
    const SampledWavelengths lambda = SampledWavelengths::sampleVisible(u);
    const SampledSpectrum q = bins.at(lambda) * sampleSpectrum(reference, lambda);
    ASSERT_TRUE(film.addSample({0, 0}, 0, q, lambda, &bins));
    film.setSamples({0, 0}, 1);
    const Image image = film.toImages()[0];
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(static_cast<double>(image.at(0, 0, c)) / expected[static_cast<std::size_t>(c)],
                  1.0, 2e-6)
          << "u " << u << " channel " << c;
  }
  // Without a reference the bins are ignored: the plain estimate, bit for bit.
  Film plain({1, 1}, {&xyz}), ignoring({1, 1}, {&xyz});
  const SampledWavelengths lambda = SampledWavelengths::sampleVisible(0.3f);
  const SampledSpectrum q = bins.at(lambda);
  plain.addSample({0, 0}, 0, q, lambda);
  ignoring.addSample({0, 0}, 0, q, lambda, &bins);
  plain.setSamples({0, 0}, 1);
  ignoring.setSamples({0, 0}, 1);
  EXPECT_EQ(plain.toImages()[0].pixels, ignoring.toImages()[0].pixels);
  // Non-finite bins reject the sample.
  Film film({1, 1}, {&xyz});
  film.setSpectralReference(reference);
  SpectralBins bad = bins;
  bad[9] = std::nanf("");
  EXPECT_FALSE(film.addSample({0, 0}, 0, q, lambda, &bad));
}

// A white room lit by one emitter: every path's spectrum is the emitter's times a number,
// so with the variate each sample's colour is the emitter's exactly and a pixel's
// chromaticity is the same in every pixel (to float rounding, measured 3e-7); the plain
// estimate's four wavelengths scatter it (measured 2.4e-2 at 16 spp).
std::string whiteRoom(bool cv) {
  return std::string(
             "camera: {position: [0, 1, -2.5], look_at: [0, 1, 0], resolution: [24, 24],"
             " focal_length_mm: 24}\n"
             "render: {max_depth: 6, spectral_control_variate: ") +
         (cv ? "true" : "false") +
         "}\n"
         "materials: {white: {type: diffuse, reflectance: 0.6}}\n"
         "shapes:\n"
         "  - {type: rectangle, corner: [-1, 0, -1], edge_u: [0, 0, 2], edge_v: [2, 0, 0],"
         " material: white}\n"
         "  - {type: rectangle, corner: [-1, 0, 1], edge_u: [0, 2, 0], edge_v: [2, 0, 0],"
         " material: white}\n"
         "  - {type: rectangle, corner: [-0.3, 1.99, -0.3], edge_u: [0.6, 0, 0], edge_v: [0, 0, "
         "0.6],"
         " emission: {luminance: 5000, spectrum: {illuminant: F11}}}\n";
}

double chromaticitySpread(const std::string& yaml) {
  const Scene scene(loadSceneFromText(yaml, "room.yaml", "."));
  RenderOptions options;
  options.spp = 16;
  options.threads = 2;
  const RenderResult r = render(scene, SpectralResponse::cieXyz(), options);
  double lo = 1e30, hi = -1e30;
  for (int y = 0; y < r.image.height; ++y)
    for (int x = 0; x < r.image.width; ++x) {
      const double X = r.image.at(x, y, 0), Y = r.image.at(x, y, 1), Z = r.image.at(x, y, 2);
      if (!(Y > 0.0)) continue;
      const double cx = X / (X + Y + Z);
      lo = std::min(lo, cx);
      hi = std::max(hi, cx);
    }
  EXPECT_LT(lo, hi + 1.0);  // some pixel is lit
  return hi - lo;
}

TEST(SpectralControlVariate, WhiteLightOnWhiteWallsHasNoColourNoise) {
  const double with = chromaticitySpread(whiteRoom(true));
  const double without = chromaticitySpread(whiteRoom(false));
  RecordProperty("spread_with", std::to_string(with));
  RecordProperty("spread_without", std::to_string(without));
  EXPECT_LT(with, 1e-5);
  EXPECT_GT(without, 1e-3);
}

// Expectation kept, on a scene that exercises the main branches: coloured and textured
// Lambertian walls, a second emitter whose band (600–640 nm, an eighth of the visible pdf) is 0 at every drawn
// wavelength half of the time, a point light (not written as bins), a metal (which turns the variate off
// for the rest of the path) and no roulette, so that the same seed traces the same paths
// with the variate on and off: the per-sample difference is then C − Y, the variate's
// term, whose mean must be 0. Its image mean over 16 seeds against its standard error:
// |t| < 4 per channel. (With the bins of the drawn wavelengths shifted by one — a wrong
// term — t read −16.5, −34.8 and −2.0.)
std::string busyRoom(bool cv, int rrDepth) {
  return std::string(
             "camera: {position: [0, 1, -2.5], look_at: [0, 1, 0], resolution: [16, 16],"
             " focal_length_mm: 20}\n"
             "render: {max_depth: 5, rr_depth: ") +
         std::to_string(rrDepth) + ", spectral_control_variate: " + (cv ? "true" : "false") +
         "}\n"
         "materials:\n"
         "  red: {type: diffuse, reflectance: {rgb: [0.7, 0.1, 0.05]}}\n"
         "  checks: {type: diffuse, reflectance: {checkerboard: {a: {rgb: [0.1, 0.6, 0.2]},"
         " b: {rgb: [0.2, 0.3, 0.8]}, checks: 4}}}\n"
         "  gold: {type: conductor, metal: Au, roughness: 0.2}\n"
         "shapes:\n"
         "  - {type: rectangle, corner: [-1, 0, -1], edge_u: [0, 0, 2], edge_v: [2, 0, 0],"
         " material: checks}\n"
         "  - {type: rectangle, corner: [-1, 0, 1], edge_u: [0, 2, 0], edge_v: [2, 0, 0],"
         " material: red}\n"
         "  - {type: rectangle, corner: [1, 0, -1], edge_u: [0, 2, 0], edge_v: [0, 0, 2],"
         " material: gold}\n"
         "  - {type: rectangle, corner: [-0.3, 1.99, -0.3], edge_u: [0.6, 0, 0], edge_v: [0, 0, "
         "0.6],"
         " emission: {luminance: 5000}}\n"
         "  - {type: sphere, centre: [-0.6, 0.3, 0.4], radius: 0.15,"
         " emission: {luminance: 1000, spectrum: {csv: band.csv}}}\n"
         "lights:\n"
         "  - {type: point, position: [0.5, 1.5, -0.5], intensity: 20}\n";
}

std::vector<double> meanXyz(const std::string& yaml, const std::filesystem::path& dir,
                            std::uint64_t seed, int spp) {
  const Scene scene(loadSceneFromText(yaml, "busy.yaml", dir));
  RenderOptions options;
  options.spp = spp;
  options.seed = seed;
  options.threads = 2;
  const RenderResult r = render(scene, SpectralResponse::cieXyz(), options);
  EXPECT_EQ(r.stats.rejectedSamples, 0u);
  std::vector<double> m(3, 0.0);
  for (int c = 0; c < 3; ++c) {
    for (int y = 0; y < r.image.height; ++y)
      for (int x = 0; x < r.image.width; ++x)
        m[static_cast<std::size_t>(c)] += static_cast<double>(r.image.at(x, y, c));
    m[static_cast<std::size_t>(c)] /= r.image.width * r.image.height;
  }
  return m;
}

void writeBand(const test::TempDir& dir) {
  test::writeFile(dir.path() / "band.csv", "wavelength_nm,band\n599,0\n600,1\n640,1\n641,0\n");
}

TEST(SpectralControlVariate, TheTermHasMeanZero) {
  const test::TempDir dir;
  writeBand(dir);
  constexpr int kSeeds = 16;
  std::vector<std::vector<double>> d(3);
  double scale[3] = {0, 0, 0};
  for (int s = 0; s < kSeeds; ++s) {
    const std::vector<double> on = meanXyz(busyRoom(true, 100), dir.path(), 100 + s, 128);
    const std::vector<double> off = meanXyz(busyRoom(false, 100), dir.path(), 100 + s, 128);
    for (int c = 0; c < 3; ++c) {
      d[static_cast<std::size_t>(c)].push_back(on[static_cast<std::size_t>(c)] -
                                               off[static_cast<std::size_t>(c)]);
      scale[c] += off[static_cast<std::size_t>(c)] / kSeeds;
    }
  }
  for (int c = 0; c < 3; ++c) {
    const std::vector<double>& v = d[static_cast<std::size_t>(c)];
    double mean = 0.0, var = 0.0;
    for (double x : v) mean += x / kSeeds;
    for (double x : v) var += (x - mean) * (x - mean) / (kSeeds - 1);
    const double se = std::sqrt(var / kSeeds);
    ASSERT_GT(se, 0.0) << "channel " << c << ": the variate changed nothing";
    EXPECT_LT(std::abs(mean) / se, 4.0) << "channel " << c << " mean " << mean << " se " << se;
    // The test's power: 4 standard errors are under 2 % of the channel.
    EXPECT_LT(4.0 * se / scale[c], 0.02) << "channel " << c;
    std::printf("channel %d: mean %.3e, t %.2f, se/channel %.2e\n", c, mean, mean / se,
                se / scale[c]);
  }
}

// With Russian roulette (it reads the bins with the variate on, the wavelengths'
// throughput without) the paths differ: the two estimates' image means over 16 seeds each
// agree within 4 standard errors of their difference.
TEST(SpectralControlVariate, RouletteOnTheBinsKeepsTheMean) {
  const test::TempDir dir;
  writeBand(dir);
  constexpr int kSeeds = 16;
  std::vector<double> on[3], off[3];
  for (int s = 0; s < kSeeds; ++s) {
    const std::vector<double> a = meanXyz(busyRoom(true, 1), dir.path(), 200 + s, 96);
    const std::vector<double> b = meanXyz(busyRoom(false, 1), dir.path(), 300 + s, 96);
    for (int c = 0; c < 3; ++c) {
      on[c].push_back(a[static_cast<std::size_t>(c)]);
      off[c].push_back(b[static_cast<std::size_t>(c)]);
    }
  }
  const auto stats = [](const std::vector<double>& v, double& mean, double& var) {
    mean = 0.0;
    var = 0.0;
    for (double x : v) mean += x / static_cast<double>(v.size());
    for (double x : v) var += (x - mean) * (x - mean) / static_cast<double>(v.size() - 1);
  };
  for (int c = 0; c < 3; ++c) {
    double ma, va, mb, vb;
    stats(on[c], ma, va);
    stats(off[c], mb, vb);
    const double se = std::sqrt(va / kSeeds + vb / kSeeds);
    EXPECT_LT(std::abs(ma - mb) / se, 4.0) << "channel " << c << ": " << ma << " vs " << mb;
    // The test's power: 4 standard errors are under 3 % of the channel.
    EXPECT_LT(4.0 * se / mb, 0.03) << "channel " << c;
    RecordProperty("t_" + std::to_string(c), std::to_string((ma - mb) / se));
  }
}

}  // namespace
}  // namespace camsim
