// Tests for sensor/sensor_model: exact Poisson sampling, the EMVA 1288 chain (dark signal,
// fixed patterns, temporal noise, clipping, quantisation) and counter-based determinism.
// All seeds are fixed; statistical tolerances are 5 standard errors unless stated.
#include "sensor/model/sensor_model.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"

namespace camsim {
namespace {

constexpr int kN = 200000;  // Poisson samples per mean

struct Moments {
  double mean = 0.0, variance = 0.0;
};

template <typename F>
Moments moments(size_t n, F value) {
  double sum = 0.0, sum2 = 0.0;
  for (size_t i = 0; i < n; ++i) sum += value(i);
  const double mean = sum / static_cast<double>(n);
  for (size_t i = 0; i < n; ++i) sum2 += (value(i) - mean) * (value(i) - mean);
  return {mean, sum2 / static_cast<double>(n - 1)};
}
Moments moments(const RawImage& raw) {
  return moments(raw.dn.size(), [&](size_t i) { return static_cast<double>(raw.dn[i]); });
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const Moments ma = moments(a.size(), [&](size_t i) { return a[i]; });
  const Moments mb = moments(b.size(), [&](size_t i) { return b[i]; });
  double cov = 0.0;
  for (size_t i = 0; i < a.size(); ++i) cov += (a[i] - ma.mean) * (b[i] - mb.mean);
  return cov / static_cast<double>(a.size() - 1) / std::sqrt(ma.variance * mb.variance);
}

std::vector<double> values(const RawImage& raw) {
  return {raw.dn.begin(), raw.dn.end()};
}

// A monochrome 16-bit sensor with K = 1 DN/e⁻ and no noise sources; tests switch some on.
SensorSpec plainSpec() {
  SensorSpec s;
  s.name = "test";
  s.fullWellE = 1e5;
  s.conversionGainEPerDn = 1.0;
  s.baseIso = 100.0;
  s.readNoiseE = 0.0;
  s.adcBits = 16;
  s.blackLevelDn = 0.0;
  return s;
}

Image flat(int w, int h, float electrons) {
  Image img(w, h, {"e"});
  for (float& p : img.pixels) p = electrons;
  return img;
}

ExposureSettings settings(double seconds = 0.01, double iso = 100.0) {
  return {seconds, iso};
}

TEST(SamplePoisson, MeanAndVarianceEqualTheMean) {
  std::printf("%10s %12s %12s %12s\n", "mean", "sample mean", "variance", "var/mean");
  std::uint64_t key = 1000;
  for (const double mu : {0.1, 1.0, 9.99, 10.0, 100.0, 1e3, 1e4, 1e6}) {
    std::vector<double> draws(kN);
    for (double& d : draws) d = static_cast<double>(samplePoisson(mu, key++));
    const Moments m = moments(draws.size(), [&](size_t i) { return draws[i]; });
    std::printf("%10g %12.6g %12.6g %12.5f\n", mu, m.mean, m.variance, m.variance / mu);
    EXPECT_NEAR(m.mean, mu, 5.0 * std::sqrt(mu / kN)) << mu;
    // Var(s²) = (μ₄ − σ⁴)/n = (μ + 2μ²)/n for a Poisson distribution.
    EXPECT_NEAR(m.variance, mu, 5.0 * std::sqrt((mu + 2.0 * mu * mu) / kN)) << mu;
  }
}

TEST(SamplePoisson, ProbabilitiesOfZeroAndOneAtMeanOneTenth) {
  int zeros = 0, ones = 0;
  for (int i = 0; i < kN; ++i) {
    const std::uint64_t k = samplePoisson(0.1, 77u + static_cast<std::uint64_t>(i));
    zeros += k == 0;
    ones += k == 1;
  }
  const double p0 = std::exp(-0.1), p1 = 0.1 * std::exp(-0.1);
  std::printf("P(0) = %.5f (exact %.5f), P(1) = %.5f (exact %.5f)\n", zeros / double(kN), p0,
              ones / double(kN), p1);
  EXPECT_NEAR(zeros / double(kN), p0, 5.0 * std::sqrt(p0 * (1 - p0) / kN));
  EXPECT_NEAR(ones / double(kN), p1, 5.0 * std::sqrt(p1 * (1 - p1) / kN));
}

// χ² goodness of fit against the exact pmf, bins with ≥ 20 expected counts (the tails
// pooled); critical value at p ≈ 1e-5 (Wilson–Hilferty, z = 4.265).
TEST(SamplePoisson, ChiSquareAgainstTheExactPmf) {
  for (const double mu : {4.5, 10.0, 37.3, 2500.0}) {
    std::vector<double> counts;
    std::vector<std::uint64_t> draws(kN);
    for (int i = 0; i < kN; ++i)
      draws[static_cast<size_t>(i)] = samplePoisson(mu, 5000000u + static_cast<std::uint64_t>(i));
    // Bins: (-inf, lo], lo+1, ..., hi-1, [hi, inf) with lo, hi where the pmf · n ≥ 20.
    auto pmf = [mu](double k) { return std::exp(k * std::log(mu) - mu - std::lgamma(k + 1.0)); };
    int lo = static_cast<int>(mu), hi = static_cast<int>(mu);
    while (lo > 0 && pmf(lo - 1) * kN >= 20.0) --lo;
    while (pmf(hi + 1) * kN >= 20.0) ++hi;
    std::vector<double> expected, observed(static_cast<size_t>(hi - lo + 1), 0.0);
    double cdfLo = 0.0;
    for (int k = 0; k <= lo; ++k) cdfLo += pmf(k);
    expected.push_back(cdfLo * kN);
    double inner = cdfLo;
    for (int k = lo + 1; k < hi; ++k) {
      expected.push_back(pmf(k) * kN);
      inner += pmf(k);
    }
    expected.push_back((1.0 - inner) * kN);
    for (const std::uint64_t d : draws) {
      const int k = static_cast<int>(d);
      observed[static_cast<size_t>(std::clamp(k, lo, hi) - lo)] += 1.0;
    }
    double chi2 = 0.0;
    for (size_t i = 0; i < expected.size(); ++i)
      chi2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    const double df = static_cast<double>(expected.size() - 1);
    const double c = 2.0 / (9.0 * df);
    const double critical = df * std::pow(1.0 - c + 4.265 * std::sqrt(c), 3.0);
    std::printf("mean %g: chi2 = %.1f, df = %g, critical %.1f\n", mu, chi2, df, critical);
    EXPECT_LT(chi2, critical) << mu;
  }
}

TEST(SamplePoisson, EdgeCasesAndDeterminism) {
  EXPECT_EQ(samplePoisson(0.0, 1), 0u);
  EXPECT_EQ(samplePoisson(-3.0, 1), 0u);
  EXPECT_EQ(samplePoisson(std::nan(""), 1), 0u);
  const double big = 1e15;
  const double draw = static_cast<double>(samplePoisson(big, 9));
  EXPECT_NEAR(draw, big, 6.0 * std::sqrt(big));
  for (std::uint64_t key = 0; key < 100; ++key)
    for (const double mu : {0.5, 12.0, 3e5})
      EXPECT_EQ(samplePoisson(mu, key), samplePoisson(mu, key));
}

TEST(Expose, ZeroLightIsBlackLevelPlusDarkAndReadNoise) {
  SensorSpec s = plainSpec();
  s.conversionGainEPerDn = 0.5;  // K = 2 DN/e⁻
  s.readNoiseE = 3.0;
  s.darkCurrentEPerS = 100.0;  // × 0.1 s = 10 e⁻
  s.blackLevelDn = 64.0;
  s.adcBits = 12;
  const RawImage raw = expose(flat(256, 256, 0.0f), s, settings(0.1), NoiseMode::kFull, 3, 0);
  const Moments m = moments(raw);
  const double n = static_cast<double>(raw.dn.size());
  const double mean = 64.0 + 2.0 * 10.0;
  const double var = 4.0 * (10.0 + 9.0) + 1.0 / 12.0;  // K²(μ_d + σ_r²) + quantisation
  std::printf("dark frame: mean %.3f (predicted %.3f), variance %.3f (predicted %.3f)\n", m.mean,
              mean, m.variance, var);
  EXPECT_NEAR(m.mean, mean, 5.0 * std::sqrt(var / n));
  EXPECT_NEAR(m.variance, var, 5.0 * var * std::sqrt(2.0 / n));
  // Photon mode: the dark signal's shot noise only.
  const Moments p =
      moments(expose(flat(256, 256, 0.0f), s, settings(0.1), NoiseMode::kPhoton, 3, 0));
  EXPECT_NEAR(p.variance, 4.0 * 10.0 + 1.0 / 12.0, 5.0 * 40.0 * std::sqrt(2.0 / n));
}

TEST(Expose, DarkSignalIsLinearInTimeAndDoublesPerDoublingInterval) {
  SensorSpec s = plainSpec();
  s.darkCurrentEPerS = 50.0;
  s.darkReferenceC = 25.0;
  s.darkDoublingC = 6.0;
  s.blackLevelDn = 100.0;
  const double n = 256.0 * 256.0;
  auto darkSignal = [&](double seconds, double celsius) {
    s.temperatureC = celsius;
    return moments(expose(flat(256, 256, 0.0f), s, settings(seconds), NoiseMode::kFull, 11, 0))
               .mean -
           100.0;
  };
  struct Case {
    double seconds, celsius, expected;
  };
  for (const Case c : {Case{1.0, 25.0, 50.0}, Case{2.0, 25.0, 100.0}, Case{4.0, 25.0, 200.0},
                       Case{1.0, 31.0, 100.0}, Case{1.0, 37.0, 200.0}, Case{1.0, 19.0, 25.0}}) {
    const double d = darkSignal(c.seconds, c.celsius);
    std::printf("dark signal %.1f s at %.0f °C: %.3f e⁻ (predicted %.0f)\n", c.seconds, c.celsius,
                d, c.expected);
    EXPECT_NEAR(d, c.expected, 5.0 * std::sqrt(c.expected / n));
  }
}

// The patterns depend on (pattern_seed, x, y) only: without light and temporal noise a
// frame is pure pattern, bit-identical across frames and noise seeds.
TEST(Expose, FixedPatternIsIdenticalAcrossFrames) {
  SensorSpec s = plainSpec();
  s.prnuFraction = 0.01;
  s.dsnuE = 3.0;
  s.rowFpnE = 2.0;
  s.columnFpnE = 2.0;
  s.blackLevelDn = 1000.0;
  const Image dark = flat(256, 256, 0.0f);
  const RawImage a = expose(dark, s, settings(), NoiseMode::kFull, 1, 0);
  EXPECT_EQ(a.dn, expose(dark, s, settings(), NoiseMode::kFull, 1, 1).dn);
  EXPECT_EQ(a.dn, expose(dark, s, settings(), NoiseMode::kFull, 99, 7).dn);
  const Moments m = moments(a);
  // σ_dsnu² + σ_row² + σ_col² + 1/12; the row and column terms come from only 256 draws
  // each (relative standard error 9 %), hence the tolerance of 3 DN².
  std::printf("dark pattern variance %.3f (predicted %.3f)\n", m.variance,
              9.0 + 4.0 + 4.0 + 1.0 / 12.0);
  EXPECT_NEAR(m.variance, 17.083, 3.0);
  s.patternSeed = 2;
  const RawImage b = expose(dark, s, settings(), NoiseMode::kFull, 1, 0);
  EXPECT_LT(std::abs(correlation(values(a), values(b))), 0.03);
}

// Flat field with every noise source: (A − B)/√2 holds only temporal noise, the average
// over frames holds the fixed pattern plus temporal/M.
TEST(Expose, TemporalAndSpatialVariancesMatchTheModel) {
  SensorSpec s = plainSpec();
  s.prnuFraction = 0.01;
  s.dsnuE = 5.0;
  s.rowFpnE = 1.0;
  s.columnFpnE = 1.0;
  s.readNoiseE = 2.0;
  s.blackLevelDn = 500.0;
  const double mu = 10000.0;
  const int w = 256, h = 256, frames = 16;
  const size_t n = static_cast<size_t>(w) * h;
  const Image light = flat(w, h, static_cast<float>(mu));
  std::vector<RawImage> raws;
  for (int f = 0; f < frames; ++f)
    raws.push_back(
        expose(light, s, settings(), NoiseMode::kFull, 5, static_cast<std::uint64_t>(f)));
  const Moments diff =
      moments(n, [&](size_t i) { return double(raws[0].dn[i]) - double(raws[1].dn[i]); });
  const double temporal = mu * (1.0 + 1e-4) + 4.0 + 1.0 / 12.0;
  std::printf("temporal variance %.1f (predicted %.1f)\n", diff.variance / 2.0, temporal);
  EXPECT_NEAR(diff.variance / 2.0, temporal, 5.0 * temporal * std::sqrt(2.0 / double(n)));
  std::vector<double> average(n, 0.0);
  for (const RawImage& r : raws)
    for (size_t i = 0; i < n; ++i) average[i] += r.dn[i] / double(frames);
  const Moments spatial = moments(n, [&](size_t i) { return average[i]; });
  const double predicted = (mu * 0.01) * (mu * 0.01) + 25.0 + 1.0 + 1.0 + temporal / frames;
  std::printf("variance of the %d-frame mean %.1f (predicted %.1f)\n", frames, spatial.variance,
              predicted);
  EXPECT_NEAR(spatial.variance, predicted, 5.0 * predicted * std::sqrt(2.0 / double(n)));
  EXPECT_NEAR(spatial.mean, 500.0 + mu, 1.0);  // patterns are zero-mean: ±0.4 DN here
}

TEST(Expose, TemporalNoiseIsIndependentBetweenFramesSeedsAndNeighbours) {
  SensorSpec s = plainSpec();
  s.readNoiseE = 2.0;
  const Image light = flat(256, 256, 1000.0f);
  const std::vector<double> f0 = values(expose(light, s, settings(), NoiseMode::kFull, 1, 0));
  const std::vector<double> f1 = values(expose(light, s, settings(), NoiseMode::kFull, 1, 1));
  const std::vector<double> g0 = values(expose(light, s, settings(), NoiseMode::kFull, 2, 0));
  const double bound = 5.0 / std::sqrt(double(f0.size()));  // 0.0195
  const double rFrames = correlation(f0, f1), rSeeds = correlation(f0, g0);
  const std::vector<double> shifted(f0.begin() + 1, f0.end()), head(f0.begin(), f0.end() - 1);
  const double rNeighbours = correlation(head, shifted);
  std::printf("correlations: frames %.4f, seeds %.4f, neighbours %.4f (bound %.4f)\n", rFrames,
              rSeeds, rNeighbours, bound);
  EXPECT_LT(std::abs(rFrames), bound);
  EXPECT_LT(std::abs(rSeeds), bound);
  EXPECT_LT(std::abs(rNeighbours), bound);
}

TEST(Expose, SaturatedPixelsReadTheWhiteLevelOrTheFullWell) {
  SensorSpec s = plainSpec();
  s.adcBits = 12;
  s.blackLevelDn = 100.0;
  s.readNoiseE = 10.0;
  s.prnuFraction = 0.01;
  s.fullWellE = 1e6;  // the ADC (3995 e⁻) clips first
  for (const std::uint16_t v :
       expose(flat(64, 64, 5000.0f), s, settings(), NoiseMode::kFull, 1, 0).dn)
    ASSERT_EQ(v, 4095);
  s.fullWellE = 3000.0;  // the full well clips first: 3000 · 1 + 100
  for (const std::uint16_t v : expose(flat(64, 64, 1e4f), s, settings(), NoiseMode::kFull, 1, 0).dn)
    ASSERT_EQ(v, 3100);
  // At 2 × base ISO, K = 2: 3000 · 2 + 100 > 4095, the ADC clips again.
  for (const std::uint16_t v :
       expose(flat(64, 64, 1e4f), s, settings(0.01, 200.0), NoiseMode::kFull, 1, 0).dn)
    ASSERT_EQ(v, 4095);
}

TEST(Expose, NegativeSignalsClampToZeroWithoutWrapAround) {
  SensorSpec s = plainSpec();
  s.readNoiseE = 1000.0;
  s.blackLevelDn = 0.0;
  const RawImage raw = expose(flat(128, 128, 0.0f), s, settings(), NoiseMode::kFull, 4, 0);
  int zeros = 0;
  std::uint16_t maximum = 0;
  for (const std::uint16_t v : raw.dn) {
    zeros += v == 0;
    maximum = std::max(maximum, v);
  }
  const double fraction = zeros / double(raw.dn.size());
  std::printf("fraction at 0 DN %.4f (expected ≈ 0.5), max %d DN\n", fraction, maximum);
  EXPECT_NEAR(fraction, 0.5, 0.02);
  EXPECT_LT(maximum, 6000);  // 6 σ: nothing wrapped to 65535
}

// Read noise is not clipped at 0 e⁻: a dark frame scatters symmetrically around the black
// level (a clamp at 0 e⁻ would raise the mean by σ/√(2π) ≈ 4 DN here).
TEST(Expose, DarkFrameScattersBelowTheBlackLevel) {
  SensorSpec s = plainSpec();
  s.readNoiseE = 10.0;
  s.blackLevelDn = 100.0;
  const RawImage raw = expose(flat(128, 128, 0.0f), s, settings(), NoiseMode::kFull, 6, 0);
  const Moments m = moments(raw);
  int below = 0;
  for (const std::uint16_t v : raw.dn) below += v < 100;
  const double n = static_cast<double>(raw.dn.size());
  std::printf("dark frame around black 100: mean %.3f, %.4f below\n", m.mean, below / n);
  EXPECT_NEAR(m.mean, 100.0, 5.0 * 10.0 / std::sqrt(n));
  EXPECT_NEAR(below / n, 0.48, 0.02);  // P(N(0, 10) < −0.5)
}

TEST(Expose, NoNoiseModeAndNoiselessSensorGiveTheRoundedMean) {
  SensorSpec s = plainSpec();
  s.conversionGainEPerDn = 3.0;
  s.blackLevelDn = 17.0;
  s.readNoiseE = 5.0;
  s.prnuFraction = 0.02;
  s.dsnuE = 4.0;
  s.darkCurrentEPerS = 30.0;
  s.fullWellE = 150000.0;
  Image ramp(300, 4, {"e"});
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 300; ++x) ramp.at(x, y, 0) = static_cast<float>(x * 700 + y * 0.37);
  const ExposureSettings set = settings(0.5, 100.0);
  const RawImage none = expose(ramp, s, set, NoiseMode::kNone, 1, 0);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 300; ++x)
      ASSERT_EQ(none.at(x, y), std::floor(expectedDn(ramp.at(x, y, 0), s, set) + 0.5)) << x;
  EXPECT_EQ(none.at(0, 0), 17 + 5);   // dark signal only: 15 e⁻ / 3
  EXPECT_EQ(none.at(100, 0), 23355);  // (70000 + 15) / 3 + 17 = 23355.3
  EXPECT_EQ(none.at(299, 0), 50017);  // 209315 e⁻ > full well: 150000 / 3 + 17
  s.noiseless = true;
  EXPECT_EQ(expose(ramp, s, set, NoiseMode::kFull, 1, 0).dn, none.dn);
  // Gain follows ISO: 2 × ISO doubles the signal above black.
  const RawImage iso = expose(flat(4, 4, 3000.0f), s, settings(0.0, 200.0), NoiseMode::kNone, 1, 0);
  EXPECT_EQ(iso.at(1, 1), 17 + 2000);
  EXPECT_THROW(expose(ramp, s, settings(0.1, 0.0), NoiseMode::kNone, 1, 0), InputError);
  EXPECT_THROW(expose(ramp, s, settings(-1.0, 100.0), NoiseMode::kNone, 1, 0), InputError);
}

