// The guide's source lobe (integrator/render/source_lobe.h): the vMF density integrates to
// one and its samples follow it (κ from 4, the least the renderer uses, to the cap 10⁵); the moments give the weighted centroid and spread; the
// lobe at a point looks at the centroid with κ = 3d²/σ² and is absent near the cloud.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

#include "integrator/render/source_lobe.h"

namespace camsim::source_lobe_test {
namespace {

// ∫ p dω over the sphere: p depends on s = 1 − μ·ω only, so 2π ∫ p ds over [0, 2], the
// midpoint rule in log s from 10⁻¹² (10⁶ cells: the lobe's width 1/κ is resolved at every
// κ the renderer uses, 4 … 10⁵). Tolerance 10⁻³: the quadrature's own error is < 10⁻⁴.
TEST(SourceLobe, VmfPdfIntegratesToOne) {
  for (const float kappa : {4.0f, 40.0f, 1200.0f, SourceLobe::kMaxKappa}) {
    const VmfLobe lobe{glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f)), kappa};
    const glm::vec3 a = glm::normalize(glm::cross(lobe.mu, glm::vec3(1.0f, 0.0f, 0.0f)));
    constexpr int n = 1000000;
    const double lo = std::log(1e-12), hi = std::log(2.0);
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double l0 = lo + (hi - lo) * i / n, l1 = lo + (hi - lo) * (i + 1) / n;
      const double sMid = std::exp(0.5 * (l0 + l1)), ds = std::exp(l1) - std::exp(l0);
      const double t = 1.0 - sMid, sinT = std::sqrt(std::max(0.0, 1.0 - t * t));
      const glm::vec3 w =
          glm::normalize(static_cast<float>(t) * lobe.mu + static_cast<float>(sinT) * a);
      sum += 2.0 * std::numbers::pi * static_cast<double>(lobe.pdf(w)) * ds;
    }
    EXPECT_NEAR(sum, 1.0, 1e-3) << "kappa " << kappa;
  }
}

// Samples (200 000 per κ, fixed seed) are unit vectors with a positive, finite reported
// pdf; their mean is (coth κ − 1/κ)·μ, each component within 5 standard errors (a wrong
// frame or φ moves the perpendicular components); and s = 1 − μ·ω follows its CDF
// (1 − e^(−κs))/(1 − e^(−2κ)): the share below each of its deciles within 5 σ of 0.1·k.
TEST(SourceLobe, VmfSamplesFollowThePdf) {
  std::mt19937 rng(7);
  const auto uniform = [&] { return static_cast<float>(rng() >> 8) * 0x1p-24f; };
  for (const float kappa : {4.0f, 40.0f, 1200.0f, SourceLobe::kMaxKappa}) {
    const VmfLobe lobe{glm::normalize(glm::vec3(-0.2f, 0.9f, 0.1f)), kappa};
    constexpr int n = 200000;
    glm::dvec3 sum(0.0), sum2(0.0);
    int below[9] = {};
    const double k = kappa;
    for (int i = 0; i < n; ++i) {
      float pdf = 0.0f;
      const glm::vec3 w = lobe.sample({uniform(), uniform()}, &pdf);
      ASSERT_NEAR(glm::length(w), 1.0f, 1e-5f);
      ASSERT_TRUE(pdf > 0.0f && std::isfinite(pdf));
      const glm::dvec3 wd(w);
      sum += wd;
      sum2 += wd * wd;
      // s from |ω − μ|²/2: no cancellation at large κ.
      const glm::dvec3 d = wd - glm::dvec3(lobe.mu);
      const double sv = 0.5 * glm::dot(d, d);
      for (int q = 1; q <= 9; ++q) {  // the decile: s with CDF q/10
        const double sq = -std::log1p(-0.1 * q * -std::expm1(-2.0 * k)) / k;
        if (sv < sq) ++below[q - 1];
      }
    }
    const double mean = 1.0 / std::tanh(k) - 1.0 / k;
    for (int c = 0; c < 3; ++c) {
      const double m = sum[c] / n, sd = std::sqrt(std::max(sum2[c] / n - m * m, 1e-18));
      EXPECT_NEAR(m, mean * static_cast<double>(lobe.mu[c]), 5.0 * sd / std::sqrt(double{n}))
          << "kappa " << kappa << ", component " << c;
    }
    for (int q = 1; q <= 9; ++q) {
      const double p = 0.1 * q;
      EXPECT_NEAR(below[q - 1] / double{n}, p, 5.0 * std::sqrt(p * (1.0 - p) / n))
          << "kappa " << kappa << ", decile " << q;
    }
  }
}

// Two points, weights 1 and 3: c = (q₀ + 3q₁)/4, σ² = Σw|q − c|²/Σw = 3/16 |q₁ − q₀|²; the
// weights 0, negative and NaN are left out.
TEST(SourceLobe, MomentsGiveTheWeightedCentroidAndSpread) {
  SourceMoments m;
  const glm::vec3 q0(1.0f, 2.0f, 3.0f), q1(1.0f, 2.0f, 3.4f);
  m.add(q0, 1.0f);
  m.add(q1, 3.0f);
  m.add({100.0f, 0.0f, 0.0f}, 0.0f);
  m.add({100.0f, 0.0f, 0.0f}, -1.0f);
  m.add({100.0f, 0.0f, 0.0f}, std::nanf(""));
  const SourceLobe lobe = SourceLobe::fit(m);
  EXPECT_NEAR(glm::length(lobe.centre - glm::vec3(1.0f, 2.0f, 3.3f)), 0.0f, 1e-6f);
  EXPECT_NEAR(lobe.spread2, 3.0f / 16.0f * 0.16f, 1e-6f);
  EXPECT_EQ(SourceLobe::fit(SourceMoments()).spread2, 0.0f);  // no records: no lobe
}

// At x 2 m from a cloud of σ² = 0.01 m²: μ towards it, κ = 3·4/0.01 = 1200; near the
// cloud (κ < 4: d < 11.5 cm) and without records, none.
TEST(SourceLobe, LooksAtTheCloudFromAfar) {
  SourceLobe lobe;
  lobe.centre = {0.0f, 2.0f, 0.0f};
  lobe.spread2 = 0.01f;
  const VmfLobe far = lobe.at({0.0f, 0.0f, 0.0f});
  EXPECT_NEAR(far.kappa, 1200.0f, 0.01f);
  EXPECT_NEAR(far.mu.y, 1.0f, 1e-6f);
  EXPECT_EQ(lobe.at({0.0f, 1.9f, 0.0f}).kappa, 0.0f);
  EXPECT_EQ(SourceLobe().at({0.0f, 0.0f, 0.0f}).kappa, 0.0f);
  lobe.spread2 = SourceLobe::kMinSpread;  // a point source: κ capped
  EXPECT_EQ(lobe.at({0.0f, 0.0f, 0.0f}).kappa, SourceLobe::kMaxKappa);
}

}  // namespace
}  // namespace camsim::source_lobe_test
