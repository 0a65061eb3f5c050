#include "sensor/isp/isp_pipeline.h"

#include <algorithm>

#include "sensor/base/check.h"
#include "sensor/isp/isp_black_level.h"
#include "sensor/spectra/color_space.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {

namespace {

// Gains from the normalised image: a mosaic (with its CFA) or a stacked sensor's planes.
std::vector<double> gainsOf(const Image& normalised, const SensorSpec& sensor,
                            const IspSettings& settings) {
  const bool stacked = sensor.cfa.isStacked();
  switch (settings.whiteBalance) {
    case IspSettings::WhiteBalance::kRegion:
      return stacked ? whiteBalanceFromRegion(normalised, settings.region)
                     : whiteBalanceFromRegion(normalised, sensor.cfa, settings.region);
    case IspSettings::WhiteBalance::kGreyWorld:
      return stacked ? whiteBalanceGreyWorld(normalised)
                     : whiteBalanceGreyWorld(normalised, sensor.cfa);
    case IspSettings::WhiteBalance::kIlluminant:
      break;
  }
  return whiteBalanceFromIlluminant(sensor, cieIlluminant(settings.illuminant));
}

Image normalised(const std::vector<RawImage>& raws, const SensorSpec& sensor) {
  CAMSIM_CHECK(!raws.empty() && (sensor.cfa.isStacked() || raws.size() == 1));
  return sensor.cfa.isStacked() ? normalizeStackedRaw(raws) : normalizeRaw(raws.front());
}

}  // namespace

std::vector<double> whiteBalanceGains(const std::vector<RawImage>& raws, const SensorSpec& sensor,
                                      const IspSettings& settings) {
  return gainsOf(normalised(raws, sensor), sensor, settings);
}

DevelopedImage developRaw(const std::vector<RawImage>& raws, const SensorSpec& sensor,
                          const IspSettings& settings, const std::filesystem::path& colorCheckerCsv,
                          const std::vector<double>* gains) {
  DevelopedImage out;
  const Spectrum illuminant = cieIlluminant(settings.illuminant);
  Image mosaic = normalised(raws, sensor);
  out.whiteBalance = gains ? *gains : gainsOf(mosaic, sensor, settings);
  if (sensor.cfa.isStacked()) {
    // X, Y, Z planes: no demosaic, no CCM; the white's XYZ adapted to the D65 white (Y
    // kept: both have Y = 1), then XYZ(D65) → working space.
    const std::vector<double>& g = out.whiteBalance;
    const glm::dvec3 white(1.0 / g[0], 1.0 / g[1], 1.0 / g[2]);
    out.colorCorrection.whiteBalance = glm::dvec3(g[0], g[1], g[2]);
    out.colorCorrection.adaptation = bradfordAdaptation(white / white.y, d65WhiteXyz());
    out.colorCorrection.cameraToXyz = out.colorCorrection.adaptation;
    out.colorCorrection.xyzToWorking = xyzD65ToWorkingSpace(RgbColorSpace::acesCg());
    out.colorCorrection.workingSpace = RgbColorSpace::acesCg().name();
    out.working = applyColorMatrix(mosaic, out.colorCorrection.cameraToWorking(), {"R", "G", "B"});
    return out;
  }
  const CfaLayout& cfa = sensor.cfa;
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

Image workingRgb(const DevelopedImage& developed) {
  const Image& plane = developed.working;
  if (plane.channelCount() != 1) return plane;
  Image grey(plane.width, plane.height, {"R", "G", "B"});
  for (std::size_t p = 0; p < plane.pixels.size(); ++p)
    for (std::size_t c = 0; c < 3; ++c) grey.pixels[p * 3 + c] = plane.pixels[p];
  return grey;
}

}  // namespace camsim