TEST(Expose, PhotonModeHasShotNoiseOnly) {
  SensorSpec s = plainSpec();
  s.prnuFraction = 0.05;  // would add (0.05 · 1000)² = 2500 to the variance in full mode
  s.readNoiseE = 20.0;
  const RawImage raw = expose(flat(256, 256, 1000.0f), s, settings(), NoiseMode::kPhoton, 8, 0);
  const Moments m = moments(raw);
  const double n = static_cast<double>(raw.dn.size());
  std::printf("photon mode variance %.2f (predicted %.2f)\n", m.variance, 1000.0 + 1.0 / 12.0);
  EXPECT_NEAR(m.variance, 1000.0 + 1.0 / 12.0, 5.0 * 1000.0 * std::sqrt(2.0 / n));
  EXPECT_NEAR(m.mean, 1000.0, 5.0 * std::sqrt(1000.0 / n));
}

TEST(Expose, BitIdenticalForTheSameSeedsAndIndependentOfImageSize) {
  SensorSpec s = plainSpec();
  s.prnuFraction = 0.01;
  s.dsnuE = 2.0;
  s.rowFpnE = 1.0;
  s.columnFpnE = 1.5;
  s.readNoiseE = 3.0;
  s.darkCurrentEPerS = 20.0;
  s.blackLevelDn = 200.0;
  Image big(48, 40, {"e"});
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 48; ++x)
      big.at(x, y, 0) = static_cast<float>((x * 37 + y * 101) % 900) * 3.3f;
  const RawImage a = expose(big, s, settings(), NoiseMode::kFull, 42, 3);
  EXPECT_EQ(a.dn, expose(big, s, settings(), NoiseMode::kFull, 42, 3).dn);
  const RawImage other = expose(big, s, settings(), NoiseMode::kFull, 42, 4);
  int differ = 0;
  for (size_t i = 0; i < a.dn.size(); ++i) differ += a.dn[i] != other.dn[i];
  EXPECT_GT(differ, static_cast<int>(a.dn.size() * 9 / 10));
  Image crop(20, 16, {"e"});
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 20; ++x) crop.at(x, y, 0) = big.at(x, y, 0);
  const RawImage c = expose(crop, s, settings(), NoiseMode::kFull, 42, 3);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 20; ++x) ASSERT_EQ(c.at(x, y), a.at(x, y)) << x << "," << y;
  EXPECT_EQ(a.whiteLevelDn, 65535.0);
  EXPECT_EQ(a.blackLevelDn, 200.0);
  EXPECT_EQ(a.adcBits, 16);
}

}  // namespace
}  // namespace camsim
