// Tests for sensor/spectrum: the dense 1 nm Spectrum, its construction and evaluation.
#include "sensor/spectra/spectrum.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

namespace camsim {
namespace {

// Index of the grid sample at wavelength lambdaNm (an integer in [360, 830]).
int at(int lambdaNm) {
  return lambdaNm - kLambdaMinNm;
}

TEST(Spectrum, DefaultIsZero) {
  const Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) EXPECT_EQ(s.sample(i), 0.0f) << "i = " << i;
}

TEST(Spectrum, ConstantHasTheValueEverywhereInRange) {
  const Spectrum s = Spectrum::constant(0.25);
  // 0.25 is exact in float: equality, no tolerance.
  for (int i = 0; i < kSpectrumSamples; ++i) EXPECT_EQ(s.sample(i), 0.25f) << "i = " << i;
  EXPECT_EQ(s(360.0f), 0.25f);
  EXPECT_EQ(s(555.5f), 0.25f);
  EXPECT_EQ(s(830.0f), 0.25f);
  EXPECT_EQ(s.minValue(), 0.25);
  EXPECT_EQ(s.maxValue(), 0.25);
}

TEST(Spectrum, FromSamplesInterpolatesLinearlyBetweenTablePoints) {
  // Table points on and off the 1 nm grid; expected values computed by hand.
  const std::vector<double> lambda{400.0, 500.0, 600.5};
  const std::vector<double> value{1.0, 3.0, 2.0};
  const Spectrum s = Spectrum::fromSamples(lambda, value, Extrapolation::kZero);
  // Tolerance 1e-6: values are stored as float (relative precision 6e-8 on values ≤ 3).
  EXPECT_NEAR(s.sample(at(400)), 1.0, 1e-6);
  EXPECT_NEAR(s.sample(at(425)), 1.5, 1e-6);
  EXPECT_NEAR(s.sample(at(450)), 2.0, 1e-6);
  EXPECT_NEAR(s.sample(at(500)), 3.0, 1e-6);
  // Between 500 (3) and 600.5 (2): v(λ) = 3 − (λ − 500) / 100.5.
  EXPECT_NEAR(s.sample(at(550)), 3.0 - 50.0 / 100.5, 1e-6);
  EXPECT_NEAR(s.sample(at(600)), 3.0 - 100.0 / 100.5, 1e-6);
}

TEST(Spectrum, FromSamplesZeroExtrapolation) {
  const std::vector<double> lambda{400.0, 500.0, 600.0};
  const std::vector<double> value{1.0, 3.0, 2.0};
  const Spectrum s = Spectrum::fromSamples(lambda, value, Extrapolation::kZero);
  EXPECT_EQ(s.sample(at(360)), 0.0f);
  EXPECT_EQ(s.sample(at(399)), 0.0f);
  EXPECT_EQ(s.sample(at(400)), 1.0f);
  EXPECT_EQ(s.sample(at(600)), 2.0f);
  EXPECT_EQ(s.sample(at(601)), 0.0f);
  EXPECT_EQ(s.sample(at(830)), 0.0f);
}

TEST(Spectrum, FromSamplesClampExtrapolation) {
  const std::vector<double> lambda{400.0, 500.0, 600.0};
  const std::vector<double> value{1.0, 3.0, 2.0};
  const Spectrum s = Spectrum::fromSamples(lambda, value, Extrapolation::kClamp);
  EXPECT_EQ(s.sample(at(360)), 1.0f);
  EXPECT_EQ(s.sample(at(399)), 1.0f);
  EXPECT_EQ(s.sample(at(601)), 2.0f);
  EXPECT_EQ(s.sample(at(830)), 2.0f);
  EXPECT_NEAR(s.sample(at(450)), 2.0, 1e-6);  // interior unaffected by the mode
}

TEST(Spectrum, FromSamplesTableWiderThanTheGrid) {
  // A table from 300 to 900 nm: v = λ / 100; both extrapolation modes are irrelevant.
  const std::vector<double> lambda{300.0, 900.0};
  const std::vector<double> value{3.0, 9.0};
  for (const Extrapolation mode : {Extrapolation::kZero, Extrapolation::kClamp}) {
    const Spectrum s = Spectrum::fromSamples(lambda, value, mode);
    // 1e-5: float storage of values up to 8.3.
    EXPECT_NEAR(s.sample(at(360)), 3.6, 1e-5);
    EXPECT_NEAR(s.sample(at(555)), 5.55, 1e-5);
    EXPECT_NEAR(s.sample(at(830)), 8.3, 1e-5);
  }
}

TEST(Spectrum, FromSamplesSinglePoint) {
  const std::vector<double> lambda{500.0};
  const std::vector<double> value{0.75};
  const Spectrum zero = Spectrum::fromSamples(lambda, value, Extrapolation::kZero);
  EXPECT_EQ(zero.sample(at(500)), 0.75f);
  EXPECT_EQ(zero.sample(at(499)), 0.0f);
  EXPECT_EQ(zero.sample(at(501)), 0.0f);
  const Spectrum clamp = Spectrum::fromSamples(lambda, value, Extrapolation::kClamp);
  EXPECT_EQ(clamp.sample(at(360)), 0.75f);
  EXPECT_EQ(clamp.sample(at(830)), 0.75f);
}

TEST(Spectrum, CallOperatorLerpsBetweenOneNmSamples) {
  Spectrum s;
  // Non-linear sample values so a wrong index or weight shows: v_i = (i mod 7)² + 0.5 i.
  for (int i = 0; i < kSpectrumSamples; ++i)
    s.sample(i) = static_cast<float>((i % 7) * (i % 7)) + 0.5f * static_cast<float>(i);
  for (int i = 0; i + 1 < kSpectrumSamples; i += 13) {
    for (const float t : {0.0f, 0.25f, 0.5f, 0.875f}) {
      const float lambda = static_cast<float>(kLambdaMinNm + i) + t;
      const double a = static_cast<double>(s.sample(i));
      const double b = static_cast<double>(s.sample(i + 1));
      const double expected = a + static_cast<double>(t) * (b - a);
      // 1e-4: float evaluation of values ≤ 271 (relative 6e-8 → ≈2e-5 absolute) plus the
      // float rounding of λ itself near 830 (t is exact in float here).
      EXPECT_NEAR(static_cast<double>(s(lambda)), expected, 1e-4) << "lambda = " << lambda;
    }
  }
  // The end points are the end samples.
  EXPECT_EQ(s(360.0f), s.sample(0));
  EXPECT_EQ(s(830.0f), s.sample(kSpectrumSamples - 1));
}

TEST(Spectrum, CallOperatorIsZeroOutsideTheGrid) {
  const Spectrum s = Spectrum::constant(1.0);
  EXPECT_EQ(s(359.99f), 0.0f);
  EXPECT_EQ(s(200.0f), 0.0f);
  EXPECT_EQ(s(-1.0f), 0.0f);
  EXPECT_EQ(s(830.01f), 0.0f);
  EXPECT_EQ(s(1000.0f), 0.0f);
  EXPECT_EQ(s(std::numeric_limits<float>::quiet_NaN()), 0.0f);
  EXPECT_EQ(s(std::numeric_limits<float>::infinity()), 0.0f);
  EXPECT_EQ(s(-std::numeric_limits<float>::infinity()), 0.0f);
}

// Planck's law, evaluated independently in long double. Returns W·m⁻²·sr⁻¹·nm⁻¹.
long double planckPerNm(long double lambdaNm, long double kelvin) {
  const long double h = 6.62607015e-34L;  // J·s (exact, SI 2019)
  const long double c = 299792458.0L;     // m/s (exact)
  const long double kB = 1.380649e-23L;   // J/K (exact, SI 2019)
  const long double lambda = lambdaNm * 1e-9L;
  const long double perMetre =
      2.0L * h * c * c /
      (std::pow(lambda, 5.0L) * (std::exp(h * c / (lambda * kB * kelvin)) - 1.0L));
  return perMetre * 1e-9L;
}

TEST(Spectrum, BlackbodyAbsoluteValueMatchesPlanck) {
  for (const double kelvin : {2856.0, 5000.0, 6500.0}) {
    const Spectrum s = Spectrum::blackbody(kelvin);
    for (const int lambdaNm : {380, 550, 700, 830}) {
      const double expected = static_cast<double>(planckPerNm(lambdaNm, kelvin));
      // Relative 1e-6: the spectrum stores float (6e-8 relative); double vs long double
      // arithmetic differs by ~1e-15.
      EXPECT_NEAR(static_cast<double>(s.sample(at(lambdaNm))), expected, 1e-6 * expected)
          << "T = " << kelvin << " K, lambda = " << lambdaNm << " nm";
    }
  }
  // One value written out (computed offline with the same constants): B(550 nm, 5000 K) =
  // 1.2713015e13 W·m⁻²·sr⁻¹·m⁻¹ = 12713.015 per nm. Tolerance 0.01 (float ulp here ≈ 0.001).
  EXPECT_NEAR(static_cast<double>(Spectrum::blackbody(5000.0).sample(at(550))), 12713.015, 0.01);
}

TEST(Spectrum, BlackbodyPeakFollowsWiensDisplacementLaw) {
  constexpr double kWienMetreKelvin = 2.897771955e-3;  // CODATA 2018
  for (const double kelvin : {4000.0, 5000.0, 6500.0}) {
    const Spectrum s = Spectrum::blackbody(kelvin);
    int best = 0;
    for (int i = 1; i < kSpectrumSamples; ++i)
      if (s.sample(i) > s.sample(best)) best = i;
    ASSERT_GT(best, 0);
    ASSERT_LT(best, kSpectrumSamples - 1);
    const double expectedNm = kWienMetreKelvin / kelvin * 1e9;
    // The grid maximum is within 0.5 nm of the true peak; the brief's tolerance is 1 nm.
    EXPECT_NEAR(kLambdaMinNm + best, expectedNm, 1.0) << "T = " << kelvin << " K";
    // Parabola through the three samples around the maximum: the vertex is within 0.1 nm
    // (the parabola's own error near a smooth peak is ≪ 0.1 nm at 1 nm spacing).
    const double a = static_cast<double>(s.sample(best - 1));
    const double b = static_cast<double>(s.sample(best));
    const double c = static_cast<double>(s.sample(best + 1));
    const double vertex = kLambdaMinNm + best + 0.5 * (a - c) / (a - 2.0 * b + c);
    EXPECT_NEAR(vertex, expectedNm, 0.1) << "T = " << kelvin << " K";
  }
}

TEST(Spectrum, SumIsTheRectangleRuleOnTheGrid) {
  EXPECT_DOUBLE_EQ(Spectrum::constant(2.0).sum(), 2.0 * kSpectrumSamples);
  Spectrum ramp;
  for (int i = 0; i < kSpectrumSamples; ++i) ramp.sample(i) = static_cast<float>(i);
  // Σ_{i=0}^{470} i = 470·471/2, exact in double.
  EXPECT_EQ(ramp.sum(), 470.0 * 471.0 / 2.0);
  EXPECT_EQ(ramp.minValue(), 0.0);
  EXPECT_EQ(ramp.maxValue(), 470.0);
}

TEST(Spectrum, InnerProduct) {
  Spectrum ramp;
  for (int i = 0; i < kSpectrumSamples; ++i) ramp.sample(i) = static_cast<float>(i);
  // Σ i·3 = 3·470·471/2 and Σ i² = n(n+1)(2n+1)/6 with n = 470: both exact in double.
  EXPECT_EQ(innerProduct(ramp, Spectrum::constant(3.0)), 3.0 * 470.0 * 471.0 / 2.0);
  EXPECT_EQ(innerProduct(ramp, ramp), 470.0 * 471.0 * 941.0 / 6.0);
  EXPECT_EQ(innerProduct(ramp, Spectrum()), 0.0);
}

TEST(Spectrum, Multiplication) {
  Spectrum ramp;
  for (int i = 0; i < kSpectrumSamples; ++i) ramp.sample(i) = static_cast<float>(i);
  const Spectrum scaled = ramp * 0.5;
  const Spectrum squared = ramp * ramp;
  for (int i = 0; i < kSpectrumSamples; ++i) {
    // Exact in float: i/2 and i² ≤ 220900 are representable.
    EXPECT_EQ(scaled.sample(i), 0.5f * static_cast<float>(i));
    EXPECT_EQ(squared.sample(i), static_cast<float>(i * i));
  }
}

}  // namespace
}  // namespace camsim
