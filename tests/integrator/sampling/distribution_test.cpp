// DiscreteDistribution: pmf = w_i / Σw; sample() picks i with that probability, never a
// zero-weight entry (also when u falls exactly on a CDF step), and remaps u to [0, 1)
// within the chosen bucket; the linear count (≤ 8 entries) and the binary search (more)
// pick the same entries.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "integrator/sampling/distribution.h"

namespace camsim {
namespace {

TEST(DiscreteDistribution, PmfIsTheNormalisedWeight) {
  const std::vector<double> w = {1.0, 0.0, 3.0, 4.0};
  const DiscreteDistribution d(w);
  EXPECT_EQ(d.size(), 4u);
  EXPECT_DOUBLE_EQ(d.total(), 8.0);
  EXPECT_FLOAT_EQ(d.pmf(0), 0.125f);
  EXPECT_EQ(d.pmf(1), 0.0f);
  EXPECT_FLOAT_EQ(d.pmf(2), 0.375f);
  EXPECT_FLOAT_EQ(d.pmf(3), 0.5f);
}

// u on a grid of 2^16 points: each entry is picked in proportion to its weight (to the grid's
// resolution), a zero weight never, and the remapped u of each bucket is uniform (mean 1/2).
void expectSamplesFollowWeights(const std::vector<double>& w) {
  const DiscreteDistribution d(w);
  constexpr int kN = 1 << 16;
  std::vector<int> count(w.size(), 0);
  std::vector<double> remappedSum(w.size(), 0.0);
  for (int k = 0; k < kN; ++k) {
    float remapped = -1.0f;
    const size_t i = d.sample((static_cast<float>(k) + 0.5f) / kN, &remapped);
    ASSERT_LT(i, w.size());
    ASSERT_GT(d.pmf(i), 0.0f) << "picked a zero-weight entry at k " << k;
    ASSERT_TRUE(remapped >= 0.0f && remapped < 1.0f) << remapped;
    ++count[i];
    remappedSum[i] += static_cast<double>(remapped);
  }
  for (size_t i = 0; i < w.size(); ++i) {
    EXPECT_NEAR(count[i], kN * d.pmf(i), 1.0) << "entry " << i;
    if (count[i] > 100) {
      EXPECT_NEAR(remappedSum[i] / count[i], 0.5, 0.01) << "entry " << i;
    }
  }
}

TEST(DiscreteDistribution, SamplesFollowTheWeightsFewEntries) {
  expectSamplesFollowWeights({1.0, 0.0, 3.0, 4.0});
  expectSamplesFollowWeights({2.0, 2.0});
  expectSamplesFollowWeights({5.0});
}

// One entry takes a shortcut: the same index and remapped u as the general path (which
// divides by the bucket's width, 1), bit for bit, also at u = 1 and below 0.
TEST(DiscreteDistribution, OneEntryRemapsUAsTheGeneralPath) {
  const DiscreteDistribution one(std::vector<double>{2.5});
  for (const float u : {0.0f, 1e-30f, 0.3f, 0.5f, 0x1.fffffep-1f, 1.0f, -0.25f}) {
    float remapped = -1.0f;
    EXPECT_EQ(one.sample(u, &remapped), 0u);
    const auto uu = static_cast<double>(u);
    EXPECT_EQ(remapped, static_cast<float>(std::clamp(uu / 1.0, 0.0, 0x1.fffffep-1))) << u;
  }
}

TEST(DiscreteDistribution, SamplesFollowTheWeightsManyEntries) {  // the binary search
  std::vector<double> w;
  for (int i = 0; i < 40; ++i) w.push_back(i % 5 == 0 ? 0.0 : 1.0 + i % 3);
  expectSamplesFollowWeights(w);
}

// u on the last CDF step (u = 1, which the samplers never give but a caller may): the
// count, clamped to the last entry, finds the trailing zero-weight entries; sample() must
// step back to the last entry with weight.
TEST(DiscreteDistribution, NeverPicksATrailingZeroWeightEntry) {
  for (const size_t n : {4u, 20u}) {
    std::vector<double> w = {1.0, 1.0};  // CDF steps at 0.5 and 1; entries 2… have no weight
    w.resize(n, 0.0);
    const DiscreteDistribution d(w);
    for (const float u : {0.0f, 0.25f, 0.5f, 0.75f, 0x1.fffffep-1f, 1.0f}) {
      const size_t i = d.sample(u);
      EXPECT_LT(i, 2u) << "n " << n << " u " << u;
      EXPECT_EQ(i, u < 0.5f ? 0u : 1u) << "n " << n << " u " << u;
    }
    std::vector<double> back(n - 1, 1.0);
    back.push_back(0.0);  // the last entry has none: u near 1 picks the one before
    EXPECT_EQ(DiscreteDistribution(back).sample(1.0f), n - 2) << n;
  }
}

}  // namespace
}  // namespace camsim
