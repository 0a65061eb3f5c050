// The scene loader's `lights:` part: point, spot, distant (sun) and environment lights in
// absolute units (docs/scene-format.md, `lights`). World up is +y; azimuths are compass
// bearings seen from above with +z as north and −x as east.
//
// | key (type)                 | unit | conversion to the LightDescription |
// |----------------------------|------|------------------------------------|
// | intensity (point, spot)    | cd   | I = S · cd / (683 Σ S ȳ Δλ)         |
// | power (point, spot)        | W    | I = S · P / (Ω Σ S Δλ)              |
// | lumens (point, spot)       | lm   | I = S · lm / (Ω · 683 Σ S ȳ Δλ)     |
// | illuminance (distant)      | lx   | E = S · lx / (683 Σ S ȳ Δλ)         |
// | irradiance (distant)       | W/m² | E = S · W / Σ S Δλ                  |
// | scale (environment)        | —    | s = scale                           |
// | illuminance (environment)  | lx   | s = lx / E_v(map at scale 1)        |
//
// S: the `spectrum` (default D65); Ω = 4π (point) or the spot's ∫ falloff dω.
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>

#include <glm/geometric.hpp>

#include "integrator/lights/environment_light.h"
#include "integrator/lights/spot_light.h"
#include "integrator/scene/scene_loader.h"
#include "integrator/scene/scene_loader_parts.h"
#include "sensor/base/file_status.h"
#include "sensor/io/exr_io.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {
namespace {

constexpr double kMaxValue = 1e30;

double degrees(const YamlValue& v, double lo, double hi, bool loOpen = false) {
  return v.number(lo, hi, loOpen) * std::numbers::pi / 180.0;
}

// The `spectrum` key (relative shape, default D65).
struct SpectralShape {
  Spectrum s;
  std::optional<YamlValue> where;
};

SpectralShape parseShapeSpectrum(YamlMap& map, const TableSearch& search) {
  SpectralShape shape;
  shape.where = map.find("spectrum");
  shape.s = shape.where ? parseSpectrum(*shape.where, SpectrumUse::kEmission, search)
                        : cieIlluminant("D65");
  return shape;
}

// shape · factor, checked for the single-precision range. `photometric`: factor is per
// unit of luminous quantity (the shape must be visible).
Spectrum scaled(const SpectralShape& shape, const YamlValue& amount, double value, bool photometric,
                double solidAngle) {
  const double per = photometric ? luminance(shape.s) : shape.s.sum();
  if (!(per > 0.0))
    (shape.where ? *shape.where : amount)
        .fail(photometric
                  ? "this spectrum has no visible power, so it cannot have a photometric amount"
                  : "this spectrum is zero over 360–830 nm");
  const Spectrum out = shape.s * (value / (solidAngle * per));
  if (!std::isfinite(out.maxValue())) amount.fail("the value exceeds the single-precision range");
  if (!(out.maxValue() > 0.0)) amount.fail("the value is too small (it is 0 in single precision)");
  return out;
}

// Exactly one of the keys; returns its index in `names`.
size_t oneOf(YamlMap& map, const std::vector<std::string>& names, std::optional<YamlValue>& value) {
  size_t chosen = names.size();
  for (size_t i = 0; i < names.size(); ++i) {
    if (auto v = map.find(names[i])) {
      if (value)
        v->fail("give only one of " + names[0] + ", " + names[1] +
                (names.size() > 2 ? ", " + names[2] : ""));
      value = v;
      chosen = i;
    }
  }
  if (!value) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "'" : "', '") + n;
    map.self().fail("needs one of " + list + "'");
  }
  return chosen;
}

glm::vec3 unitDirection(const YamlValue& v) {
  const glm::dvec3 d = v.vec3();
  if (!(glm::length(d) > 0.0)) v.fail("direction must not be zero");
  return glm::vec3(glm::normalize(d));
}

// Point and spot: intensity on the axis from cd, W or lm.
Spectrum parseIntensity(YamlMap& map, const TableSearch& search, double solidAngle) {
  const SpectralShape shape = parseShapeSpectrum(map, search);
  std::optional<YamlValue> v;
  const size_t which = oneOf(map, {"intensity", "power", "lumens"}, v);
  const double amount = v->number(0.0, kMaxValue, true);
  if (which == 0) return scaled(shape, *v, amount, true, 1.0);
  return scaled(shape, *v, amount, which == 2, solidAngle);
}

