// Tests for sensor/sampled_spectrum: the visible-wavelength pdf, its inverse CDF, the
// stratified hero-wavelength sets and SampledSpectrum arithmetic.
#include "sensor/spectra/sampled_spectrum.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "sensor/model/spectral_response.h"
#include "sensor/spectra/cie.h"

namespace camsim {
namespace {

// Σ ȳ over the 1 nm grid of the CIE 1931 2° table (luts/spectra/cie1931_2deg_xyz.csv).
constexpr double kSampledSumYBar = 106.856895;

// Composite Simpson's rule of visibleWavelengthPdf over [a, b] with n (even) intervals.
// The pdf is smooth (a scaled sech²), so n = 2000 over ≤ 470 nm is accurate to ≪ 1e-8.
double integratePdf(double a, double b, int n = 2000) {
  if (b <= a) return 0.0;
  const double h = (b - a) / n;
  auto f = [](double x) {
    return static_cast<double>(visibleWavelengthPdf(static_cast<float>(x)));
  };
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += (i % 2 == 1 ? 4.0 : 2.0) * f(a + i * h);
  return s * h / 3.0;
}

// Uniform float in [0, 1) from 24 random bits (exactly representable, never 1).
float uniformFloat(std::mt19937& rng) {
  return static_cast<float>(rng() >> 8) * 0x1p-24f;
}

TEST(VisibleWavelengthPdf, IntegratesToOneOverTheVisibleRange) {
  // Tolerance 1e-4 (brief); the quadrature error is ≪ 1e-8 and the float pdf adds ~1e-7.
  EXPECT_NEAR(integratePdf(kLambdaMinNm, kLambdaMaxNm), 1.0, 1e-4);
}

TEST(VisibleWavelengthPdf, IsZeroOutsideAndPeaksAt538Nm) {
  EXPECT_EQ(visibleWavelengthPdf(359.9f), 0.0f);
  EXPECT_EQ(visibleWavelengthPdf(830.1f), 0.0f);
  EXPECT_GT(visibleWavelengthPdf(360.0f), 0.0f);
  EXPECT_GT(visibleWavelengthPdf(830.0f), 0.0f);
  // Closed form at the centre: a / Z with Z = tanh(a·292) − tanh(−a·178), a = 0.0072.
  const double z = std::tanh(0.0072 * 292.0) - std::tanh(-0.0072 * 178.0);
  // Relative 1e-6: float result.
  EXPECT_NEAR(static_cast<double>(visibleWavelengthPdf(538.0f)), 0.0072 / z, 1e-6 * 0.0072 / z);
  EXPECT_GT(visibleWavelengthPdf(538.0f), visibleWavelengthPdf(520.0f));
  EXPECT_GT(visibleWavelengthPdf(538.0f), visibleWavelengthPdf(560.0f));
}

// sampleVisible computes its four wavelengths and grid positions as one Float4: each lane
// must be what the scalar functions give for that lane's u (u + i/4 mod 1).
TEST(SampleVisibleWavelength, FourLanesAreTheScalarSamples) {
  for (int k = 0; k <= 1000; ++k) {
    const float u = k == 1000 ? 0.99999994f : static_cast<float>(k) / 1000.0f;
    const SampledWavelengths w = SampledWavelengths::sampleVisible(u);
    for (int i = 0; i < kWavelengthSamples; ++i) {
      float ui = u + static_cast<float>(i) / kWavelengthSamples;
      if (ui >= 1.0f) ui -= 1.0f;
      const float lambda = sampleVisibleWavelength(ui);
      EXPECT_EQ(w[i], lambda) << "u = " << u << ", lane " << i;
      // p from t (the sampler) against p from λ (closed form): 1e-5, as the file's header
      EXPECT_NEAR(w.pdf(i) / visibleWavelengthPdf(lambda), 1.0f, 1e-5f) << "u = " << u;
      const Spectrum::GridPosition g = Spectrum::gridPosition(lambda);
      EXPECT_EQ(w.gridIndex(i), g.index) << "u = " << u << ", lane " << i;
      EXPECT_EQ(w.gridFraction(i), g.fraction) << "u = " << u << ", lane " << i;
    }
  }
  // The grid's clamps, lane by lane: below, at and above both ends.
  const Float4 lambda = {350.0f, 360.0f, 830.0f, 840.0f};
  Int4 index;
  Float4 fraction;
  Spectrum::gridPositionLanes(lambda, index, fraction);
  for (int i = 0; i < 4; ++i) {
    const Spectrum::GridPosition g = Spectrum::gridPosition(lambda[i]);
    EXPECT_EQ(index[i], g.index) << lambda[i];
    EXPECT_EQ(fraction[i], g.fraction) << lambda[i];
  }
  EXPECT_EQ(index[0], 0);
  EXPECT_EQ(index[3], kSpectrumSamples - 2);
  EXPECT_EQ(fraction[3], 1.0f);
}

TEST(SampleVisibleWavelength, IsTheInverseCdf) {
  for (const float u : {0.001f, 0.05f, 0.1f, 0.25f, 0.4f, 0.5f, 0.6f, 0.75f, 0.9f, 0.99f}) {
    const float lambda = sampleVisibleWavelength(u);
    ASSERT_GE(lambda, static_cast<float>(kLambdaMinNm));
    ASSERT_LE(lambda, static_cast<float>(kLambdaMaxNm));
    // ∫_360^λ p = u within 1e-4 (brief); λ is float (ulp ≈ 6e-5 nm, i.e. ≪ 1e-6 in u).
    EXPECT_NEAR(integratePdf(kLambdaMinNm, static_cast<double>(lambda)), static_cast<double>(u),
                1e-4)
        << "u = " << u;
  }
  // The ends of the unit interval map to the ends of the range (float atanh: 1e-3 nm).
  EXPECT_NEAR(static_cast<double>(sampleVisibleWavelength(0.0f)), kLambdaMinNm, 1e-3);
  EXPECT_NEAR(static_cast<double>(sampleVisibleWavelength(1.0f)), kLambdaMaxNm, 1e-3);
}

TEST(SampleVisibleWavelength, IsMonotonic) {
  float previous = sampleVisibleWavelength(0.0f);
  for (int i = 1; i <= 1000; ++i) {
    const float lambda = sampleVisibleWavelength(static_cast<float>(i) / 1000.0f);
    EXPECT_GT(lambda, previous) << "i = " << i;
    previous = lambda;
  }
}

TEST(SampledWavelengths, SampleVisibleIsStratifiedOverCdfQuarters) {
  // N = kWavelengthSamples strata of the CDF (quarters for N = 4, eighths for 8). u values
  // chosen away from multiples of 1/8 so no wavelength sits on a stratum boundary.
  constexpr int n = kWavelengthSamples;
  for (const float u : {0.01f, 0.06f, 0.3f, 0.49f, 0.62f, 0.73f, 0.999f}) {
    const SampledWavelengths w = SampledWavelengths::sampleVisible(u);
    std::array<int, n> perQuarter{};
    for (int i = 0; i < n; ++i) {
      const double cdf = integratePdf(kLambdaMinNm, static_cast<double>(w[i]));
      const int quarter = std::clamp(static_cast<int>(cdf * n), 0, n - 1);
      ++perQuarter[quarter];
      // The i-th wavelength is the inverse CDF of u + i/N (mod 1); 1e-4 as above.
      const double ui = std::fmod(static_cast<double>(u) + static_cast<double>(i) / n, 1.0);
      EXPECT_NEAR(cdf, ui, 1e-4) << "u = " << u << ", i = " << i;
      // The pdf is the visible pdf at that wavelength (computed from t: see below).
      EXPECT_NEAR(w.pdf(i), visibleWavelengthPdf(w[i]), 1e-5f * visibleWavelengthPdf(w[i]))
          << "u = " << u << ", i = " << i;
      EXPECT_EQ(w.pdfs()[i], w.pdf(i));
    }
    for (int q = 0; q < n; ++q) EXPECT_EQ(perQuarter[q], 1) << "u = " << u << ", stratum " << q;
  }
}

// sampleVisible takes p(λ) from t = tanh(a(λ − 538)) instead of evaluating it at λ: the
// two must agree (relative 1e-5; an error in the sech² identity or a swapped factor
// is off by far more: 1 − t instead of (1 − t)(1 + t) is off by up to 6×).
TEST(SampledWavelengths, SampleVisiblePdfIsThePdfAtTheSampledWavelength) {
  double worst = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const SampledWavelengths w = SampledWavelengths::sampleVisible((k + 0.5f) / 4000.0f);
    for (int i = 0; i < kWavelengthSamples; ++i) {
      const double expected = visibleWavelengthPdf(w[i]);
      ASSERT_GT(expected, 0.0);
      worst = std::max(worst, std::abs(static_cast<double>(w.pdf(i)) / expected - 1.0));
    }
  }
  EXPECT_LT(worst, 1e-5);
}

TEST(SampledWavelengths, SampleUniformIsStratifiedWithConstantPdf) {
  const SampledWavelengths w = SampledWavelengths::sampleUniform(0.1f);
  // Expected λ_i = 360 + 470·((0.1 + i/N) mod 1): for N = 4 407, 524.5, 642, 759.5
  // (float: 1e-3 nm).
  for (int i = 0; i < kWavelengthSamples; ++i) {
    const double expected =
        360.0 + 470.0 * std::fmod(0.1 + static_cast<double>(i) / kWavelengthSamples, 1.0);
    EXPECT_NEAR(static_cast<double>(w[i]), expected, 1e-3) << "i = " << i;
    EXPECT_NEAR(static_cast<double>(w.pdf(i)), 1.0 / 470.0, 1e-9);
  }
}

TEST(SampledWavelengths, MonochromaticPutsEveryLaneAtOneWavelength) {
  const SampledWavelengths w = SampledWavelengths::monochromatic(550.5f);
  const SampledSpectrum yBar = sampleSpectrum(Cie1931::get().y, w);
  for (int i = 0; i < kWavelengthSamples; ++i) {
    EXPECT_EQ(w[i], 550.5f) << "i = " << i;
    EXPECT_EQ(w.pdf(i), 1.0f);
    EXPECT_FLOAT_EQ(yBar[i], Cie1931::get().y(550.5f));  // the grid position is λ's
  }
  EXPECT_FALSE(w.secondaryTerminated());
}

TEST(SampledWavelengths, MonteCarloIntegralOfYBarMatchesTheTableSum) {
  // ∫ȳ dλ ≈ (1/N) Σ_samples (1/4) Σ_i ȳ(λ_i) / p(λ_i), N = 2^16 with a fixed seed.
  const Spectrum& yBar = Cie1931::get().y;
  std::mt19937 rng(12345u);
  constexpr int kSamples = 1 << 16;
  double total = 0.0;
  for (int n = 0; n < kSamples; ++n) {
    const SampledWavelengths w = SampledWavelengths::sampleVisible(uniformFloat(rng));
    const SampledSpectrum estimate = safeDiv(sampleSpectrum(yBar, w), w.pdfs());
    total += static_cast<double>(estimate.average());
  }
  // 0.5 % (brief). The pdf follows ȳ closely and the samples are stratified, so the
  // standard error at 2^16 samples is far smaller (≈0.05 %).
  EXPECT_NEAR(total / kSamples, kSampledSumYBar, 0.005 * kSampledSumYBar);
}

TEST(SampledSpectrum, Arithmetic) {
  SampledSpectrum a;
  SampledSpectrum b;
  for (int i = 0; i < kWavelengthSamples; ++i) {
    a[i] = static_cast<float>(i + 1);      // 1 2 3 4
    b[i] = static_cast<float>(2 * i + 1);  // 1 3 5 7
  }
  // Small integers and halves: exact in float.
  const SampledSpectrum sum = a + b;
  const SampledSpectrum diff = b - a;
  const SampledSpectrum prod = a * b;
  const SampledSpectrum scaled = 2.0f * a;
  const SampledSpectrum halved = a / 2.0f;
  for (int i = 0; i < kWavelengthSamples; ++i) {
    EXPECT_EQ(sum[i], static_cast<float>(3 * i + 2));
    EXPECT_EQ(diff[i], static_cast<float>(i));
    EXPECT_EQ(prod[i], static_cast<float>((i + 1) * (2 * i + 1)));
    EXPECT_EQ(scaled[i], static_cast<float>(2 * (i + 1)));
    EXPECT_EQ(halved[i], 0.5f * static_cast<float>(i + 1));
  }
  EXPECT_EQ(a.average(), 0.5f * (kWavelengthSamples + 1));  // (1 + … + N)/N
  EXPECT_EQ(b.maxComponent(), static_cast<float>(2 * kWavelengthSamples - 1));
  EXPECT_FALSE(a.isZero());
  EXPECT_TRUE(SampledSpectrum().isZero());
  EXPECT_TRUE(a.isFinite());
  SampledSpectrum bad = a;
  bad[2] = std::numeric_limits<float>::infinity();
  EXPECT_FALSE(bad.isFinite());
}

// isZero tests each lane: a single non-zero or NaN lane anywhere makes it non-zero, and
// −0 is zero (as the loop over floats it replaced had it).
TEST(SampledSpectrum, IsZeroLooksAtEveryLane) {
  for (int i = 0; i < kWavelengthSamples; ++i) {
    for (const float v : {1e-30f, -2.0f, std::numeric_limits<float>::quiet_NaN()}) {
      SampledSpectrum s;
      s[i] = v;
      EXPECT_FALSE(s.isZero()) << "lane " << i << " value " << v;
    }
    SampledSpectrum negativeZero;
    negativeZero[i] = -0.0f;
    EXPECT_TRUE(negativeZero.isZero()) << "lane " << i;
  }
}

// isFinite tests each lane: ±∞ or NaN in any one lane makes the spectrum not finite; the
// largest finite float, denormals and −0 do not.
TEST(SampledSpectrum, IsFiniteLooksAtEveryLane) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (int i = 0; i < kWavelengthSamples; ++i) {
    for (const float v : {kInf, -kInf, std::numeric_limits<float>::quiet_NaN()}) {
      SampledSpectrum s(1.0f);
      s[i] = v;
      EXPECT_FALSE(s.isFinite()) << "lane " << i << " value " << v;
    }
    for (const float v : {std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                          std::numeric_limits<float>::denorm_min(), -0.0f}) {
      SampledSpectrum s(1.0f);
      s[i] = v;
      EXPECT_TRUE(s.isFinite()) << "lane " << i << " value " << v;
    }
  }
}

