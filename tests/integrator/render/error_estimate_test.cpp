// A render's estimate of its own error (error_estimate.h) and the passes it drives
// (render.h): the estimator against Gaussian pixels of known variance, the estimate of a
// Cornell box render against its error to a converged reference, and passes that stop at a
// target error on the same spp for any thread count, bit for bit the render at that spp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "integrator/measure/bench_metrics.h"
#include "integrator/render/error_estimate.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"

namespace camsim::error_estimate_test {
namespace {

// Pixels of mean μ (1 … 3 down the 200 × 100 image, row by row) with Gaussian samples of
// σ = 0.2 μ: the exact
// rMSE of an n-sample mean is (σ/μ)²/n up to ε (1 % of the mean: a 1e-4 relative change),
// its MRAE √(2/π)·(σ/μ)/√n. 20 000 pixels: the estimates' relative standard errors are
// about √(2/20000) = 1 % (rMSE) and 0.5 % (MRAE); the tolerances are 5 %.
TEST(ErrorEstimate, MatchesTheErrorOfGaussianPixels) {
  for (int n : {2, 5, 16}) {
    constexpr std::size_t kPixels = 20000;
    std::mt19937_64 rng(17 + static_cast<unsigned>(n));
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::vector<double> all(kPixels), odd(kPixels);
    double exactRmse = 0.0;
    for (std::size_t i = 0; i < kPixels; ++i) {
      const double mu = 1.0 + 2.0 * static_cast<double>(i) / kPixels, sigma = 0.2 * mu;
      for (int s = 0; s < n; ++s) {
        const double v = mu + sigma * gauss(rng);
        all[i] += v;
        if (s % 2 == 1) odd[i] += v;
      }
      exactRmse += 0.04 / n / kPixels;
    }
    std::vector<float> means(kPixels), oddMeans(kPixels);  // as the film writes them
    for (std::size_t i = 0; i < kPixels; ++i) {
      means[i] = static_cast<float>(all[i] / n);
      oddMeans[i] = static_cast<float>(odd[i] / (n / 2));
    }
    const ErrorMetrics e = estimateFromHalves(means.data(), 1, oddMeans.data(), 200, 100, n);
    EXPECT_NEAR(e.rmse / exactRmse, 1.0, 0.05) << n << " samples";
    const double exactMrae = std::sqrt(2.0 / M_PI) * 0.2 / std::sqrt(n);
    EXPECT_NEAR(e.mrae / exactMrae, 1.0, 0.05) << n << " samples";
  }
}

// Pixels carried by rare bright paths: each sample is t + 0.1 t·(Gaussian) plus, with
// probability p = 0.02, a hit of H = 50 (r = t + pH). At 4 and 16 spp most pixels hold no
// hit, so their 3×3 median is about t, not r: with t = 1 (half of r from hits) that
// denominator made the rMSE estimate 3.3–3.9× the image's true rMSE; with t = 0.2 (83 %
// from hits) the MRAE estimate 2.9× its true MRAE (a NumPy model of the rule before
// the rare part). The truth is this image's error against the exact r. Tolerances: the
// issue's factor 1.5 in both (rMSE at t = 1: measured 0.79 and 1.09 at 4 and 16 spp; MRAE at
// t = 0.2: 0.81 and 0.96). With hits in 8 % of the pixels at 4 spp the cluster window
// (error_estimate.h) fires in places and lifts r̂: the fixed windows measured 1.11, 1.17 and
// 1.06, 1.15 here; a rule that fired only where hits are denser than around them centred
// these but pushed dof_chart's rMSE estimate to 2–3× (docs/performance.md).
TEST(ErrorEstimate, MatchesTheErrorOfPixelsCarriedByRarePaths) {
  constexpr int kWidth = 200, kHeight = 100;
  constexpr std::size_t kPixels = static_cast<std::size_t>(kWidth) * kHeight;
  constexpr double kHit = 50.0, kP = 0.02;
  for (const double typical : {1.0, 0.2})
    for (int n : {4, 16}) {
      std::mt19937_64 rng(29 + static_cast<unsigned>(n));
      std::normal_distribution<double> gauss(0.0, 1.0);
      std::uniform_real_distribution<double> uniform(0.0, 1.0);
      std::vector<float> means(kPixels), oddMeans(kPixels);
      const double r = typical + kP * kHit;
      double sumSq = 0.0, sumAbs = 0.0;
      for (std::size_t i = 0; i < kPixels; ++i) {
        double all = 0.0, odd = 0.0;
        for (int s = 0; s < n; ++s) {
          const double v = typical * (1.0 + 0.1 * gauss(rng)) + (uniform(rng) < kP ? kHit : 0.0);
          all += v;
          if (s % 2 == 1) odd += v;
        }
        means[i] = static_cast<float>(all / n);
        oddMeans[i] = static_cast<float>(odd / (n / 2));
      }
      const double eps = 0.01 * r;
      for (std::size_t i = 0; i < kPixels; ++i) {
        const double e = static_cast<double>(means[i]) - r;
        sumSq += e * e / (r * r + eps * eps);
        sumAbs += std::abs(e) / (r + eps);
      }
      const double trueRmse = sumSq / kPixels, trueMrae = sumAbs / kPixels;
      const ErrorMetrics est =
          estimateFromHalves(means.data(), 1, oddMeans.data(), kWidth, kHeight, n);
      const std::string what = "t " + std::to_string(typical) + ", " + std::to_string(n) + " spp";
      if (typical == 1.0) {
        EXPECT_GT(est.rmse / trueRmse, 1.0 / 1.5) << what;
        EXPECT_LT(est.rmse / trueRmse, 1.5) << what;
      } else {
        EXPECT_GT(est.mrae / trueMrae, 1.0 / 1.5) << what;
        EXPECT_LT(est.mrae / trueMrae, 1.5) << what;
      }
    }
}

// Rare paths in clusters with sharp edges: ten discs of radius 6 px (a lamp's bokeh seen
// through a defocused lens, dof_chart) where a sample is, with probability p = 0.02, a hit
// of H = 1000 over a background t = 1 with 10 % Gaussian noise (r = t + pH inside, t
// outside); 0.32 and 1.28 hits per disc pixel at 16 and 64 spp. The fixed windows alone
// (the 15 × 15 rare share, the 7 × 7 missed share) spread the discs' share over the dark
// around them: MRAE 2.64× and 3.43× the truth, rMSE 8.6× and 26.5× (measured before the
// cluster rules of error_estimate.h). With them: MRAE within the factor 1.5
// (measured 1.11, 1.35); rMSE within a factor 4 (measured 2.5, 3.2: the discs' edge pixels
// carry it, half of whose neighbours are dark, and a hit of 1000 over r = 21 makes their
// error large), a bound the fixed windows fail by 2–7×.
TEST(ErrorEstimate, MatchesTheErrorOfClustersOfRarePaths) {
  constexpr int kWidth = 200, kHeight = 100, kRadius = 6;
  constexpr std::size_t kPixels = static_cast<std::size_t>(kWidth) * kHeight;
  constexpr double kHit = 1000.0, kP = 0.02, kTypical = 1.0;
  auto inDisc = [&](int x, int y) {
    const int dx = x % 40 - 20, dy = y % 50 - 25;  // centres (20 + 40 i, 25 + 50 j)
    return dx * dx + dy * dy <= kRadius * kRadius;
  };
  for (int n : {16, 64}) {
    std::mt19937_64 rng(41 + static_cast<unsigned>(n));
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::vector<float> means(kPixels), oddMeans(kPixels);
    double sumSq = 0.0, sumAbs = 0.0, refSum = 0.0;
    std::vector<double> reference(kPixels);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * kWidth + static_cast<std::size_t>(x);
        const bool disc = inDisc(x, y);
        double all = 0.0, odd = 0.0;
        for (int s = 0; s < n; ++s) {
          const double v =
              kTypical * (1.0 + 0.1 * gauss(rng)) + (disc && uniform(rng) < kP ? kHit : 0.0);
          all += v;
          if (s % 2 == 1) odd += v;
        }
        means[i] = static_cast<float>(all / n);
        oddMeans[i] = static_cast<float>(odd / (n / 2));
        reference[i] = kTypical + (disc ? kP * kHit : 0.0);
        refSum += reference[i];
      }
    const double eps = 0.01 * refSum / kPixels;
    for (std::size_t i = 0; i < kPixels; ++i) {
      const double e = static_cast<double>(means[i]) - reference[i];
      sumSq += e * e / (reference[i] * reference[i] + eps * eps);
      sumAbs += std::abs(e) / (reference[i] + eps);
    }
    const double trueRmse = sumSq / kPixels, trueMrae = sumAbs / kPixels;
    const ErrorMetrics est =
        estimateFromHalves(means.data(), 1, oddMeans.data(), kWidth, kHeight, n);
    const std::string what = std::to_string(n) + " spp: rMSE " +
                             std::to_string(est.rmse / trueRmse) + ", MRAE " +
                             std::to_string(est.mrae / trueMrae);
    EXPECT_GT(est.mrae / trueMrae, 1.0 / 1.5) << what;
    EXPECT_LT(est.mrae / trueMrae, 1.5) << what;
    EXPECT_GT(est.rmse / trueRmse, 1.0 / 4.0) << what;
    EXPECT_LT(est.rmse / trueRmse, 4.0) << what;
  }
}

SceneDescription smallCornell() {
  SceneDescription d =
      loadScene(std::filesystem::path(CAMSIM_SOURCE_DIR) / "scenes/cornell_box.yaml");
  d.camera.resolution = {48, 48};
  return d;
}

RenderResult renderXyz(const Scene& scene, RenderOptions options) {
  static const SpectralResponse xyz = SpectralResponse::cieXyz();
  return render(scene, xyz, options);
}

Image luminance(const Image& xyz) {
  Image y(xyz.width, xyz.height, {"Y"});
  const int c = xyz.channelIndex("Y");
  for (int j = 0; j < xyz.height; ++j)
    for (int i = 0; i < xyz.width; ++i) y.at(i, j, 0) = xyz.at(i, j, c);
  return y;
}

// The estimate of 16- and 64-spp renders (both samplers) against the error to a 4096-spp
// reference (two 2048-spp halves: the reference's own noise, ≈ 1/64 of a 64-spp render's,
// is taken out as the bench does): within a factor 1.5 (the bound), MRAE at both,
// rMSE at 64 spp. (At 16 spp one 48² render's rMSE is itself a wild draw — a few pixels'
// rare bright paths carry it: two seeds' true rMSE differ by 30 % — and the estimate was
// 0.97× and 0.45× of it for the two samplers; measured at 128 px in the bench table.)
// Measured with the cluster rules (error_estimate.h): rMSE ratios at 64 spp 0.88
// (independent), 0.85 (Sobol'); MRAE 0.90, 0.90 (independent, 16 and 64 spp), 0.85, 0.91.
TEST(ErrorEstimate, EstimatesTheRendersErrorAgainstAConvergedReference) {
  const Scene scene(smallCornell());
  RenderOptions o;
  o.seed = 1000;
  o.spp = 2048;
  const Image a = luminance(renderXyz(scene, o).image);
  o.seed = 1001;
  const Image b = luminance(renderXyz(scene, o).image);
  Image reference = a;
  for (std::size_t i = 0; i < reference.pixels.size(); ++i)
    reference.pixels[i] = 0.5f * (a.pixels[i] + b.pixels[i]);
  const ErrorMetrics floor = referenceNoise(a, b, 0);
  for (const SamplerKind kind : {SamplerKind::kIndependent, SamplerKind::kSobol})
    for (int spp : {16, 64}) {
      RenderOptions r;
      r.spp = spp;
      r.seed = 3;
      r.sampler = kind;
      const RenderResult result = renderXyz(scene, r);
      ASSERT_TRUE(result.stats.estimatedError.has_value());
      EXPECT_EQ(result.stats.estimatedError->channel, "Y");
      BenchRow row;
      row.error = compareImages(luminance(result.image), reference, 0);
      row.floor = floor;
      const ErrorMetrics truth = errorBeyondFloor(row);
      const ErrorMetrics est = result.stats.estimatedError->error;
      const std::string what = std::string(samplerName(kind)) + " " + std::to_string(spp) + " spp";
      EXPECT_GT(est.mrae / truth.mrae, 1.0 / 1.5) << what;
      EXPECT_LT(est.mrae / truth.mrae, 1.5) << what;
      if (spp < 64) continue;
      EXPECT_GT(est.rmse / truth.rmse, 1.0 / 1.5) << what;
      EXPECT_LT(est.rmse / truth.rmse, 1.5) << what;
    }
}

bool sameImage(const Image& a, const Image& b) {
  return a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

// A target error: the passes stop at the same spp on 1 and 2 threads, at an estimate no
// above the target, after a pass whose predecessor was above it; the image is bit for bit a
// one-pass render at that spp.
TEST(RenderPasses, StopAtTheTargetErrorOnTheSameSppForAnyThreadCount) {
  const Scene scene(smallCornell());
  RenderOptions o;
  o.spp = 4;
  o.seed = 9;
  o.targetError = 0.08;
  o.threads = 1;
  const RenderResult one = renderXyz(scene, o);
  o.threads = 2;
  const RenderResult two = renderXyz(scene, o);
  EXPECT_EQ(one.stats.stop, RenderStop::kTargetError);
  EXPECT_EQ(one.stats.spp, two.stats.spp);
  EXPECT_GT(one.stats.passes, 1);
  EXPECT_TRUE(sameImage(one.image, two.image));
  ASSERT_TRUE(one.stats.estimatedError.has_value());
  EXPECT_LE(one.stats.estimatedError->error.mrae, 0.08);
  // Pass totals are the first pass's spp times powers of two.
  EXPECT_EQ(one.stats.spp % 4, 0);
  EXPECT_EQ(__builtin_popcount(static_cast<unsigned>(one.stats.spp / 4)), 1);

  RenderOptions plain;
  plain.spp = one.stats.spp;
  plain.seed = 9;
  const RenderResult direct = renderXyz(scene, plain);
  EXPECT_EQ(direct.stats.passes, 1);
  EXPECT_TRUE(sameImage(one.image, direct.image));
  EXPECT_EQ(direct.stats.estimatedError->error.mrae, one.stats.estimatedError->error.mrae);
  // Half the samples were not enough.
  plain.spp = one.stats.spp / 2;
  EXPECT_GT(renderXyz(scene, plain).stats.estimatedError->error.mrae, 0.08);
}

// max_spp caps the passes; a time limit stops them (here before a second pass can fit in
// a microsecond), and the image is still a one-pass render at its spp.
TEST(RenderPasses, StopAtMaxSppAndAtTheTimeLimit) {
  const Scene scene(smallCornell());
  RenderOptions o;
  o.spp = 2;
  o.targetError = 1e-6;
  o.maxSpp = 12;
  const RenderResult capped = renderXyz(scene, o);
  EXPECT_EQ(capped.stats.stop, RenderStop::kMaxSpp);
  EXPECT_EQ(capped.stats.spp, 12);  // 2 → 8 (4× as the estimate is far off) → 12

  RenderOptions t;
  t.spp = 2;
  t.timeLimitS = 1e-6;
  const RenderResult timed = renderXyz(scene, t);
  EXPECT_EQ(timed.stats.stop, RenderStop::kTimeLimit);
  EXPECT_EQ(timed.stats.passes, 1);
  EXPECT_EQ(timed.stats.spp, 2);
}

// One sample per pixel: no estimate (it needs both halves); nor for a share of the tiles.
TEST(ErrorEstimate, NoneBelowTwoSppOrForAShare) {
  const Scene scene(smallCornell());
  RenderOptions o;
  o.spp = 1;
  EXPECT_FALSE(renderXyz(scene, o).stats.estimatedError.has_value());
  o.spp = 4;
  o.tiles = Share{0, 2};
  EXPECT_FALSE(renderXyz(scene, o).stats.estimatedError.has_value());
}

// A black image (every sample 0: a scene whose lights are off) has no error: 0, not the
// 0/0 = NaN that ε = 1 % of a zero mean gave ("-nan" in the EXR header; found by probing).
// One lit pixel among black ones still counts.
TEST(ErrorEstimate, ABlackImageHasNoError) {
  const std::vector<float> zeros(64, 0.0f);
  const ErrorMetrics black = estimateFromHalves(zeros.data(), 1, zeros.data(), 8, 8, 4);
  EXPECT_EQ(black.rmse, 0.0);
  EXPECT_EQ(black.mrae, 0.0);
  std::vector<float> means = zeros, odd = zeros;
  means[5] = 1.0f;
  odd[5] = 0.5f;
  const ErrorMetrics one = estimateFromHalves(means.data(), 1, odd.data(), 8, 8, 4);
  EXPECT_TRUE(std::isfinite(one.rmse) && one.rmse > 0.0) << one.rmse;
  EXPECT_TRUE(std::isfinite(one.mrae) && one.mrae > 0.0) << one.mrae;
}

}  // namespace
}  // namespace camsim::error_estimate_test
