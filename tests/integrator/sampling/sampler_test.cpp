// IndependentSampler: numbers depend only on (seed, pixel, sample index, dimension); every
// draw takes one dimension (a 2D draw is one hash, split in two 24-bit numbers); the numbers
// are uniform on [0, 1) and the two of a pair are uncorrelated.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "integrator/sampling/sampler.h"
#include "tests/integrator/sampler_contract.h"

namespace camsim {
namespace {

TEST(IndependentSampler, NumbersDependOnlyOnPixelSampleAndDimension) {  // sampler_contract.h
  IndependentSampler a(4), b(4), other(5);
  expectNumbersDependOnlyOnPixelSampleAndDimension(a, b, other);
}

TEST(IndependentSampler, EveryDrawTakesOneDimension) {  // sampler_contract.h
  IndependentSampler a(2), b(2);
  expectEveryDrawTakesOneDimension(a, b);
}

// 2^16 pairs: each coordinate's mean (σ = 1/√(12·65536) ≈ 0.0011) within 0.005 of 1/2, its
// variance within 0.005 of 1/12, every one of 16 × 16 cells holds 256 ± 64 pairs (σ ≈ 16),
// and the correlation of x and y (σ ≈ 0.004) is below 0.02.
TEST(IndependentSampler, PairsAreUniformAndUncorrelated) {
  IndependentSampler s(11);
  constexpr int kN = 1 << 16;
  double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  std::vector<int> cells(256, 0);
  for (int i = 0; i < kN; ++i) {
    s.startPixelSample({i % 256, i / 256}, 0);
    s.setDimension(kDimPath);
    const glm::vec2 p = s.get2D();
    ASSERT_TRUE(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f) << i;
    const double x = p.x, y = p.y;
    sx += x;
    sy += y;
    sxx += x * x;
    syy += y * y;
    sxy += x * y;
    ++cells[static_cast<size_t>(static_cast<int>(x * 16) * 16 + static_cast<int>(y * 16))];
  }
  const double mx = sx / kN, my = sy / kN;
  const double vx = sxx / kN - mx * mx, vy = syy / kN - my * my;
  EXPECT_NEAR(mx, 0.5, 0.005);
  EXPECT_NEAR(my, 0.5, 0.005);
  EXPECT_NEAR(vx, 1.0 / 12.0, 0.005);
  EXPECT_NEAR(vy, 1.0 / 12.0, 0.005);
  EXPECT_LT(std::abs((sxy / kN - mx * my) / std::sqrt(vx * vy)), 0.02);
  for (int c = 0; c < 256; ++c) EXPECT_NEAR(cells[static_cast<size_t>(c)], 256, 64) << c;
}

}  // namespace
}  // namespace camsim
