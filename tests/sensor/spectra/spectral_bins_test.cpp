// The bins of equal probability and SpectralBins (sensor/spectra/spectral_bins.h).
#include "sensor/spectra/spectral_bins.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace camsim {
namespace {

// Each bin holds 1/16 of the visible pdf: its integral by the midpoint rule on a 1e-3 nm
// grid (error ≈ 1e-9 of a bin) against 1/16 within 1e-6.
TEST(SpectralBins, EachBinHoldsAnEqualShareOfTheVisiblePdf) {
  EXPECT_EQ(binEdgeNm(0), 360.0);
  EXPECT_EQ(binEdgeNm(kSpectralBins), 830.0);
  for (int b = 0; b < kSpectralBins; ++b) {
    const double lo = binEdgeNm(b), hi = binEdgeNm(b + 1);
    ASSERT_LT(lo, hi);
    const int n = static_cast<int>((hi - lo) / 1e-3);
    const double h = (hi - lo) / n;
    double mass = 0.0;
    for (int i = 0; i < n; ++i)
      mass += static_cast<double>(visibleWavelengthPdf(static_cast<float>(lo + (i + 0.5) * h))) * h;
    EXPECT_NEAR(mass, 1.0 / kSpectralBins, 1e-6) << "bin " << b;
    EXPECT_EQ(binOf(binCentreNm(b)), b);
    EXPECT_GT(binCentreNm(b), lo);
    EXPECT_LT(binCentreNm(b), hi);
  }
  // Narrow at the pdf's peak, wide in the tails.
  EXPECT_NEAR(binEdgeNm(8), 545.9, 0.05);
  EXPECT_LT(binEdgeNm(8) - binEdgeNm(7), 16.0);
  EXPECT_NEAR(binEdgeNm(1) - binEdgeNm(0), 45.2, 0.05);
  EXPECT_NEAR(binEdgeNm(16) - binEdgeNm(15), 114.3, 0.05);
}

// A sampled wavelength's bin (from its place u in the CDF) is the bin its λ lies in;
// ties only within float rounding (2e-4 nm) of an edge.
TEST(SpectralBins, SampledWavelengthsKnowTheirBins) {
  int checked = 0;
  for (int k = 0; k < 4096; ++k) {
    const SampledWavelengths w = SampledWavelengths::sampleVisible((k + 0.37f) / 4096.0f);
    for (int i = 0; i < kWavelengthSamples; ++i) {
      const double lambda = w[i];
      const int b = w.bin(i);
      ASSERT_GE(b, 0);
      ASSERT_LT(b, kSpectralBins);
      EXPECT_GT(lambda, binEdgeNm(b) - 1e-3) << "λ " << lambda << " bin " << b;
      EXPECT_LT(lambda, binEdgeNm(b + 1) + 1e-3) << "λ " << lambda << " bin " << b;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 4096 * kWavelengthSamples);
  const SampledWavelengths u = SampledWavelengths::sampleUniform(0.3f);
  for (int i = 0; i < kWavelengthSamples; ++i) EXPECT_EQ(u.bin(i), binOf(u[i]));
  for (int k = 0; k < kSpectralBins / kWavelengthSamples; ++k) {
    const SampledWavelengths& c = SampledWavelengths::binCentres(k);
    for (int i = 0; i < kWavelengthSamples; ++i) {
      EXPECT_EQ(c.bin(i), k * kWavelengthSamples + i);
      EXPECT_EQ(c[i], binCentreNm(c.bin(i)));
    }
  }
}

// ∫_bin a·b of piecewise-linear spectra: the bins of 1·1 sum to 470 nm; of a ramp times a
// constant, the closed form c·(λ₁² − λ₀²)/2 per bin (1e-9 relative: double rounding); of a
// spectrum with a steep step between 500 and 501 nm and the ramp: quadratic on each piece,
// which Simpson's rule integrates exactly: checked against a 1e-3 nm midpoint sum (1e-6).
TEST(SpectralBins, BinIntegralsAreExactForPiecewiseLinearSpectra) {
  const Spectrum one = Spectrum::constant(1.0);
  double total = 0.0;
  for (double v : binIntegrals(one, one)) total += v;
  EXPECT_NEAR(total, 470.0, 1e-9);

  const std::array<double, 2> x{360.0, 830.0}, y{360.0, 830.0};
  const Spectrum ramp = Spectrum::fromSamples(x, y, Extrapolation::kZero);
  const Spectrum three = Spectrum::constant(3.0);
  const std::array<double, kSpectralBins> r = binIntegrals(ramp, three);
  for (int b = 0; b < kSpectralBins; ++b) {
    const double lo = binEdgeNm(b), hi = binEdgeNm(b + 1);
    EXPECT_NEAR(r[static_cast<std::size_t>(b)] / (1.5 * (hi * hi - lo * lo)), 1.0, 1e-9);
  }

  const std::array<double, 4> kx{360.0, 500.0, 501.0, 830.0}, ky{0.2, 0.9, 0.1, 0.6};
  const Spectrum kinked = Spectrum::fromSamples(kx, ky, Extrapolation::kZero);
  const std::array<double, kSpectralBins> q = binIntegrals(kinked, ramp);
  for (int b = 0; b < kSpectralBins; ++b) {
    const double lo = binEdgeNm(b), hi = binEdgeNm(b + 1);
    const int n = static_cast<int>((hi - lo) / 1e-3);
    const double h = (hi - lo) / n;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const auto l = static_cast<float>(lo + (i + 0.5) * h);
      sum += static_cast<double>(kinked(l)) * static_cast<double>(ramp(l)) * h;
    }
    EXPECT_NEAR(q[static_cast<std::size_t>(b)] / sum, 1.0, 1e-6) << "bin " << b;
  }
}

TEST(SpectralBins, Arithmetic) {
  SpectralBins a(0.0f);
  EXPECT_TRUE(a.isZero());
  EXPECT_TRUE(a.isFinite());
  for (int b = 0; b < kSpectralBins; ++b) a[b] = static_cast<float>(b + 1);
  EXPECT_FALSE(a.isZero());
  EXPECT_EQ(a.maxComponent(), 16.0f);
  EXPECT_EQ(a.sum(), 136.0f);
  SpectralBins b(2.0f);
  b.addScaled(a, 0.5f);
  EXPECT_EQ(b[13], 9.0f);
  EXPECT_EQ((a * b)[15], 16.0f * 10.0f);
  a[13] = -1.0f;
  a[7] = 100.0f;
  EXPECT_EQ(a.maxComponent(), 100.0f);
  // isZero and isFinite see every bin (each quarter of the vector).
  for (int k = 0; k < kSpectralBins; ++k) {
    SpectralBins z(0.0f);
    z[k] = 1e-30f;
    EXPECT_FALSE(z.isZero()) << k;
    z[k] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(z.isFinite()) << k;
    z[k] = -std::numeric_limits<float>::infinity();
    EXPECT_FALSE(z.isFinite()) << k;
    z[k] = 3e38f;
    EXPECT_TRUE(z.isFinite()) << k;
  }
  // A constant spectrum's averages: a step from 0 at 599 nm to 1 at 600 nm (the 1 nm grid's
  // ramp) is 0 below and 1 above, its bin holding 600 nm the share above plus ½ nm.
  const std::array<double, 4> sx{360.0, 599.999, 600.0, 830.0}, sy{0.0, 0.0, 1.0, 1.0};
  const SpectralBins step = binAverages(Spectrum::fromSamples(sx, sy, Extrapolation::kClamp));
  const int b600 = binOf(600.0f);
  EXPECT_EQ(step[b600 - 1], 0.0f);
  EXPECT_NEAR(step[b600 + 1], 1.0, 1e-6);
  EXPECT_NEAR(step[b600],
              (binEdgeNm(b600 + 1) - 600.0 + 0.5) / (binEdgeNm(b600 + 1) - binEdgeNm(b600)), 1e-6);
  const SampledWavelengths w = SampledWavelengths::sampleVisible(0.1f);
  const SampledSpectrum s = b.at(w);
  for (int i = 0; i < kWavelengthSamples; ++i) EXPECT_EQ(s[i], b[w.bin(i)]);
}

}  // namespace
}  // namespace camsim