void parsePoint(YamlMap& map, LightDescription& d, const TableSearch& search,
                const glm::dvec3& origin) {
  const YamlValue position = map.require("position");
  d.position = toPoint(position, position.vec3() - origin);
  d.spectrum = parseIntensity(map, search, 4.0 * std::numbers::pi);
}

void parseSpot(YamlMap& map, LightDescription& d, const TableSearch& search,
               const glm::dvec3& origin) {
  const YamlValue position = map.require("position");
  const glm::dvec3 p = position.vec3();
  d.position = toPoint(position, p - origin);
  std::optional<YamlValue> aim;
  if (oneOf(map, {"direction", "look_at"}, aim) == 0) {
    d.direction = unitDirection(*aim);
  } else {
    const glm::dvec3 to = aim->vec3() - p;
    if (!(glm::length(to) > 0.0)) aim->fail("look_at equals position");
    d.direction = glm::vec3(glm::normalize(to));
  }
  double cone = 30.0 * std::numbers::pi / 180.0;
  if (auto c = map.find("cone_angle")) cone = degrees(*c, 0.0, 180.0, true);
  double start = std::max(0.0, cone - 5.0 * std::numbers::pi / 180.0);
  if (auto f = map.find("falloff_start")) {
    start = degrees(*f, 0.0, 180.0);
    if (start > cone) f->fail("falloff_start must not exceed cone_angle");
  }
  d.coneAngle = static_cast<float>(cone);
  d.falloffStart = std::min(static_cast<float>(start), d.coneAngle);
  d.spectrum = parseIntensity(map, search, SpotLight::effectiveSolidAngle(cone, start));
}

void parseDistant(YamlMap& map, LightDescription& d, const TableSearch& search) {
  std::optional<YamlValue> dir;
  const auto elevation = map.find("elevation");
  const auto azimuth = map.find("azimuth");
  if (auto v = map.find("direction")) {
    if (elevation || azimuth) v->fail("give either direction or elevation/azimuth, not both");
    d.direction = unitDirection(*v);
  } else if (elevation) {
    const double el = degrees(*elevation, -90.0, 90.0);
    const double az = azimuth ? degrees(*azimuth, -360.0, 360.0) : 0.0;
    // toward the sun: azimuth clockwise from +z (north) seen from above, −x is east
    const glm::dvec3 toSun(-std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
    d.direction = glm::vec3(-toSun);
  } else {
    (azimuth ? *azimuth : map.self()).fail("needs 'direction' or 'elevation' (and 'azimuth')");
  }
  double diameter = 0.53;
  if (auto a = map.find("angular_diameter")) {
    diameter = a->number(0.0, 90.0);
    if (diameter > 0.0 && diameter < SceneLimits::kMinSunDiameterDeg)
      a->fail(
          "a disc smaller than 0.001° is lost to rounding: use 0 for parallel light (limit "
          "SceneLimits::kMinSunDiameterDeg)");
  }
  d.angularDiameter = static_cast<float>(diameter * std::numbers::pi / 180.0);
  const SpectralShape shape = parseShapeSpectrum(map, search);
  std::optional<YamlValue> v;
  const size_t which = oneOf(map, {"illuminance", "irradiance"}, v);
  d.spectrum = scaled(shape, *v, v->number(0.0, kMaxValue, true), which == 0, 1.0);
}

std::shared_ptr<const Image> readMap(const YamlValue& file, const std::filesystem::path& path) {
  if (!isRegularFile(path)) file.fail("environment map '" + path.string() + "' not found");
  ExrFile exr;
  try {
    exr = readExr(path);
  } catch (const InputError& e) {
    file.fail(e.message());
  }
  const Image& img = exr.image;
  const int r = img.channelIndex("R"), g = img.channelIndex("G"), b = img.channelIndex("B");
  if (r < 0 || g < 0 || b < 0)
    file.fail("environment map '" + path.string() + "' needs channels R, G and B");
  if (exr.chromaticities) {
    const ExrChromaticities& c = *exr.chromaticities;
    const RgbColorSpace& s = RgbColorSpace::linearRec709();
    auto near = [](Chromaticity a, Chromaticity e) {
      return std::abs(a.x - e.x) + std::abs(a.y - e.y) < 2e-3;
    };
    if (!near(c.red, s.red()) || !near(c.green, s.green()) || !near(c.blue, s.blue()) ||
        !near(c.white, s.white()))
      file.fail("environment map '" + path.string() +
                "' is not in linear Rec.709 (its chromaticities differ)");
  }
  bool lit = false;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c : {r, g, b}) {
        const float v = img.at(x, y, c);
        if (!std::isfinite(v))
          file.fail("environment map '" + path.string() + "' has a non-finite value at pixel (" +
                    std::to_string(x) + ", " + std::to_string(y) + ")");
        lit = lit || v > 0.0f;
      }
  if (!lit) file.fail("environment map '" + path.string() + "' is black");
  return std::make_shared<const Image>(std::move(exr.image));
}

