// Tests for sensor/model/ptc_statistics.cpp: the photon transfer at several ISOs of sensors
// described in YAML (the parser's keys), whose fits across ISOs must give back the
// configured K, σ_pre and σ_post within 2 %, and the dual-conversion-gain step at its ISO.
// Fixed noise seeds; 128 × 128 photosites (8192 analysed G photosites), 50 levels, 16
// frames per stack: about a second per ISO in Release.
#include "sensor/model/ptc_statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sensor/model/sensor_noise.h"
#include "sensor/model/sensor_spec.h"

namespace camsim::ptc_statistics_test {
namespace {

SensorSpec sensorFrom(const std::string& extra) {
  const std::string text =
      "name: test-iso\n"
      "pixel_pitch_um: 4.0\n"
      "cfa: RGGB\n"
      "qe: {curves: cameras/nikon_d850.csv, peak_qe: 0.5}\n"
      "full_well_e: 20000\n"
      "conversion_gain_e_per_dn: 4.0\n"
      "base_iso: 100\n"
      "adc_bits: 16\n"
      "black_level_dn: 1024\n"
      "dark_current_e_per_s: 0\n"
      "prnu_percent: 0.5\n"
      "dsnu_e: 0.5\n"
      "pattern_seed: 5\n" +
      extra;
  return parseSensorSpec(text, "test-iso.yaml", CAMSIM_LUTS_DIR, CAMSIM_LUTS_DIR);
}

PtcOptions smallOptions(double iso, std::uint64_t seed) {
  PtcOptions o;
  o.width = o.height = 128;
  o.levels = 50;
  o.iso = iso;
  o.seed = seed;
  return o;
}

struct Measured {
  std::vector<IsoPoint> points;
  std::vector<PtcResult> results;
  IsoFit fit;
};

Measured measureAt(const SensorSpec& s, const std::vector<double>& isos) {
  Measured m;
  for (double iso : isos) {
    const PtcResult r = measurePhotonTransfer(s, smallOptions(iso, 11));
    m.points.push_back(isoPoint(r, photonTransferUncertainty(r)));
    m.results.push_back(r);
  }
  m.fit = fitAcrossIsos(m.points);
  return m;
}

double rel(double measured, double configured) {
  return std::abs(measured / configured - 1.0);
}

TEST(PtcAcrossIsos, RecoversGainAndTheDarkNoiseSplit) {
  // K = 0.25, 2, 8 DN/e⁻; σ_pre = 2 e⁻ dominates at ISO 3200, σ_post = 3 DN at ISO 100.
  const SensorSpec s = sensorFrom("read_noise_e: 2.0\nread_noise_post_dn: 3.0\n");
  const Measured m = measureAt(s, {100, 800, 3200});
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const double k = s.systemGain(m.points[i].iso);
    EXPECT_LT(rel(m.points[i].systemGainK.value, k), 0.02) << m.points[i].iso;
    // The stated standard error is the right size: the error is within 4 u.
    EXPECT_LT(std::abs(m.points[i].systemGainK.value - k),
              4.0 * m.points[i].systemGainK.uncertainty)
        << m.points[i].iso << ": " << m.points[i].systemGainK.value << " ± "
        << m.points[i].systemGainK.uncertainty;
  }
  ASSERT_EQ(m.fit.segments.size(), 1u);
  ASSERT_TRUE(m.fit.splitFitted);
  const GainSegment& g = m.fit.segments[0];
  EXPECT_LT(rel(g.gainPerIso.value * 100.0, 0.25), 0.02) << g.gainPerIso.value;
  EXPECT_LT(rel(g.sigmaPreE.value, 2.0), 0.02)
      << g.sigmaPreE.value << " ± " << g.sigmaPreE.uncertainty;
  EXPECT_LT(rel(m.fit.sigmaPostDn.value, 3.0), 0.02)
      << m.fit.sigmaPostDn.value << " ± " << m.fit.sigmaPostDn.uncertainty;
  EXPECT_GT(g.sigmaPreE.uncertainty, 0.0);
  EXPECT_EQ(m.fit.dof, 1);
  std::printf(
      "[ measured ] K %.5g %.5g %.5g DN/e-; sigma_pre %.4f +- %.4f e-; sigma_post %.4f +- %.4f "
      "DN\n",
      m.points[0].systemGainK.value, m.points[1].systemGainK.value, m.points[2].systemGainK.value,
      g.sigmaPreE.value, g.sigmaPreE.uncertainty, m.fit.sigmaPostDn.value,
      m.fit.sigmaPostDn.uncertainty);
  // σ_d(ISO) from the split against the configuration's.
  for (double iso : {100.0, 800.0, 3200.0}) {
    const double k = s.systemGain(iso);
    EXPECT_LT(rel(fittedDarkNoiseE(m.fit, iso), std::sqrt(4.0 + 9.0 / (k * k))), 0.02) << iso;
  }
}

TEST(PtcAcrossIsos, DualConversionGainStepsAtItsIso) {
  // Low gain: 4 e⁻/DN at ISO 100, σ_pre 3 e⁻; from ISO 800: 1.5 e⁻/DN there, σ_pre 1 e⁻.
  const SensorSpec s = sensorFrom(
      "read_noise_e: 3.0\nread_noise_post_dn: 2.0\n"
      "dual_conversion_gain: {iso: 800, conversion_gain_e_per_dn: 1.5, read_noise_e: 1.0}\n");
  ASSERT_TRUE(noiseAtIso(s, 800).highConversionGain);
  const Measured m = measureAt(s, {200, 400, 800, 1600});
  ASSERT_EQ(m.fit.segments.size(), 2u);
  const GainSegment& low = m.fit.segments[0];
  const GainSegment& high = m.fit.segments[1];
  EXPECT_EQ(low.isoMax, 400.0);
  EXPECT_EQ(high.isoMin, 800.0);  // the step lies between the two: at 800 as configured
  EXPECT_LT(rel(low.gainPerIso.value * 100.0, 0.25), 0.02) << low.gainPerIso.value;
  EXPECT_LT(rel(high.gainPerIso.value * 800.0, 1.0 / 1.5), 0.02) << high.gainPerIso.value;
  ASSERT_TRUE(m.fit.splitFitted);
  EXPECT_LT(rel(low.sigmaPreE.value, 3.0), 0.03)
      << low.sigmaPreE.value << " ± " << low.sigmaPreE.uncertainty;
  EXPECT_LT(rel(high.sigmaPreE.value, 1.0), 0.05)
      << high.sigmaPreE.value << " ± " << high.sigmaPreE.uncertainty;
  EXPECT_LT(rel(m.fit.sigmaPostDn.value, 2.0), 0.03) << m.fit.sigmaPostDn.value;
  std::printf(
      "[ measured ] DCG: K/ISO %.6g | %.6g; sigma_pre %.4f +- %.4f | %.4f +- %.4f e-; sigma_post "
      "%.4f DN\n",
      low.gainPerIso.value, high.gainPerIso.value, low.sigmaPreE.value, low.sigmaPreE.uncertainty,
      high.sigmaPreE.value, high.sigmaPreE.uncertainty, m.fit.sigmaPostDn.value);
  // The configured values at each ISO follow the mode.
  for (const PtcResult& r : m.results) {
    PtcOptions o = smallOptions(r.iso, 1);
    EXPECT_EQ(configuredPhotonTransfer(s, o).highConversionGain, r.iso >= 800.0);
  }
}

TEST(PtcAcrossIsos, OneIsoHasNoSplit) {
  IsoPoint p;
  p.iso = 100;
  p.systemGainK = {0.25, 0.001};
  p.darkVariance = {9.25, 0.03};
  const IsoFit fit = fitAcrossIsos({p});
  ASSERT_EQ(fit.segments.size(), 1u);
  EXPECT_FALSE(fit.splitFitted);
  EXPECT_NEAR(fit.segments[0].gainPerIso.value, 0.0025, 1e-12);
}

TEST(PtcAcrossIsos, ExactSplitOnSyntheticPoints) {
  // y = K²·4 + 9 at three ISOs: σ_pre = 2 e⁻, σ_post = 3 DN exactly.
  std::vector<IsoPoint> points;
  for (double iso : {100.0, 800.0, 3200.0}) {
    const double k = iso / 400.0;
    points.push_back({iso, {k, 1e-4 * k}, {4.0 * k * k + 9.0, 0.01}});
  }
  const IsoFit fit = fitAcrossIsos(points);
  ASSERT_TRUE(fit.splitFitted);
  EXPECT_NEAR(fit.segments[0].sigmaPreE.value, 2.0, 1e-9);
  EXPECT_NEAR(fit.sigmaPostDn.value, 3.0, 1e-9);
  EXPECT_NEAR(fit.chi2, 0.0, 1e-9);
}

}  // namespace
}  // namespace camsim::ptc_statistics_test
