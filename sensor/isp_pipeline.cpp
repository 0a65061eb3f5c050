#include "sensor/isp_pipeline.h"

#include <algorithm>

#include "sensor/check.h"
#include "sensor/color_space.h"
#include "sensor/isp_black_level.h"
#include "sensor/spectral_data.h"

namespace camsim {

DevelopedImage developRaw(const std::vector<RawImage>& raws, const SensorSpec& sensor,
                          const IspSettings& settings,
                          const std::filesystem::path& colorCheckerCsv) {
  CAMSIM_CHECK(!raws.empty());
  DevelopedImage out;
  const Spectrum illuminant = cieIlluminant(settings.illuminant);
  if (sensor.cfa.isStacked()) {
    // X, Y, Z planes: no demosaic, no CCM; only XYZ(D65) → working space.
    const Image xyz = normalizeStackedRaw(raws);
    out.whiteBalance.assign(3, 1.0);
    out.colorCorrection.xyzToWorking = xyzD65ToWorkingSpace(RgbColorSpace::acesCg());
    out.colorCorrection.workingSpace = RgbColorSpace::acesCg().name();
    out.working = applyColorMatrix(xyz, out.colorCorrection.xyzToWorking, {"R", "G", "B"});
    return out;
  }
  CAMSIM_CHECK(raws.size() == 1);
  const CfaLayout& cfa = sensor.cfa;
  Image mosaic = normalizeRaw(raws.front());
  switch (settings.whiteBalance) {
    case IspSettings::WhiteBalance::kIlluminant:
      out.whiteBalance = whiteBalanceFromIlluminant(sensor, illuminant);
      break;
    case IspSettings::WhiteBalance::kRegion:
      out.whiteBalance = whiteBalanceFromRegion(mosaic, cfa, settings.region);
      break;
    case IspSettings::WhiteBalance::kGreyWorld:
      out.whiteBalance = whiteBalanceGreyWorld(mosaic, cfa);
      break;
  }
  mosaic = applyWhiteBalance(mosaic, cfa, out.whiteBalance);
  // Highlight clipping: a photosite that saturated (≥ 1 before the gains) would turn
  // coloured once its channel is multiplied; clip every channel where the channel with
  // the smallest gain saturates, so clipped highlights stay neutral (as dcraw does).
  const double clipLevel = *std::min_element(out.whiteBalance.begin(), out.whiteBalance.end());
  for (float& v : mosaic.pixels) v = std::min(v, static_cast<float>(clipLevel));
  const Image camera = cfa.isMonochrome() ? mosaic : demosaic(mosaic, cfa, settings.demosaic);
  if (cfa.isMonochrome()) {  // one channel: no colour to correct
    out.working = camera;
    out.working.channels = {"Y"};
    return out;
  }
  out.colorCorrection = fitColorCorrection(sensor.qe, illuminant, colorCheckerCsv);
  out.working = applyColorMatrix(camera, out.colorCorrection.cameraToWorking(), {"R", "G", "B"});
  return out;
}

}  // namespace camsim
