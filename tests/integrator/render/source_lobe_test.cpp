// The guide's source lobe (integrator/render/source_lobe.h): the vMF density integrates to
// one and its samples follow it; the moments give the weighted centroid and spread; the
// lobe at a point looks at the centroid with κ = 3d²/σ² and is absent near the cloud.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "integrator/render/source_lobe.h"

namespace camsim::source_lobe_test {
namespace {

// ∫ p dω over the sphere: p depends on t = μ·ω only, so ∫ 2π p(t) dt over [−1, 1], midpoint
// rule in t on a grid fine enough for the lobe's width 1/κ (10⁶ cells).
TEST(SourceLobe, VmfPdfIntegratesToOne) {
  for (const float kappa : {0.01f, 1.0f, 40.0f, 3000.0f}) {
    const VmfLobe lobe{glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f)), kappa};
    const glm::vec3 a = glm::normalize(glm::cross(lobe.mu, glm::vec3(1.0f, 0.0f, 0.0f)));
    constexpr int n = 1000000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double t = -1.0 + (i + 0.5) * 2.0 / n;
      const glm::vec3 w = static_cast<float>(t) * lobe.mu +
                          static_cast<float>(std::sqrt(std::max(0.0, 1.0 - t * t))) * a;
      sum += 2.0 * 3.14159265358979 * static_cast<double>(lobe.pdf(glm::normalize(w))) * 2.0 / n;
    }
    EXPECT_NEAR(sum, 1.0, 2e-3) << "kappa " << kappa;
  }
}

// Samples: unit, the pdf they report is pdf(w), and the mean of μ·ω is the vMF's,
// coth κ − 1/κ, within 5 standard errors (200 000 samples, fixed seed).
TEST(SourceLobe, VmfSamplesFollowThePdf) {
  std::mt19937 rng(7);
  const auto uniform = [&] { return static_cast<float>(rng() >> 8) * 0x1p-24f; };
  for (const float kappa : {0.5f, 8.0f, 500.0f}) {
    const VmfLobe lobe{glm::normalize(glm::vec3(-0.2f, 0.9f, 0.1f)), kappa};
    constexpr int n = 200000;
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < n; ++i) {
      float pdf = 0.0f;
      const glm::vec3 w = lobe.sample({uniform(), uniform()}, &pdf);
      ASSERT_NEAR(glm::length(w), 1.0f, 1e-5f);
      ASSERT_NEAR(pdf, lobe.pdf(w), 1e-4f * lobe.pdf(w));
      const double t = glm::dot(lobe.mu, w);
      sum += t;
      sum2 += t * t;
    }
    const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
    const double k = kappa, expected = 1.0 / std::tanh(k) - 1.0 / k;
    EXPECT_NEAR(mean, expected, 5.0 * sd / std::sqrt(double{n})) << "kappa " << kappa;
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
