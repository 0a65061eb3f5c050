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

}  // namespace
}  // namespace camsim
