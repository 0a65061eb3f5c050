// `materials:` entries → MaterialDescription. Keys per type (docs/scene-format.md):
//   diffuse     reflectance
//   mirror      reflectance
//   conductor   metal | eta + k, fresnel (exact | schlick; schlick takes reflectance = R0),
//               roughness, anisotropy, distribution, masking
//   dielectric  glass | ior, roughness, anisotropy, distribution, masking
//   plastic     reflectance, specular (ks), roughness, anisotropy, distribution, masking
//   metallic_roughness  base_color, metallic, roughness (perceptual, α = r²)
//   every type  normal_map (an RGB image read raw), normal_scale
//   any type    alpha_cutout {alpha, factor, cutoff}
#include <string>
#include <vector>

#include "integrator/scene/scene_loader_parts.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {
namespace {

MaterialDescription::Type parseType(const YamlValue& type) {
  using T = MaterialDescription::Type;
  return type.choice<T>("material type");
}

// The microfacet keys shared by conductor, dielectric and plastic.
void parseMicrofacet(YamlMap& map, MaterialDescription& m, const TableSearch& search,
                     const std::filesystem::path& baseDir, std::vector<std::string>& known) {
  if (auto r = map.find("roughness"))
    m.roughness = parseTexture(*r, TextureUse::kRoughness, search, baseDir);
  if (auto a = map.find("anisotropy")) m.anisotropy = static_cast<float>(a->number(-0.99, 0.99));
  if (auto d = map.find("distribution"))
    m.distribution = d->choice<MicrofacetDistribution>("distribution");
  if (auto g = map.find("masking")) m.masking = g->choice<MaskingModel>("masking");
  known.insert(known.end(), {"roughness", "anisotropy", "distribution", "masking"});
}

// A named table shipped in luts/spectra/<folder>/<name>.csv (or found on the spectra path).
Spectrum namedColumn(const YamlValue& name, const std::string& folder, const std::string& column,
                     const TableSearch& search) {
  const std::string file = folder + "/" + name.string() + ".csv";
  const std::optional<std::filesystem::path> path = search.locate(file);
  if (!path)
    name.fail("no " + folder + " table '" + name.string() + "' (looked for " + file +
              " on the spectra path)");
  try {
    const SpectralTable table = readSpectralCsv(*path);
    return table.spectrum(table.columnIndex(column), Extrapolation::kClamp);
  } catch (const InputError& e) {
    name.fail(e.message() + " in " + path->string());
  }
}

void parseConductor(YamlMap& map, MaterialDescription& m, const TableSearch& search,
                    std::vector<std::string>& known) {
  if (auto f = map.find("fresnel")) m.fresnel = f->choice<FresnelModel>("fresnel");
  const auto metal = map.find("metal");
  const auto eta = map.find("eta");
  const auto k = map.find("k");
  known.insert(known.end(), {"fresnel", "metal", "eta", "k"});
  if (m.fresnel == FresnelModel::kSchlick) {
    if (metal || eta || k)
      (metal ? *metal
       : eta ? *eta
             : *k)
          .fail("fresnel: schlick takes 'reflectance' (R0), not η and k");
    if (!map.has("reflectance"))
      map.self().fail("fresnel: schlick needs 'reflectance' (normal-incidence R0)");
    return;
  }
  if (map.has("reflectance"))
    map.self().fail(
        "'reflectance' is for fresnel: schlick; exact Fresnel uses 'metal' or 'eta' and 'k'");
  if (metal && (eta || k)) (eta ? *eta : *k).fail("give either 'metal' or 'eta' and 'k', not both");
  if (metal) {
    m.eta = namedColumn(*metal, "metals", "eta", search);
    m.k = namedColumn(*metal, "metals", "k", search);
  } else if (eta && k) {
    m.eta = parseSpectrum(*eta, SpectrumUse::kIndex, search);
    m.k = parseSpectrum(*k, SpectrumUse::kIndex, search);
  } else {
    map.self().fail("a conductor needs 'metal' (e.g. Au, Ag, Al, Cu) or both 'eta' and 'k'");
  }
  if (!(m.eta.minValue() > 0.0) && !(m.k.minValue() > 0.0))
    map.self().fail("a conductor needs η > 0 or k > 0 at every wavelength");
}

void parseDielectric(YamlMap& map, MaterialDescription& m, const TableSearch& search,
                     std::vector<std::string>& known) {
  const auto glass = map.find("glass");
  const auto ior = map.find("ior");
  known.insert(known.end(), {"glass", "ior"});
  if (glass && ior) ior->fail("give either 'glass' or 'ior', not both");
  if (glass)
    m.eta = namedColumn(*glass, "glasses", "eta", search);
  else if (ior)
    m.eta = parseSpectrum(*ior, SpectrumUse::kIndex, search);
  if (!(m.eta.minValue() >= 1e-3))
    (glass ? *glass : *ior).fail("the index of refraction must be > 0");
}

// glTF's metallic-roughness: the base colour, metalness and perceptual roughness, each a
// constant or a texture (scalars in [0, 1]).
void parseMetallicRoughness(YamlMap& map, MaterialDescription& m, const TableSearch& search,
                            const std::filesystem::path& baseDir, std::vector<std::string>& known) {
  if (auto c = map.find("base_color"))
    m.reflectance = parseTexture(*c, TextureUse::kReflectance, search, baseDir);
  if (auto v = map.find("metallic"))
    m.metallic = parseTexture(*v, TextureUse::kFraction, search, baseDir);
  if (auto r = map.find("roughness"))
    m.roughness = parseTexture(*r, TextureUse::kFraction, search, baseDir);
  known.insert(known.end(), {"base_color", "metallic", "roughness"});
}

// Any material: a tangent-space normal map and glTF's normalTexture.scale.
void parseNormalMap(YamlMap& map, MaterialDescription& m, const TableSearch& search,
                    const std::filesystem::path& baseDir, std::vector<std::string>& known) {
  const auto scale = map.find("normal_scale");
  if (auto n = map.find("normal_map"))
    m.normalMap = parseTexture(*n, TextureUse::kNormalMap, search, baseDir);
  else if (scale)
    scale->fail("'normal_scale' needs a 'normal_map'");
  if (scale) m.normalScale = static_cast<float>(scale->number(-100.0, 100.0));
  known.insert(known.end(), {"normal_map", "normal_scale"});
}

}  // namespace

