// developRaw on a neutral grey under a non-D65 illuminant: every white-balance method
// (illuminant, grey region, grey world) makes it neutral, for a Bayer sensor (gains + CCM)
// and for the stacked ideal-xyz sensor (Bradford adaptation of the planes), and the gains
// it reports are the ones whiteBalanceGains computes from the same raws (what the DNG's
// AsShotNeutral carries). The noise-free electrons are the closed form
// c_k = Σ QE_k ρ I λ (white_balance.h), scaled to 40 % of saturation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "sensor/isp/isp_pipeline.h"
#include "sensor/model/sensor_model.h"
#include "sensor/spectra/spectral_data.h"
#include "tests/support/lut_paths.h"

namespace camsim {
namespace {

// Raws of a uniform grey card of reflectance 0.5 under `illuminant`, 16 × 16 photosites.
std::vector<RawImage> greyCardRaws(const SensorSpec& spec, const std::string& illuminant) {
  const std::vector<double> c =
      cameraResponse(spec.qe, Spectrum::constant(0.5), cieIlluminant(illuminant));
  double peak = 0.0;
  for (double v : c) peak = std::max(peak, v);
  const double k = 0.4 * spec.saturationElectrons(spec.baseIso) / peak;
  const ExposureSettings exposure{0.01, spec.baseIso};
  std::vector<RawImage> raws;
  if (spec.cfa.isStacked()) {
    for (size_t ch = 0; ch < c.size(); ++ch) {
      Image plane(16, 16, {spec.cfa.channels[ch]});
      for (float& v : plane.pixels) v = static_cast<float>(c[ch] * k);
      raws.push_back(expose(plane, spec, exposure, NoiseMode::kNone, 0, 0));
    }
  } else {
    Image mosaic(16, 16, {"e"});
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x)
        mosaic.at(x, y, 0) =
            static_cast<float>(c[static_cast<size_t>(spec.cfa.channelAt(x, y))] * k);
    raws.push_back(expose(mosaic, spec, exposure, NoiseMode::kNone, 0, 0));
  }
  return raws;
}

class GreyUnderF11 : public testing::TestWithParam<std::string> {};

TEST_P(GreyUnderF11, EveryWhiteBalanceMakesItNeutral) {
  const SensorSpec spec = loadSensorSpec(GetParam(), test::kLuts);
  const std::vector<RawImage> raws = greyCardRaws(spec, "F11");
  for (const auto method :
       {IspSettings::WhiteBalance::kIlluminant, IspSettings::WhiteBalance::kRegion,
        IspSettings::WhiteBalance::kGreyWorld}) {
    IspSettings isp;
    isp.illuminant = "F11";
    isp.whiteBalance = method;
    isp.region = {4, 4, 8, 8};
    const DevelopedImage dev = developRaw(raws, spec, isp, test::kColorChecker);
    EXPECT_EQ(dev.whiteBalance, whiteBalanceGains(raws, spec, isp));
    double gainSpread = 0.0;
    for (double g : dev.whiteBalance) gainSpread = std::max(gainSpread, std::abs(g - 1.0));
    EXPECT_GT(gainSpread, 0.05) << "F11 is not D65: some gain must differ from 1";
    const glm::dvec3 rgb(dev.working.at(8, 8, 0), dev.working.at(8, 8, 1), dev.working.at(8, 8, 2));
    std::printf("[measured] %s, F11, method %d: ACEScg R/G %.5f B/G %.5f\n", GetParam().c_str(),
                static_cast<int>(method), rgb.x / rgb.y, rgb.z / rgb.y);
    EXPECT_NEAR(rgb.x / rgb.y, 1.0, 1e-3) << static_cast<int>(method);
    EXPECT_NEAR(rgb.z / rgb.y, 1.0, 1e-3) << static_cast<int>(method);
  }
}

INSTANTIATE_TEST_SUITE_P(Sensors, GreyUnderF11, testing::Values("ideal-xyz", "fullframe-d850"),
                         [](const testing::TestParamInfo<std::string>& p) {
                           return p.param == "ideal-xyz" ? std::string("IdealXyz")
                                                         : std::string("FullframeD850");
                         });

// Under D65 the ideal-xyz sensor's adaptation is the identity (its planes are XYZ).
TEST(IspStacked, D65AdaptationIsTheIdentity) {
  const SensorSpec spec = loadSensorSpec("ideal-xyz", test::kLuts);
  const DevelopedImage dev =
      developRaw(greyCardRaws(spec, "D65"), spec, IspSettings{}, test::kColorChecker);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(dev.colorCorrection.adaptation[c][r], r == c ? 1.0 : 0.0, 1e-4);
}

}  // namespace
}  // namespace camsim
