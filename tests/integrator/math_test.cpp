// Tests for integrator/math.h: nextFloatToward against std::nextafter (the reference it
// replaces) over zeros, denormals, normal numbers of both signs, the largest finite values
// and infinities; direction 0 leaves v unchanged.
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
  for (float v : values) {
    EXPECT_EQ(nextFloatToward(v, 1.0f), std::nextafter(v, L::infinity())) << v;
    EXPECT_EQ(nextFloatToward(v, -2.5f), std::nextafter(v, -L::infinity())) << v;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(nextFloatToward(v, 0.0f)),
              std::bit_cast<std::uint32_t>(v))
        << v;
  }
  EXPECT_EQ(nextFloatToward(L::infinity(), -1.0f), L::infinity());  // documented: ±∞ stay
  EXPECT_EQ(nextFloatToward(-L::infinity(), 1.0f), -L::infinity());
}

}  // namespace
}  // namespace camsim
