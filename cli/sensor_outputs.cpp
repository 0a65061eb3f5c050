#include "cli/sensor_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>

#include "integrator/scene/scene_loader.h"
#include "sensor/io/dng_writer.h"
#include "sensor/io/exr_io.h"
#include "sensor/isp/isp_pipeline.h"
#include "sensor/model/sensor_model.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {
namespace {

std::string evSuffix(double ev, bool bracketed) {
  if (!bracketed) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "_ev%+g", ev);
  return buf;
}

Image scaled(const Image& image, double k) {
  Image out = image;
  for (float& v : out.pixels) v = static_cast<float>(static_cast<double>(v) * k);
  return out;
}

}  // namespace

SensorOutputs writeSensorFrames(const SensorSettings& sensor, const IspSettings& isp,
                                const DngCapture& capture, const std::string& name,
                                double exposureTimeS, bool sceneMoves, const Image& electrons,
                                const std::function<Image(double)>& rerender, const Metadata& meta,
                                OutputSet& outputs, std::ostream& log) {
  const SensorSpec& spec = sensor.spec;
  SensorOutputs result;
  double& exposureScale = result.exposureScale;
  Image base = electrons;
  if (sensor.autoExposure) {
    exposureScale =
        autoExposureScale(electrons, *sensor.autoExposure, spec.saturationElectrons(sensor.iso));
    base = sceneMoves ? rerender(exposureScale) : scaled(electrons, exposureScale);
    log << "auto-exposure (" << meteringName(sensor.autoExposure->metering) << ", target "
        << sensor.autoExposure->target << " of saturation): exposure time "
        << exposureTimeS * exposureScale << " s (x" << exposureScale << " the scene's), ISO "
        << sensor.iso << "\n";
  }
  const bool bracketed = !sensor.bracketEv.empty();
  const std::vector<double> evs = bracketed ? sensor.bracketEv : std::vector<double>{0.0};
  // The DNG's colour follows the ISP's white balance: matrices for its illuminant (and D65),
  // AsShotNeutral from the gains it applies to each frame.
  DngColor color =
      spec.qe.size() == 3 && !spec.cfa.isStacked()
          ? dngColorFromQe(spec.qe, isp.illuminant,
                           lutsDirectory() / "spectra" / "colorchecker_classic_reflectance.csv")
          : DngColor{};
  const size_t reference =
      static_cast<size_t>(std::find(evs.begin(), evs.end(), 0.0) == evs.end()
                              ? 0
                              : std::find(evs.begin(), evs.end(), 0.0) - evs.begin());
  for (size_t i = 0; i < evs.size(); ++i) {
    const double k = std::exp2(evs[i]);
    const Image frameElectrons =
        evs[i] == 0.0 ? base : (sceneMoves ? rerender(exposureScale * k) : scaled(base, k));
    SensorFrameReport report;
    report.ev = evs[i];
    report.exposureTimeS = exposureTimeS * exposureScale * k;
    const ExposureSettings settings{report.exposureTimeS, sensor.iso};
    // A mosaic is one plane; a stacked sensor exposes each channel plane (own noise seed).
    std::vector<Image> stackedPlanes;
    if (frameElectrons.channelCount() > 1)
      for (int c = 0; c < frameElectrons.channelCount(); ++c)
        stackedPlanes.push_back(frameElectrons.channel(c));
    const auto plane = [&](size_t c) -> const Image& {
      return stackedPlanes.empty() ? frameElectrons : stackedPlanes[c];
    };
    std::vector<RawImage> raws;
    for (size_t c = 0; c < static_cast<size_t>(frameElectrons.channelCount()); ++c)
      raws.push_back(expose(plane(c), spec, settings, sensor.noise,
                            sensor.noiseSeed + static_cast<std::uint64_t>(c) * 0x9e3779b9u,
                            sensor.frame + i));
    size_t clipped = 0, total = 0;
    for (const RawImage& raw : raws) {
      for (std::uint16_t v : raw.dn) clipped += static_cast<double>(v) >= raw.whiteLevelDn ? 1 : 0;
      total += raw.dn.size();
    }
    report.clippedFraction =
        total == 0 ? 0.0 : static_cast<double>(clipped) / static_cast<double>(total);
    Metadata frameMeta = meta;
    for (auto& [key, value] : frameMeta)
      if (key == "camsim:units")
        value =
            "raw.DN: raw digital numbers as the ADC gives them, black level "
            "included; electrons.<channel>: the noise-free expected photo-electrons per "
            "photosite at this frame's exposure";
    frameMeta.insert(frameMeta.end(),
                     {{"camsim:sensor", spec.name},
                      {"camsim:iso", std::to_string(sensor.iso)},
                      {"camsim:exposure_time_s", std::to_string(report.exposureTimeS)},
                      {"camsim:noise_seed", std::to_string(sensor.noiseSeed)},
                      {"camsim:frame", std::to_string(sensor.frame + i)}});
    const std::string stem = name + evSuffix(evs[i], bracketed);
    if (!spec.cfa.isStacked()) {
      report.dngFile = stem + ".dng";
      if (spec.qe.size() == 3)
        color.asShotNeutral = dngNeutralFromGains(whiteBalanceGains(raws, spec, isp));
      DngCapture frameCapture = capture;
      frameCapture.exposureTimeS = report.exposureTimeS;
      frameCapture.iso = sensor.iso;
      writeDng(outputs.add(report.dngFile), raws.front(), color, frameMeta, frameCapture);
      report.rawExrFile = stem + "_raw.exr";
      writeRawExr(outputs.add(report.rawExrFile), raws.front(), frameElectrons, frameMeta);
    } else {
      for (size_t c = 0; c < raws.size(); ++c) {
        report.rawExrFile = stem + "_raw_" + spec.cfa.channels[c] + ".exr";
        writeRawExr(outputs.add(report.rawExrFile), raws[c], plane(c), frameMeta);
      }
    }
    if (i == reference) result.referenceRaws = std::move(raws);
    result.frames.push_back(report);
  }
  return result;
}

}  // namespace camsim
