// Tests for sensor/base/float_math.h against double-precision libm: logOfNormal over the whole
// normal range (and densely where the wavelength sampler uses it), sinCosQuarterPi over
// [−π/4, π/4]. Errors in units in the last place of the float result (ulp), with an
// absolute floor where the result crosses zero (ln x near x = 1, sin x near 0). The Float4
// form of logOfNormal gives, lane by lane, the scalar form's bits.
#include "sensor/base/float_math.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace camsim {
namespace {

// |got − exact| in ulps of the float nearest to exact; below `floor` absolute counts as 0.
double ulpError(float got, double exact, double floor) {
  const double diff = std::abs(static_cast<double>(got) - exact);
  if (diff <= floor) return 0.0;
  const auto e = static_cast<float>(exact);
  const double ulp = static_cast<double>(
      std::nextafter(std::abs(e), std::numeric_limits<float>::infinity()) - std::abs(e));
  return diff / ulp;
}

TEST(FloatMath, LogOfNormalIsWithinTwoUlpOfLibm) {
  double worst = 0.0, worstAt = 0.0;
  auto check = [&](float x) {
    const double err = ulpError(logOfNormal(x), std::log(static_cast<double>(x)), 1.5e-7);
    if (err > worst) {
      worst = err;
      worstAt = static_cast<double>(x);
    }
  };
  for (float x = std::numeric_limits<float>::min(); x < 3.4e38f; x *= 1.001f) check(x);
  check(std::numeric_limits<float>::max());
  for (int i = 0; i <= 2000000; ++i) check(0.05f + 100.0f * static_cast<float>(i) / 2e6f);
  for (int i = -100000; i <= 100000; ++i) check(1.0f + static_cast<float>(i) * 1e-7f);
  EXPECT_LE(worst, 2.0) << "at x = " << worstAt;
  EXPECT_EQ(logOfNormal(1.0f), 0.0f);
  EXPECT_NEAR(logOfNormal(2.0f), 0.69314718f, 1e-7f);
}

TEST(FloatMath, SinCosQuarterPiIsWithinOneUlp) {
  double worstSin = 0.0, worstCos = 0.0;
  const double quarterPi = M_PI / 4.0;
  for (int i = -1000000; i <= 1000000; ++i) {
    const auto x = static_cast<float>(quarterPi * i / 1e6);
    const SinCos sc = sinCosQuarterPi(x);
    worstSin = std::max(worstSin, ulpError(sc.sin, std::sin(static_cast<double>(x)), 0.0));
    worstCos = std::max(worstCos, ulpError(sc.cos, std::cos(static_cast<double>(x)), 0.0));
  }
  EXPECT_LE(worstSin, 1.0);  // measured 0.70 and 0.98 (Horner's order: 1.12)
  EXPECT_LE(worstCos, 1.0);
  EXPECT_EQ(sinCosQuarterPi(0.0f).sin, 0.0f);
  EXPECT_EQ(sinCosQuarterPi(0.0f).cos, 1.0f);
}

TEST(FloatMath, LogOfNormalOnFourLanesGivesTheScalarBits) {
  const float values[] = {1.0f,     0.70710677f, 0.70710683f, 1.4142135f, 1.4142137f, 2.0f,
                          3.0e-38f, 1e-20f,      0.3f,        7.5f,       1e20f,      3.4e38f};
  for (const float a : values) {
    for (const float b : values) {
      const Float4 x = {a, b, a * 0.5f, b * 0.75f};  // all normal, finite, > 0
      const Float4 got = logOfNormal(x);
      for (int i = 0; i < 4; ++i)
        EXPECT_EQ(std::bit_cast<std::uint32_t>(got[i]),
                  std::bit_cast<std::uint32_t>(logOfNormal(x[i])))
            << "lane " << i << " x = " << x[i];
    }
  }
}

}  // namespace
}  // namespace camsim
