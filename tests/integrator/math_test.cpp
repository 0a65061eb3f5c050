// Tests for integrator/math.h: nextFloatToward against std::nextafter (the reference it
// replaces) over zeros, denormals, normal numbers of both signs, the largest finite values
// and infinities; direction 0 leaves v unchanged; the Float4 form gives the scalar bits in
// every lane. erfInv against std::erf.
#include "integrator/math.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace camsim {
namespace {

TEST(Math, NextFloatTowardMatchesNextafter) {
  using L = std::numeric_limits<float>;
  const float values[] = {
      0.0f, -0.0f,    L::denorm_min(), -L::denorm_min(), L::min(), -L::min(), 1.0f, -1.0f,
      0.3f, -1234.5f, 1e30f,           -1e-30f,          L::max(), -L::max()};
  const auto bits = [](float x) { return std::bit_cast<std::uint32_t>(x); };
  for (float v : values) {
    // Bit patterns (EXPECT_EQ would take −0 for +0), except the documented difference:
    // −2⁻¹⁴⁹ stepped up gives +0, std::nextafter −0.
    const float up = std::nextafter(v, L::infinity());
    EXPECT_EQ(bits(nextFloatToward(v, 1.0f)), bits(v == -L::denorm_min() ? 0.0f : up)) << v;
    EXPECT_EQ(bits(nextFloatToward(v, -2.5f)), bits(std::nextafter(v, -L::infinity()))) << v;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(nextFloatToward(v, 0.0f)),
              std::bit_cast<std::uint32_t>(v))
        << v;
  }
  EXPECT_EQ(nextFloatToward(L::infinity(), -1.0f), L::infinity());  // documented: ±∞ stay
  EXPECT_EQ(nextFloatToward(-L::infinity(), 1.0f), -L::infinity());
}

// offsetRayOrigin steps its three components as one Float4: each lane must be the scalar
// function's bits, for every value above and each direction (up, down, none).
TEST(Math, NextFloatTowardOnFourLanesGivesTheScalarBits) {
  using L = std::numeric_limits<float>;
  const float values[] = {0.0f,
                          -0.0f,
                          L::denorm_min(),
                          -L::denorm_min(),
                          L::min(),
                          -L::min(),
                          1.0f,
                          -1.0f,
                          0.3f,
                          -1234.5f,
                          1e30f,
                          -1e-30f,
                          L::max(),
                          -L::max(),
                          L::infinity(),
                          -L::infinity()};
  const float directions[] = {1.0f, -2.5f, 0.0f, -0.0f};
  for (const float a : values) {
    for (const float b : values) {
      for (const float da : directions) {
        for (const float db : directions) {
          const Float4 v = {a, b, b, a}, direction = {da, db, da, db};
          const Float4 got = nextFloatToward(v, direction);
          for (int i = 0; i < 4; ++i)
            ASSERT_EQ(std::bit_cast<std::uint32_t>(got[i]),
                      std::bit_cast<std::uint32_t>(nextFloatToward(v[i], direction[i])))
                << "lane " << i << " v = " << v[i] << " direction = " << direction[i];
        }
      }
    }
  }
}

// erf(erfInv(x)) = x over (−1, 1) to within single-precision rounding of the result
// (|Δx| ≤ erf′(y)·|y|·4e-7), odd, and finite up to 1 ∓ 1e-7.
TEST(Math, ErfInvInvertsErf) {
  double worst = 0.0;
  for (int i = -99999; i <= 99999; ++i) {
    const float x = static_cast<float>(i) * 1e-5f;
    const double y = erfInv(x);
    const double slope = 2.0 / std::sqrt(M_PI) * std::exp(-y * y);
    const double error = std::abs(std::erf(y) - static_cast<double>(x));
    worst = std::max(worst, error);
    ASSERT_LE(error, slope * std::abs(y) * 4e-7 + 1e-12) << x;
    ASSERT_EQ(erfInv(-x), -erfInv(x)) << x;
  }
  EXPECT_LT(worst, 2e-7);
  EXPECT_EQ(erfInv(1.0f), std::numeric_limits<float>::infinity());
  EXPECT_EQ(erfInv(-1.0f), -std::numeric_limits<float>::infinity());
  for (float x : {1.0f - 1e-7f, 1.0f - 1e-6f}) {
    const double y = erfInv(x);
    EXPECT_TRUE(std::isfinite(y));
    EXPECT_NEAR(std::erfc(y), 1.0 - static_cast<double>(x), 1e-3 * (1.0 - static_cast<double>(x)));
  }
}

}  // namespace
}  // namespace camsim
