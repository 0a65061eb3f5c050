// An ELD-calibrated preset measured as `camsim ptc` measures it (measurePhotonTransfer: dark
// and flat frames at an ISO, dark_frame_analysis.h): the Tukey-λ scale, the temporal row
// noise and the Gaussian read noise at three gains agree with ELD's published log-linear
// fits (Wei et al., CVPR 2020 / TPAMI 2021; Vandermode/ELD camera_params, copied below from
// eld_camera_params.json) evaluated at the measured K, within 3 %.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "sensor/model/photon_transfer.h"
#include "sensor/model/sensor_spec.h"
#include "tests/support/lut_paths.h"

namespace camsim::eld_preset_ptc_test {
namespace {

// SonyA7S2, Profile-1: ln σ = slope · ln K + bias.
struct Fit {
  double slope, bias;
  double at(double k) const { return std::exp(slope * std::log(k) + bias); }
};
constexpr Fit kGaussian{0.5407496082896145, 1.218237123334061};  // g_scale
constexpr Fit kTukey{0.46210495986526035, 0.5657147358616816};   // G_scale
constexpr Fit kRow{0.5275360468633209, -0.5917002648887661};     // R_scale

// 512² photosites (half of them green, the analysed channel) and 32 dark frames:
// the row σ's standard error is ≈ 1 %, the Tukey scale's ≈ 0.5 %.
PtcOptions options(double iso) {
  PtcOptions o;
  o.iso = iso;
  o.width = o.height = 512;
  o.levels = 50;
  o.spatialFrames = 32;
  o.seed = 37;
  return o;
}

TEST(EldPresetPtc, SonyA7S2MeasuresAsThePublishedFits) {
  const SensorSpec preset = loadSensorSpec("eld-sony-a7s2", test::kLuts);
  SensorSpec gaussian = preset;  // ELD's G+P baseline: the same fits, Gaussian read noise
  gaussian.noise.shape = ReadNoiseShape::kGaussian;
  for (double iso : {800.0, 3200.0, 6400.0}) {
    SCOPED_TRACE(iso);
    const PtcResult tukey = measurePhotonTransfer(preset, options(iso));
    const double k = tukey.systemGainK;
    EXPECT_NEAR(k, 0.09391607086816033 * iso / 100.0, 0.01 * k);  // K within 1 %
    const DarkFrameAnalysis& d = tukey.data.dark;
    EXPECT_NEAR(d.tukeyScaleDn.value / kTukey.at(k), 1.0, 0.03)
        << d.tukeyScaleDn.value << " ± " << d.tukeyScaleDn.uncertainty << " DN";
    EXPECT_NEAR(d.rowTemporalDn.value / kRow.at(k), 1.0, 0.03)
        << d.rowTemporalDn.value << " ± " << d.rowTemporalDn.uncertainty << " DN";
    const PtcResult normal = measurePhotonTransfer(gaussian, options(iso));
    const DarkFrameAnalysis& g = normal.data.dark;
    EXPECT_NEAR(g.readGaussianDn.value / kGaussian.at(normal.systemGainK), 1.0, 0.03)
        << g.readGaussianDn.value << " ± " << g.readGaussianDn.uncertainty << " DN";
    std::printf(
        "ISO %g: K %.4f; Tukey scale %.4f (ELD %.4f), row %.4f (ELD %.4f), Gaussian σ %.4f "
        "(ELD %.4f) DN\n",
        iso, k, d.tukeyScaleDn.value, kTukey.at(k), d.rowTemporalDn.value, kRow.at(k),
        g.readGaussianDn.value, kGaussian.at(normal.systemGainK));
  }
}

}  // namespace
}  // namespace camsim::eld_preset_ptc_test