void parseEnvironment(YamlMap& map, LightDescription& d, const std::filesystem::path& baseDir) {
  const YamlValue file = map.require("file");
  d.file = file.string();
  if (d.file.is_relative()) d.file = baseDir / d.file;
  d.image = readMap(file, d.file);
  std::optional<YamlValue> v;
  if (oneOf(map, {"scale", "illuminance"}, v) == 0) {
    d.spectrum = Spectrum::constant(v->number(0.0, kMaxValue, true));
  } else {
    const double unit = EnvironmentLight::zenithIlluminance(*d.image);
    if (!(unit > 0.0))
      v->fail("the map is black above the horizon, so it cannot give an illuminance");
    d.spectrum = Spectrum::constant(v->number(0.0, kMaxValue, true) / unit);
  }
  if (!std::isfinite(d.spectrum.maxValue()) || !(d.spectrum.maxValue() > 0.0))
    v->fail("the scale is outside the single-precision range");
  double rotation = 0.0;
  if (auto r = map.find("rotation")) rotation = degrees(*r, -360.0, 360.0);
  // Map space (+z zenith) → world (+y up): map +x → −z, map +y → −x, so the image centre
  // (u = ½) lies north (+z) and u grows eastwards (−x); then turn by −rotation about +y
  // (clockwise seen from above: the map's content moves to larger azimuths).
  const glm::dmat3 base(glm::dvec3(0.0, 0.0, -1.0), glm::dvec3(-1.0, 0.0, 0.0),
                        glm::dvec3(0.0, 1.0, 0.0));
  const double c = std::cos(-rotation), s = std::sin(-rotation);
  const glm::dmat3 turn(glm::dvec3(c, 0.0, -s), glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(s, 0.0, c));
  d.worldFromLight = turn * base;
}

LightDescription parseLight(YamlMap map, size_t index, const TableSearch& search,
                            const std::filesystem::path& baseDir, const glm::dvec3& origin) {
  LightDescription d;
  d.label = "lights[" + std::to_string(index) + "]";
  if (auto n = map.find("name")) d.label = n->string();
  const YamlValue type = map.require("type");
  const std::string t = type.string();
  std::vector<std::string> known = {"type", "name"};
  if (t == "point") {
    d.kind = LightDescription::Kind::kPoint;
    parsePoint(map, d, search, origin);
    known.insert(known.end(), {"position", "spectrum", "intensity", "power", "lumens"});
  } else if (t == "spot") {
    d.kind = LightDescription::Kind::kSpot;
    parseSpot(map, d, search, origin);
    known.insert(known.end(), {"position", "direction", "look_at", "cone_angle", "falloff_start",
                               "spectrum", "intensity", "power", "lumens"});
  } else if (t == "distant") {
    d.kind = LightDescription::Kind::kDistant;
    parseDistant(map, d, search);
    known.insert(known.end(), {"direction", "elevation", "azimuth", "angular_diameter", "spectrum",
                               "illuminance", "irradiance"});
  } else if (t == "environment") {
    d.kind = LightDescription::Kind::kEnvironment;
    parseEnvironment(map, d, baseDir);
    search.noteRead(d.file);
    known.insert(known.end(), {"file", "scale", "illuminance", "rotation"});
  } else {
    type.fail("unknown light type '" + t + "' (known: point, spot, distant, environment)");
  }
  map.finish(known);
  return d;
}

}  // namespace

std::vector<LightDescription> parseLights(const YamlValue& lights, const TableSearch& search,
                                          const std::filesystem::path& baseDir,
                                          const glm::dvec3& renderOrigin) {
  std::vector<LightDescription> out;
  const std::vector<YamlValue> items = lights.items();
  for (size_t i = 0; i < items.size(); ++i)
    out.push_back(parseLight(YamlMap(items[i]), i, search, baseDir, renderOrigin));
  return out;
}

}  // namespace camsim