TEST(SampledSpectrum, SafeDivTreatsZeroDenominatorAsZero) {
  SampledSpectrum num(6.0f);
  SampledSpectrum den;
  den[0] = 2.0f;
  den[1] = 0.0f;
  den[2] = 3.0f;
  den[3] = 0.0f;
  const SampledSpectrum q = safeDiv(num, den);
  EXPECT_EQ(q[0], 3.0f);
  EXPECT_EQ(q[1], 0.0f);
  EXPECT_EQ(q[2], 2.0f);
  EXPECT_EQ(q[3], 0.0f);
}

// The lane forms against the scalar code they replaced, written out here: the grid
// position with std::clamp and a scalar truncation, each lerp with Spectrum::interpolate,
// and the film's estimate as a loop of float products summed in double.
TEST(SampledSpectrum, LanesGiveTheBitsOfTheScalarCode) {
  Spectrum wiggly;
  for (int i = 0; i < kSpectrumSamples; ++i)
    wiggly.sample(i) = 0.5f + 0.4f * std::sin(0.37f * static_cast<float>(i)) / 3.0f;
  const SpectralResponse xyz = SpectralResponse::cieXyz();
  const auto bits = [](float x) { return std::bit_cast<std::uint32_t>(x); };
  for (int k = 0; k < 2000; ++k) {
    const float u = static_cast<float>(k) / 2000.0f;
    for (const SampledWavelengths& w :
         {SampledWavelengths::sampleVisible(u), SampledWavelengths::sampleUniform(u)}) {
      SampledSpectrum q;
      for (int i = 0; i < kWavelengthSamples; ++i) {
        const float x = std::clamp(w[i] - static_cast<float>(kLambdaMinNm), 0.0f,
                                   static_cast<float>(kSpectrumSamples - 1));
        const int index = std::min(static_cast<int>(x), kSpectrumSamples - 2);
        ASSERT_EQ(w.gridIndex(i), index) << w[i];
        ASSERT_EQ(bits(w.gridFraction(i)), bits(x - static_cast<float>(index))) << w[i];
        q[i] = 1.0f + static_cast<float>(i) * u;
      }
      const SampledSpectrum s = sampleSpectrum(wiggly, w);
      for (int i = 0; i < kWavelengthSamples; ++i)
        ASSERT_EQ(bits(s[i]), bits(wiggly.interpolate(w.gridIndex(i), w.gridFraction(i))));
      for (int c = 0; c < xyz.channelCount(); ++c) {
        double sum = 0.0;
        for (int i = 0; i < kWavelengthSamples; ++i)
          sum += static_cast<double>(
              xyz.channel(c).curve.interpolate(w.gridIndex(i), w.gridFraction(i)) * q[i]);
        ASSERT_EQ(xyz.estimate(c, q, w), sum / kWavelengthSamples) << "channel " << c;
      }
    }
  }
}

TEST(SampledSpectrum, SampleSpectrumEvaluatesAtTheWavelengths) {
  Spectrum ramp;
  for (int i = 0; i < kSpectrumSamples; ++i) ramp.sample(i) = static_cast<float>(i);
  const SampledWavelengths w = SampledWavelengths::sampleUniform(0.1f);
  const SampledSpectrum s = sampleSpectrum(ramp, w);
  // ramp(λ) = λ − 360 (linear, so the lerp is exact up to float rounding of λ: 1e-3).
  for (int i = 0; i < kWavelengthSamples; ++i)
    EXPECT_NEAR(static_cast<double>(s[i]), static_cast<double>(w[i]) - kLambdaMinNm, 1e-3);
}

}  // namespace
}  // namespace camsim
