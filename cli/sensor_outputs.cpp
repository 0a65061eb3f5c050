#include "cli/sensor_outputs.h"

#include <cmath>
#include <cstdio>
#include <ostream>

#include "integrator/scene_loader.h"
#include "sensor/dng_writer.h"
#include "sensor/exr_io.h"
#include "sensor/sensor_model.h"
#include "sensor/spectral_data.h"

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

std::vector<SensorFrameReport> writeSensorFrames(const SensorSettings& sensor, const std::string& name,
                                                 double exposureTimeS, bool sceneMoves, const Image& electrons,
                                                 const std::function<Image(double)>& rerender,
                                                 const Metadata& meta, OutputSet& outputs, std::ostream& log,
                                                 double& exposureScale) {
  const SensorSpec& spec = sensor.spec;
  exposureScale = 1.0;
  Image base = electrons;
  if (sensor.autoExposure) {
    exposureScale = autoExposureScale(electrons, *sensor.autoExposure, spec.saturationElectrons(sensor.iso));
    base = sceneMoves ? rerender(exposureScale) : scaled(electrons, exposureScale);
    log << "auto-exposure (" << meteringName(sensor.autoExposure->metering) << ", target "
        << sensor.autoExposure->target << " of saturation): exposure time " << exposureTimeS * exposureScale
        << " s (x" << exposureScale << " the scene's), ISO " << sensor.iso << "\n";
  }
  const bool bracketed = !sensor.bracketEv.empty();
  const std::vector<double> evs = bracketed ? sensor.bracketEv : std::vector<double>{0.0};
  const DngColor color = spec.qe.size() == 3 && !spec.cfa.isStacked()
                             ? dngColorFromQe(spec.qe, cieIlluminant("D65"),
                                              lutsDirectory() / "spectra" / "colorchecker_classic_reflectance.csv")
                             : DngColor{};
  std::vector<SensorFrameReport> reports;
  for (size_t i = 0; i < evs.size(); ++i) {
    const double k = std::exp2(evs[i]);
    const Image frameElectrons = evs[i] == 0.0 ? base : (sceneMoves ? rerender(exposureScale * k) : scaled(base, k));
    SensorFrameReport report;
    report.ev = evs[i];
    report.exposureTimeS = exposureTimeS * exposureScale * k;
    const ExposureSettings settings{report.exposureTimeS, sensor.iso};
    const RawImage raw = expose(frameElectrons, spec, settings, sensor.noise, sensor.noiseSeed, sensor.frame + i);
    size_t clipped = 0;
    for (std::uint16_t v : raw.dn) clipped += static_cast<double>(v) >= raw.whiteLevelDn ? 1 : 0;
    report.clippedFraction = raw.dn.empty() ? 0.0 : static_cast<double>(clipped) / static_cast<double>(raw.dn.size());
    Metadata frameMeta = meta;
    frameMeta.insert(frameMeta.end(), {{"camsim:sensor", spec.name},
                                       {"camsim:iso", std::to_string(sensor.iso)},
                                       {"camsim:exposure_time_s", std::to_string(report.exposureTimeS)},
                                       {"camsim:noise_seed", std::to_string(sensor.noiseSeed)},
                                       {"camsim:frame", std::to_string(sensor.frame + i)}});
    const std::string stem = name + evSuffix(evs[i], bracketed);
    if (!spec.cfa.isStacked()) {
      report.dngFile = stem + ".dng";
      writeDng(outputs.add(report.dngFile), raw, color, frameMeta);
    }
    report.rawExrFile = stem + "_raw.exr";
    writeRawExr(outputs.add(report.rawExrFile), raw, frameElectrons, frameMeta);
    reports.push_back(report);
  }
  return reports;
}

}  // namespace camsim
