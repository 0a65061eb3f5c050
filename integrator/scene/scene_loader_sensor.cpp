// The scene loader's `sensor:` block (docs/scene-format.md): which sensor, ISO, noise,
// auto-exposure and brackets. The sensor description itself is parsed by sensor/.
#include <cmath>
#include <cstdio>

#include "integrator/scene/scene_loader.h"
#include "integrator/scene/scene_loader_parts.h"
#include "sensor/model/sensor_noise.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {

std::string bracketSuffix(double ev) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "_ev%+g", ev);
  return buf;
}

SensorSettings parseSensorSettings(YamlMap map, const std::filesystem::path& baseDir,
                                   const YamlValue& camera, PhysicalCameraParams& cameraParams) {
  SensorSettings s;
  const YamlValue model = map.require("model");
  std::string name = model.string();
  // A sensor file is relative to the scene, like every other file a scene names.
  if (isSensorSpecPath(name) && std::filesystem::path(name).is_relative())
    name = (baseDir / name).string();
  try {
    s.spec = loadSensorSpec(name, lutsDirectory());
  } catch (const InputError& e) {
    model.failInNamedFile(e);  // an error inside the sensor file keeps its own place too
  }
  s.iso = s.spec.baseIso;
  if (auto v = map.find("iso")) {
    s.iso = v->number(setting_ranges::kIso.lo, setting_ranges::kIso.hi);
    try {
      (void)noiseAtIso(s.spec, s.iso);  // a calibrated sensor's ISO range (its iso_table)
    } catch (const InputError& e) {
      v->fail(e.message());
    }
  }
  if (auto v = map.find("noise")) s.noise = v->choice<NoiseMode>("noise mode");
  if (auto v = map.find("noise_seed"))
    s.noiseSeed = static_cast<std::uint64_t>(
        v->integer(setting_ranges::kNoiseSeed.lo, setting_ranges::kNoiseSeed.hi));
  if (auto v = map.find("frame")) s.frame = static_cast<std::uint64_t>(v->integer(0, INT64_MAX));
  if (auto v = map.find("auto_exposure")) {
    YamlMap ae(*v);
    AutoExposure a;
    if (auto m = ae.find("metering")) {
      using M = AutoExposure::Metering;
      a.metering = m->choice<M>("metering");
      if (a.metering == M::kPercentile) a.target = 0.9;
    }
    if (auto t = ae.find("target")) a.target = t->number(0.0, 1.0, true);
    if (auto p = ae.find("percentile")) {
      if (a.metering != AutoExposure::Metering::kPercentile)
        p->fail("percentile needs metering: percentile");
      a.percentile = p->number(0.0, 100.0, true);
    }
    ae.finish({"metering", "target", "percentile"});
    s.autoExposure = a;
  }
  if (auto b = map.find("bracket_ev")) {
    s.bracketEv = b->numbers();
    if (s.bracketEv.empty() || s.bracketEv.size() > 16)
      b->fail("give 1 to 16 exposure offsets in stops");
    for (size_t i = 0; i < s.bracketEv.size(); ++i) {
      s.bracketEv[i] += 0.0;  // -0 is +0: one exposure, one file name
      if (std::abs(s.bracketEv[i]) > 20.0) b->fail("exposure offsets must lie within ±20 stops");
      for (size_t j = 0; j < i; ++j)
        if (bracketSuffix(s.bracketEv[j]) == bracketSuffix(s.bracketEv[i]))
          b->fail("offsets " + std::to_string(j) + " and " + std::to_string(i) +
                  " name the same files (NAME" + bracketSuffix(s.bracketEv[i]) +
                  ".dng: 6 significant digits): give each exposure once");
    }
  }
  map.finish({"model", "iso", "noise", "noise_seed", "frame", "auto_exposure", "bracket_ev"});

  // The sensor sets the pixel geometry; the camera must not contradict it.
  YamlMap cameraKeys(camera);
  for (const char* key : kSensorGeometryKeys)
    if (auto v = cameraKeys.find(key))
      v->fail(std::string(key) +
              " conflicts with the sensor's pixel pitch and fill factor: remove it");
  cameraParams.sensorSize = glm::dvec2(cameraParams.resolution) * s.spec.pixelPitchM;
  cameraParams.fillFactor = s.spec.fillFactor;
  return s;
}

