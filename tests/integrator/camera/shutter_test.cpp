// Shutter: effective exposure time, and time samples distributed as s(t)/T_eff.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "integrator/camera/shutter.h"
#include "integrator/sampling/rng.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace {

TEST(Shutter, EffectiveTimeOfBoxTrapezoidAndCurve) {
  EXPECT_DOUBLE_EQ(Shutter::box(0.0, 0.01).effectiveTime(), 0.01);
  EXPECT_NEAR(Shutter::trapezoid(0.0, 0.01, 0.002, 0.004).effectiveTime(), 0.01 - 0.003, 1e-15);
  const Shutter curve({0.0, 0.001, 0.002, 0.005}, {0.0, 1.0, 0.5, 0.0}, Shutter::Type::kGlobal,
                      0.0);
  EXPECT_NEAR(curve.effectiveTime(), 0.0005 + 0.00075 + 0.00075, 1e-15);
  EXPECT_DOUBLE_EQ(curve.efficiency(0.0015), 0.75);
  EXPECT_DOUBLE_EQ(curve.efficiency(-1.0), 0.0);
}

// Found by probing (each aborted the process on a check of equal knot times): a ramp that
// fills the exposure, ramps lost to rounding, and an exposure scaled or moved until its
// times run together in double precision (now an InputError keyed "shutter").
TEST(Shutter, RampsAtTheLimitsAndTimesThatRunTogether) {
  // ramp_open = the exposure: a ramp 0 → 1 across it (T_eff = half), as is a ramp down.
  EXPECT_NEAR(Shutter::trapezoid(0.0, 0.01, 0.01, 0.0).effectiveTime(), 0.005, 1e-15);
  EXPECT_NEAR(Shutter::trapezoid(0.0, 0.01, 0.0, 0.01).effectiveTime(), 0.005, 1e-15);
  EXPECT_NEAR(Shutter::trapezoid(0.0, 0.01, 0.005, 0.005).effectiveTime(), 0.005, 1e-15);
  // 0.3 − 0.1 rounds below 0.2: the whole exposure still.
  EXPECT_NEAR(Shutter::trapezoid(0.1, 0.3, 0.2, 0.0).effectiveTime(), 0.1, 1e-15);
  // Ramps of 1e-20 s at 0.5 s and at 1 s are lost to rounding: a box.
  EXPECT_DOUBLE_EQ(Shutter::trapezoid(0.5, 1.0, 1e-20, 0.0).effectiveTime(), 0.5);
  EXPECT_DOUBLE_EQ(Shutter::trapezoid(0.0, 1.0, 0.0, 1e-20).effectiveTime(), 1.0);
  // Both ramps over an exposure of one ulp: no time to peak between them, a box.
  const double open = 0.5, close = std::nextafter(0.5, 1.0);
  EXPECT_DOUBLE_EQ(Shutter::trapezoid(open, close, close - open, close - open).effectiveTime(),
                   close - open);
  const Shutter late = Shutter::box(0.5, 0.51);
  for (const auto& make : {std::function<Shutter()>([&] { return late.scaled(1e-15); }),
                           std::function<Shutter()>([&] { return late.shifted(1e16); })}) {
    try {
      make();
      ADD_FAILURE() << "made";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "shutter");
      EXPECT_NE(e.message().find("too short for the time it opens at"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_NEAR(late.scaled(1e-3).effectiveTime(), 1e-5, 1e-15);  // still apart: fine
}

// Kolmogorov–Smirnov: the empirical CDF of 2^17 samples against ∫s/T_eff; the 99.9 %
// critical value is 1.95/√n ≈ 0.0054.
TEST(Shutter, SamplesFollowTheEfficiencyCurve) {
  const Shutter shutters[] = {
      Shutter::trapezoid(0.0, 0.01, 0.003, 0.001),
      Shutter({0.0, 0.001, 0.002, 0.005}, {0.0, 1.0, 0.5, 0.0}, Shutter::Type::kGlobal, 0.0)};
  for (const Shutter& s : shutters) {
    constexpr int n = 1 << 17;
    std::vector<double> t(n);
    Pcg32 rng(7, 1);
    for (double& v : t) v = s.sample(static_cast<double>(rng.uniform()));
    std::sort(t.begin(), t.end());
    double worst = 0.0;
    for (int k = 1; k < 200; ++k) {
      const double x = s.open() + (s.close() - s.open()) * k / 200.0;
      double cdf = 0.0;  // trapezoidal integral of s up to x (s is piecewise linear)
      constexpr int m = 2000;
      for (int i = 0; i < m; ++i) {
        const double a = s.open() + (x - s.open()) * i / m,
                     b = s.open() + (x - s.open()) * (i + 1) / m;
        cdf += 0.5 * (s.efficiency(a) + s.efficiency(b)) * (b - a);
      }
      cdf /= s.effectiveTime();
      const double empirical =
          static_cast<double>(std::upper_bound(t.begin(), t.end(), x) - t.begin()) / n;
      worst = std::max(worst, std::abs(empirical - cdf));
    }
    EXPECT_LT(worst, 0.0054);
    EXPECT_GE(t.front(), s.open());
    EXPECT_LE(t.back(), s.close());
  }
}

TEST(Shutter, RollingShutterDelaysRowsGlobalDoesNot) {
  const Shutter rolling = Shutter::trapezoid(0.0, 0.01, 0.0, 0.0, Shutter::Type::kRolling, 1e-5);
  EXPECT_DOUBLE_EQ(rolling.rowOffset(0), 0.0);
  EXPECT_DOUBLE_EQ(rolling.rowOffset(100), 1e-3);
  EXPECT_DOUBLE_EQ(Shutter::box(0.0, 0.01).rowOffset(100), 0.0);
}

}  // namespace
}  // namespace camsim
