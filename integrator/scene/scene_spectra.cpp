#include "integrator/scene/scene_spectra.h"

#include "sensor/base/file_status.h"
#include "sensor/base/format.h"
#include "sensor/spectra/color_space.h"
#include "sensor/spectra/rgb_uplift.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {
namespace {

Spectrum fromTable(YamlMap& map, SpectrumUse use, const TableSearch& search) {
  const YamlValue file = map.require("csv");
  const std::filesystem::path path = search.find(file, file.string());
  SpectralTable table;
  try {
    table = readSpectralCsv(path);
  } catch (const InputError& e) {
    file.failInNamedFile(e);
  }
  size_t column = 0;
  if (const auto col = map.find("column")) {
    try {
      column = table.columnIndex(col->string());
    } catch (const InputError& e) {
      col->fail(e.message() + " in " + path.string());
    }
  } else if (table.columns.size() != 1) {
    map.self().fail("table " + path.string() + " has several columns: name one with 'column'");
  }
  map.finish({"csv", "column"});
  Spectrum s = table.spectrum(
      column, use == SpectrumUse::kEmission ? Extrapolation::kZero : Extrapolation::kClamp);
  if (s.minValue() < 0.0) file.fail("spectral table has negative values");
  if (use == SpectrumUse::kReflectance && s.maxValue() > 1.0)
    file.fail("reflectance must lie in [0, 1]; the table exceeds 1");
  // The ranges an inline value has (1e3 for an index, 1e30 for an emission shape): past
  // 3.4e38 the float spectrum is infinite, and an emitter's light distribution was NaN (a
  // failed check, exit 134); an ior of 1e300 from a table was taken.
  const double hi = use == SpectrumUse::kIndex ? 1e3 : 1e30;
  if (!(s.maxValue() <= hi))
    file.fail("spectral table has values above " + formatShortest(hi) +
              (use == SpectrumUse::kIndex ? " (an index of refraction's limit, as inline)"
                                          : " (as an inline value)"));
  return s;
}

}  // namespace

Spectrum parseSpectrum(const YamlValue& value, SpectrumUse use, const TableSearch& search) {
  const bool reflectance = use == SpectrumUse::kReflectance;
  if (use == SpectrumUse::kIndex) {
    if (value.isScalar()) return Spectrum::constant(value.number(0.0, 1e3));
    YamlMap map(value);
    if (map.has("csv")) return fromTable(map, use, search);
    map.self().fail("expected a number or {csv: file, column: name}");
  }
  if (value.isScalar()) {
    return Spectrum::constant(reflectance ? value.number(0.0, 1.0) : value.number(0.0, 1e30));
  }
  YamlMap map(value);
  if (map.has("rgb")) {
    const YamlValue rgbValue = *map.find("rgb");
    const glm::dvec3 rgb = rgbValue.vec3();
    map.finish({"rgb"});
    const double hi = reflectance ? 1.0 : 1e30;
    for (int i = 0; i < 3; ++i)
      if (rgb[i] < 0.0 || rgb[i] > hi)
        rgbValue.fail(reflectance ? "RGB reflectance components must lie in [0, 1]"
                                  : "RGB components must lie in [0, 1e30]");
    if (reflectance) return rgbToReflectance(rgb, RgbColorSpace::linearRec709());
    if (rgb.x + rgb.y + rgb.z == 0.0) return Spectrum::constant(0.0);
    return rgbToEmissionShape(rgb, RgbColorSpace::linearRec709());
  }
  if (map.has("csv")) return fromTable(map, use, search);
  if (map.has("blackbody") || map.has("illuminant")) {
    if (reflectance) map.self().fail("a reflectance cannot be a blackbody or an illuminant");
    if (const auto t = map.find("blackbody")) {
      const double kelvin = t->number(100.0, 1e6);
      map.finish({"blackbody"});
      return Spectrum::blackbody(kelvin);
    }
    const YamlValue name = *map.find("illuminant");
    map.finish({"illuminant"});
    try {
      return cieIlluminant(name.string());
    } catch (const InputError& e) {
      name.fail(e.message());
    }
  }
  map.self().fail(reflectance ? "expected a number in [0, 1], {rgb: [...]} or {csv: ...}"
                              : "expected a number, {rgb}, {csv}, {blackbody} or {illuminant}");
}

}  // namespace camsim
