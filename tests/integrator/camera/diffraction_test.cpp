// Diffraction: the jitter's optical transfer function against the diffraction-limited MTF of
// a circular pupil, the MIS weights' mean per wavelength, the PSF's scaling with λN_w, and
// the turned stop's spikes in camera axes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/geometric.hpp>

#include "integrator/camera/diffraction.h"
#include "integrator/camera/physical_camera.h"
#include "integrator/sampling/rng.h"

namespace camsim {
namespace diffraction_test {

// MTF of an aberration-free circular pupil at ν = f·λ·N (ν ≥ 1: 0).
double circularMtf(double nu) {
  if (nu >= 1.0) return 0.0;
  return 2.0 / M_PI * (std::acos(nu) - nu * std::sqrt(1.0 - nu * nu));
}

// A uniform number in [−½, ½).
double centred(Pcg32& rng) {
  return static_cast<double>(rng.uniform()) - 0.5;
}

// The wavelengths λ₀ = lambda0 and its rotations over [360, 830] nm.
SampledWavelengths wavelengthsFrom(double lambda0) {
  return SampledWavelengths::sampleUniform(static_cast<float>((lambda0 - 360.0) / 470.0));
}

// The OTF of wavelength i is E[w_i cos(2π f·δ)] (the MIS estimator of ∫ PSF_λi(δ) cos(2π f·δ)):
// at f/8 and 550 nm (λ₀), along x and along a diagonal, it is the circular pupil's MTF within
// 0.02 at ν = 0 … 1 in steps of 0.05 (n = 2^18 samples; the estimate's σ ≤ 0.003). The other
// wavelengths of the path, each with its own ν, meet the same bound.
TEST(Diffraction, OtfOfTheCircularStopIsTheDiffractionLimitedMtf) {
  constexpr double kN = 8.0;
  const Diffraction diffraction(ApertureShape{0, 0.0}, kN);
  const SampledWavelengths lambda = wavelengthsFrom(550.0);
  ASSERT_NEAR(lambda[0], 550.0, 1e-3);
  constexpr int n = 1 << 18;
  std::vector<DiffractionSample> samples(n);
  Pcg32 rng(5, 8);
  for (DiffractionSample& s : samples)
    s = diffraction.sample({rng.uniform(), rng.uniform()}, rng.uniform(), lambda, {});
  for (int i = 0; i < kWavelengthSamples; ++i) {
    const double lambdaM = static_cast<double>(lambda[i]) * 1e-9;
    double worst = 0.0;
    for (int step = 0; step <= 20; ++step) {
      const double nu = 0.05 * step, f = nu / (lambdaM * kN);  // cycles per m
      for (const glm::dvec2 dir : {glm::dvec2(1.0, 0.0), glm::dvec2(M_SQRT1_2, M_SQRT1_2)}) {
        double sum = 0.0;
        for (const DiffractionSample& s : samples)
          sum +=
              static_cast<double>(s.weight[i]) * std::cos(2.0 * M_PI * f * glm::dot(dir, s.offset));
        const double otf = sum / n;
        EXPECT_NEAR(otf, circularMtf(nu), 0.02) << "λ = " << lambda[i] << " nm, ν = " << nu;
        worst = std::max(worst, std::abs(otf - circularMtf(nu)));
      }
    }
    RecordProperty("worst_mtf_error_" + std::to_string(i), std::to_string(worst));
  }
}

// One-sample MIS: the weights of each wavelength average to 1 (unbiased), lie in [0, n], for
// a circular and a bladed stop, wavelengths spread over 360–830 nm (n = 2^18 samples:
// measured within 0.0018 of 1; tolerance 0.005).
TEST(Diffraction, MisWeightsAverageToOnePerWavelength) {
  for (const ApertureShape stop : {ApertureShape{0, 0.0}, ApertureShape{6, 0.3}}) {
    const Diffraction diffraction(stop, 2.8);
    for (double lambda0 : {380.0, 550.0, 700.0}) {
      const SampledWavelengths lambda = wavelengthsFrom(lambda0);
      constexpr int n = 1 << 18;
      // Half the samples with a point photosite, half with a 3 µm one (x uniform over it).
      Pcg32 rng(11, static_cast<std::uint64_t>(stop.blades));
      std::vector<double> sum(kWavelengthSamples, 0.0);
      for (int k = 0; k < n; ++k) {
        const glm::dvec2 x = 3e-6 * glm::dvec2(centred(rng), centred(rng));
        const Photosite site = k % 2 ? Photosite{x, glm::dvec2(1.5e-6)} : Photosite{};
        const DiffractionSample s =
            diffraction.sample({rng.uniform(), rng.uniform()}, rng.uniform(), lambda, site);
        for (int i = 0; i < kWavelengthSamples; ++i) {
          ASSERT_GE(s.weight[i], 0.0f);
          ASSERT_LE(s.weight[i], kWavelengthSamples * (1.0f + 1e-6f));
          sum[static_cast<size_t>(i)] += static_cast<double>(s.weight[i]);
        }
      }
      double worst = 0.0;
      for (int i = 0; i < kWavelengthSamples; ++i) {
        EXPECT_NEAR(sum[static_cast<size_t>(i)] / n, 1.0, 0.005)
            << stop.blades << " blades, λ = " << lambda[i] << " nm";
        worst = std::max(worst, std::abs(sum[static_cast<size_t>(i)] / n - 1.0));
      }
      std::printf("[measured] %d blades, λ0 = %.0f nm: worst |mean w_i − 1| = %.5f\n", stop.blades,
                  lambda0, worst);
    }
  }
}

// PSF_λ(δ) = p(δ/(λN_w))/(λN_w)²: doubling λN_w doubles the pattern and quarters its level;
// near the circle's peak (π/4 per (λN_w)²) it is the centre cell's mean, the grid's
// probability of the cell [0, h]² over h² (h its first edge from the centre, 1/16 λN_w).
TEST(Diffraction, PsfScalesWithLambdaTimesWorkingFNumber) {
  const Diffraction a(ApertureShape{6, 0.2}, 4.0), b(ApertureShape{6, 0.2}, 8.0);
  for (const glm::dvec2 d : {glm::dvec2(1e-6, 0.5e-6), glm::dvec2(-3e-6, 7e-6)}) {
    const double pa = a.psf(d, 500.0);
    EXPECT_GT(pa, 0.0);
    EXPECT_NEAR(b.psf(2.0 * d, 500.0) * 4.0 / pa, 1.0, 1e-9);
    EXPECT_NEAR(a.psf(2.0 * d, 1000.0) * 4.0 / pa, 1.0, 1e-9);
  }
  const Diffraction circle(ApertureShape{0, 0.0}, 8.0);
  const double s = 550e-9 * 8.0;
  const PsfGrid& grid = circle.grid();
  const double h = grid.edge(grid.cellsPerAxis() / 2 + 1);
  const double centreMean = grid.boxMass({0.0, 0.0}, {h, h}) / (h * h);
  EXPECT_NEAR(circle.psf({0.01 * s, 0.01 * s}, 550.0) * s * s / centreMean, 1.0, 1e-9);
  EXPECT_NEAR(centreMean, 0.25 * M_PI, 0.005);
}

// With the photosite (a square of side a around the film point, which is uniform over it) the
// weights estimate the PSF convolved with the photosite: E[w_i cos(2π f·y)], y = x + δ the
// moved film point, is the diffraction MTF times the photosite's sinc(π f a) along x, at
// f/8, 550 nm (λ₀) and a 5 µm photosite (fill 1), ν = 0 … 1 in steps of 0.1, within 0.02
// (n = 2^18; σ ≤ 0.003), for every wavelength of the path.
TEST(Diffraction, PhotositeWeightsGiveTheMtfTimesThePixelSinc) {
  constexpr double kN = 8.0, kSide = 5e-6;
  const Diffraction diffraction(ApertureShape{0, 0.0}, kN);
  const SampledWavelengths lambda = wavelengthsFrom(550.0);
  constexpr int n = 1 << 18;
  std::vector<DiffractionSample> samples(n);
  std::vector<glm::dvec2> film(n);
  Pcg32 rng(7, 2);
  for (int k = 0; k < n; ++k) {
    const glm::dvec2 x = kSide * glm::dvec2(centred(rng), centred(rng));
    samples[static_cast<size_t>(k)] = diffraction.sample(
        {rng.uniform(), rng.uniform()}, rng.uniform(), lambda, {x, glm::dvec2(0.5 * kSide)});
    film[static_cast<size_t>(k)] = x + samples[static_cast<size_t>(k)].offset;
  }
  for (int i = 0; i < kWavelengthSamples; ++i) {
    const double lambdaM = static_cast<double>(lambda[i]) * 1e-9;
    for (int step = 0; step <= 10; ++step) {
      const double nu = 0.1 * step, f = nu / (lambdaM * kN);  // cycles per m
      double sum = 0.0;
      for (int k = 0; k < n; ++k)
        sum += static_cast<double>(samples[static_cast<size_t>(k)].weight[i]) *
               std::cos(2.0 * M_PI * f * film[static_cast<size_t>(k)].x);
      const double pixel = f > 0.0 ? std::sin(M_PI * f * kSide) / (M_PI * f * kSide) : 1.0;
      EXPECT_NEAR(sum / n, circularMtf(nu) * pixel, 0.02)
          << "λ = " << lambda[i] << " nm, ν = " << nu;
    }
  }
}

// The same through the camera, as a render draws it (pFilm = the photosite's centre +
// pPhotosite, pixels, y down): 10 × 6 µm pixels at fill 0.5 (photosite 7.07 × 4.24 µm), a
// thin lens at f/8 focused at infinity, so a ray's direction gives the moved film point y
// (z_i·d.xy/d.z, upright). E[w_i cos(2π f·(y − c))] along x and along y is the diffraction
// MTF times the photosite's sinc in that axis, ν = 0.1 … 0.7, within 0.015 (2^18 samples;
// σ ≤ 0.003): a camera that flipped an axis of pPhotosite or took the pixel's sides for the
// photosite's is off by more (checked: a y flip fails the y rows).
TEST(Diffraction, CameraWeightsIntegrateOverItsPhotosite) {
  constexpr double kPitchX = 10e-6, kPitchY = 6e-6, kFill = 0.5, kN = 8.0;
  PhysicalCameraParams p;
  p.resolution = {4, 4};
  p.sensorSize = {4 * kPitchX, 4 * kPitchY};
  p.fillFactor = kFill;
  p.focalLength = 0.2;
  p.fNumber = kN;
  p.aperture = ApertureShape{0, 0.0, true};
  const PhysicalCamera camera(p);
  PhysicalCameraParams off = p;
  off.aperture = ApertureShape{0, 0.0, false};
  const PhysicalCamera geometric(off);
  const glm::ivec2 pixel(1, 2);
  const glm::vec2 centre = glm::vec2(pixel) + 0.5f;
  const double zi = camera.imageDistance();
  // The photosite's centre c, upright film metres (the camera's own mapping of pFilm).
  const glm::dvec2 c((static_cast<double>(centre.x) / 4.0 - 0.5) * p.sensorSize.x,
                     (0.5 - static_cast<double>(centre.y) / 4.0) * p.sensorSize.y);
  const SampledWavelengths lambda = wavelengthsFrom(550.0);
  const float side = static_cast<float>(std::sqrt(kFill));
  CameraSample at;
  at.pFilm = centre;
  const float w0 = geometric.generateRay(at, lambda)->weight[0];
  constexpr int n = 1 << 18;
  std::vector<glm::dvec2> film(n);
  std::vector<SampledSpectrum> weight(n);
  Pcg32 rng(13, 5);
  for (int k = 0; k < n; ++k) {
    CameraSample cs;
    cs.pPhotosite = glm::vec2(rng.uniform() - 0.5f, rng.uniform() - 0.5f) * side;
    cs.pFilm = centre + cs.pPhotosite;
    cs.pDiffraction = {rng.uniform(), rng.uniform()};
    cs.uDiffractionWavelength = rng.uniform();
    const CameraRay r = *camera.generateRay(cs, lambda);
    const glm::dvec3 d(r.ray.d);
    film[static_cast<size_t>(k)] = glm::dvec2(d.x, d.y) / d.z * zi - c;
    weight[static_cast<size_t>(k)] = r.weight / w0;
  }
  for (int i = 0; i < kWavelengthSamples; ++i) {
    const double lambdaM = static_cast<double>(lambda[i]) * 1e-9;
    for (int axis = 0; axis < 2; ++axis) {
      const double a = std::sqrt(kFill) * (axis == 0 ? kPitchX : kPitchY);
      for (const double nu : {0.1, 0.3, 0.5, 0.7}) {
        const double f = nu / (lambdaM * kN);
        double sum = 0.0;
        for (int k = 0; k < n; ++k)
          sum += static_cast<double>(weight[static_cast<size_t>(k)][i]) *
                 std::cos(2.0 * M_PI * f * film[static_cast<size_t>(k)][axis]);
        const double expected = circularMtf(nu) * std::sin(M_PI * f * a) / (M_PI * f * a);
        EXPECT_NEAR(sum / n, expected, 0.015)
            << "λ = " << lambda[i] << " nm, axis " << axis << ", ν = " << nu;
      }
    }
  }
}

// The photosite's weights vary less between a path's wavelengths than the point estimator's:
// the spread (standard deviation of w_i over samples, wavelengths spread over 360–830 nm)
// at f/8 on a 5 µm photosite is under half the point photosite's (measured 0.207 against
// 0.464) — the colour noise diffraction adds.
TEST(Diffraction, PhotositeWeightsSpreadLessThanPointWeights) {
  const Diffraction diffraction(ApertureShape{0, 0.0}, 8.0);
  constexpr double kSide = 5e-6;
  auto spread = [&](bool photosite) {
    Pcg32 rng(9, 4);
    double sum = 0.0, sum2 = 0.0;
    constexpr int n = 1 << 16;
    for (int k = 0; k < n; ++k) {
      const SampledWavelengths lambda = SampledWavelengths::sampleUniform(rng.uniform());
      const glm::dvec2 x = kSide * glm::dvec2(centred(rng), centred(rng));
      const Photosite site = photosite ? Photosite{x, glm::dvec2(0.5 * kSide)} : Photosite{};
      const DiffractionSample s =
          diffraction.sample({rng.uniform(), rng.uniform()}, rng.uniform(), lambda, site);
      for (int i = 0; i < kWavelengthSamples; ++i) {
        sum += static_cast<double>(s.weight[i]);
        sum2 += static_cast<double>(s.weight[i]) * static_cast<double>(s.weight[i]);
      }
    }
    const double m = sum / (n * kWavelengthSamples);
    return std::sqrt(sum2 / (n * kWavelengthSamples) - m * m);
  };
  const double point = spread(false), box = spread(true);
  std::printf("[measured] weight spread at f/8, 5 µm: point %.3f, photosite %.3f\n", point, box);
  EXPECT_LT(box, 0.5 * point);
}

// The stop's rotation turns the spikes with it, in camera axes (x right, y up): a hexagon
// turned by 10° has its edge normals at 40° + 60°k; most offsets between 3 and 64 λN_w lie
// within ±3° of them.
TEST(Diffraction, TurnedStopTurnsItsSpikes) {
  const double rotation = 10.0 * M_PI / 180.0;
  const Diffraction diffraction(ApertureShape{6, rotation}, 8.0);
  const SampledWavelengths lambda = wavelengthsFrom(550.0);
  Pcg32 rng(3, 1);
  int onNormals = 0, onVertices = 0;
  for (int k = 0; k < (1 << 18); ++k) {
    const DiffractionSample s =
        diffraction.sample({rng.uniform(), rng.uniform()}, rng.uniform(), lambda, {});
    const double scale = 550e-9 * 8.0;  // λ₀; the other λ only scale the radius
    const double r = glm::length(s.offset) / scale;
    if (r < 3.0 || r > 64.0) continue;
    const double a = std::atan2(s.offset.y, s.offset.x) * 180.0 / M_PI;
    onNormals += std::abs(std::remainder(a - 40.0, 60.0)) <= 3.0 ? 1 : 0;
    onVertices += std::abs(std::remainder(a - 10.0, 60.0)) <= 3.0 ? 1 : 0;
  }
  EXPECT_GT(onNormals, 8 * onVertices) << onNormals << " vs " << onVertices;
}

}  // namespace diffraction_test
}  // namespace camsim