MaterialDescription parseMaterial(const std::string& name, YamlMap map, const TableSearch& search,
                                  const std::filesystem::path& baseDir) {
  MaterialDescription m;
  m.name = name;
  m.type = parseType(map.require("type"));
  std::vector<std::string> known = {"type"};
  using Type = MaterialDescription::Type;
  if (m.type == Type::kMirror) m.reflectance = TextureDescription::constant(1.0);
  if (m.type != Type::kDielectric && m.type != Type::kMetallicRoughness) {
    if (auto r = map.find("reflectance"))
      m.reflectance = parseTexture(*r, TextureUse::kReflectance, search, baseDir);
    known.push_back("reflectance");
  }
  if (m.type == Type::kConductor || m.type == Type::kDielectric || m.type == Type::kPlastic)
    parseMicrofacet(map, m, search, baseDir, known);
  if (m.type == Type::kConductor) parseConductor(map, m, search, known);
  if (m.type == Type::kDielectric) parseDielectric(map, m, search, known);
  if (m.type == Type::kPlastic) {
    if (auto ks = map.find("specular")) m.specularWeight = static_cast<float>(ks->number(0.0, 1.0));
    known.push_back("specular");
  }
  if (m.type == Type::kMetallicRoughness) parseMetallicRoughness(map, m, search, baseDir, known);
  parseNormalMap(map, m, search, baseDir, known);
  if (auto a = map.find("alpha_cutout")) m.alphaCutout = parseAlphaCutout(*a, search, baseDir);
  known.push_back("alpha_cutout");
  map.finish(known);
  return m;
}

// Any material: where factor · alpha < cutoff the surface is cut away (see
// integrator/textures/alpha_cutout.h). `alpha` is a scalar texture read raw, as roughness
// maps are: a number, {texture: FILE, …} or {checkerboard: …}.
MaterialDescription::AlphaCutout parseAlphaCutout(const YamlValue& value, const TableSearch& search,
                                                  const std::filesystem::path& baseDir) {
  YamlMap map(value);
  MaterialDescription::AlphaCutout a;
  if (auto t = map.find("alpha"))
    a.texture = parseTexture(*t, TextureUse::kRoughness, search, baseDir);
  if (auto f = map.find("factor")) a.factor = static_cast<float>(f->number(0.0, 1e6));
  if (auto c = map.find("cutoff")) a.cutoff = static_cast<float>(c->number(0.0, 1e6));
  map.finish({"alpha", "factor", "cutoff"});
  return a;
}

}  // namespace camsim