namespace {

// Whether a whole CFA tile, aligned with the tile grid, lies inside the region (what the
// white balance averages: white_balance.cpp).
bool holdsCfaTile(const CfaLayout& cfa, const PixelRegion& r) {
  const int x0 = (r.x + cfa.width - 1) / cfa.width * cfa.width;
  const int y0 = (r.y + cfa.height - 1) / cfa.height * cfa.height;
  return x0 + cfa.width <= r.x + r.width && y0 + cfa.height <= r.y + r.height;
}

}  // namespace

IspSettings parseIspSettings(YamlMap map, const SensorSpec& sensor, glm::ivec2 resolution,
                             std::map<std::string, SourceLocation>& keyPlaces) {
  IspSettings isp;
  keyPlaces["isp"] = map.self().where();
  std::optional<YamlValue> wbValue = map.find("white_balance");
  if (wbValue) {
    using W = IspSettings::WhiteBalance;
    isp.whiteBalance = wbValue->choice<W>("white balance");
    keyPlaces["isp.white_balance"] = wbValue->where();
  }
  if (auto ill = map.find("illuminant")) {
    isp.illuminant = ill->string();
    try {
      cieIlluminant(isp.illuminant);
    } catch (const InputError& e) {
      ill->fail(e.message());
    }
  }
  if (auto r = map.find("region")) {
    if (isp.whiteBalance != IspSettings::WhiteBalance::kRegion)
      r->fail("region needs white_balance: region");
    const std::vector<YamlValue> v = r->items();
    if (v.size() != 4) r->fail("expected [x, y, width, height] in pixels");
    isp.region = {
        static_cast<int>(v[0].integer(0, 1 << 20)), static_cast<int>(v[1].integer(0, 1 << 20)),
        static_cast<int>(v[2].integer(1, 1 << 20)), static_cast<int>(v[3].integer(1, 1 << 20))};
    keyPlaces["isp.region"] = r->where();
    const PixelRegion& g = isp.region;
    if (g.x + g.width > resolution.x || g.y + g.height > resolution.y)
      r->fail("the region [" + std::to_string(g.x) + ", " + std::to_string(g.y) + ", " +
              std::to_string(g.width) + ", " + std::to_string(g.height) + "] is not inside the " +
              std::to_string(resolution.x) + " × " + std::to_string(resolution.y) + " image");
    if (!holdsCfaTile(sensor.cfa, g))
      r->fail("the region holds no whole " + std::to_string(sensor.cfa.width) + " × " +
              std::to_string(sensor.cfa.height) + " CFA tile (aligned with the tile grid)");
  } else if (isp.whiteBalance == IspSettings::WhiteBalance::kRegion) {
    map.self().fail("white_balance: region needs region: [x, y, width, height]");
  }
  if (isp.whiteBalance == IspSettings::WhiteBalance::kGreyWorld &&
      !holdsCfaTile(sensor.cfa, {0, 0, resolution.x, resolution.y}))
    wbValue->fail("grey_world needs an image of at least one whole " +
                  std::to_string(sensor.cfa.width) + " × " + std::to_string(sensor.cfa.height) +
                  " CFA tile; the image is " + std::to_string(resolution.x) + " × " +
                  std::to_string(resolution.y));
  if (auto d = map.find("demosaic")) isp.demosaic = d->choice<DemosaicMethod>("demosaic");
  map.finish({"white_balance", "illuminant", "region", "demosaic"});
  return isp;
}

}  // namespace camsim
