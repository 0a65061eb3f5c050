// glTF materials and KHR_lights_punctual lights as camsim's (docs/scene-format.md, "glTF
// assets", lists every mapping):
//
// | glTF                                   | camsim                                          |
// |----------------------------------------|-------------------------------------------------|
// | pbrMetallicRoughness                   | metallic_roughness material (Appendix B)        |
// | baseColorFactor × baseColorTexture     | base colour: texels sRGB-decoded, × factor, uplifted |
// |   × COLOR_0                            |   × the mesh's vertex colours (MeshData::colors)  |
// | KHR_texture_transform, texCoord        | the texture's uv transform (below); one uv set    |
// | metallicRoughnessTexture B, G × factor | metallic, roughness maps (one channel each)     |
// | normalTexture, .scale                  | normal map, normal scale                        |
// | occlusionTexture                       | ignored (a path tracer computes occlusion; noted) |
// | emissiveFactor × strength × texture    | uniform emission of the shapes: luminance =      |
// |                                        | emissive_luminance · Y(emissive) (texture: mean) |
// | alphaMode MASK / BLEND, alphaCutoff    | alpha cut-out (BLEND as MASK at 0.5, noted)      |
// | KHR_materials_transmission > 0, _ior   | dielectric, η = ior, α = roughness²              |
// | point / spot light, intensity (cd)     | point / spot light, I_v = intensity · Y(color)   |
// | directional light (lx)                 | distant light, E_v = intensity · Y(color)        |
// | light range                            | ignored (inverse-square falloff kept; noted)     |
// Y(c) = 0.2126 r + 0.7152 g + 0.0722 b (linear Rec.709); colours become spectra through
// rgbToEmissionShape (lights) and the reflectance uplift (textures, constants).
//
// KHR_texture_transform works in glTF's uv, whose v runs down the image; camsim's runs up
// (v_camsim = 1 − v_gltf, gltf_accessors.cpp). With F(u, v) = (u, 1 − v) the glTF map
// uv' = o + R_gltf(r) · (uv ⊙ s) becomes, in camsim's uv, F ∘ that ∘ F:
//   uv' = R(r) · (uv ⊙ s) + (o.x + s.y sin r, 1 − o.y − s.y cos r)
// with R(r) the counter-clockwise rotation in camsim's (u, v) (TextureDescription::
// uvRotation): the same turn of the image as glTF's counter-clockwise one.
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <glm/geometric.hpp>

#include "integrator/scene/gltf_convert.h"
#include "integrator/scene/scene_loader.h"
#include "integrator/textures/texture_encoding.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/color_space.h"
#include "sensor/spectra/rgb_uplift.h"

namespace camsim {
namespace {

double lumaOf(const glm::dvec3& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

// A texture of the given channels of a glTF image, each value f(texel), as camsim's
// decoded texels (no file: the description keeps them, see releaseDecodedImages).
template <typename F>
TextureDescription imageTexture(const GltfImage& image, int channels, F f) {
  auto out = std::make_shared<TextureImage>();
  out->width = image.texels->width;
  out->height = image.texels->height;
  out->channels = channels;
  const size_t n = static_cast<size_t>(out->width) * static_cast<size_t>(out->height);
  out->values.resize(n * static_cast<size_t>(channels));
  for (size_t p = 0; p < n; ++p)
    for (int c = 0; c < channels; ++c)
      out->values[p * static_cast<size_t>(channels) + static_cast<size_t>(c)] =
          static_cast<float>(f(&image.texels->values[p * 4], c));
  TextureDescription d;
  d.kind = TextureDescription::Kind::kImage;
  d.image = std::move(out);
  d.encoding = TextureEncoding::kLinear;
  return d;
}

// The texture's KHR_texture_transform (above) on a converted texture.
TextureDescription transformed(TextureDescription d, const GltfTextureRef& ref) {
  const double s = std::sin(ref.uvRotation), c = std::cos(ref.uvRotation);
  d.uvScale = glm::vec2(ref.uvScale);
  d.uvOffset =
      glm::vec2(ref.uvOffset.x + ref.uvScale.y * s, 1.0 - ref.uvOffset.y - ref.uvScale.y * c);
  d.uvRotation = static_cast<float>(ref.uvRotation);
  return d;
}

void note(SceneDescription& scene, const GltfInclude& inc, const std::string& what) {
  scene.notes.push_back(inc.where + ": " + what);
}

// `base`, or base#2, base#3, … : the first name no material of the scene has.
std::string uniqueName(const SceneDescription& scene, const std::string& base) {
  std::string name = base;
  for (int k = 2;; ++k) {
    bool clash = false;
    for (const MaterialDescription& m : scene.materials) clash = clash || m.name == name;
    if (!clash) return name;
    name = base + "#" + std::to_string(k);
  }
}

// The include's materials, converting each (image, use, factor) once: materials that share
// an image and a factor share its converted texels.
struct MaterialConverter {
  enum class Use { kBaseColor, kMetallic, kRoughness, kNormal, kAlpha };
  const GltfInclude& inc;
  SceneDescription& scene;
  std::map<std::tuple<int, Use, double, double, double>, TextureDescription> converted;

  template <typename F>
  TextureDescription texture(int image, Use use, const glm::dvec3& factor, int channels, F f) {
    TextureDescription& t = converted[{image, use, factor.x, factor.y, factor.z}];
    if (!t.image) {
      t = imageTexture(inc.doc.images[static_cast<size_t>(image)], channels, f);
      if (use != Use::kBaseColor) t.encoding = TextureEncoding::kRaw;
    }
    return t;
  }

  MaterialDescription convert(const GltfMaterial& m, const std::string& name) {
    MaterialDescription d;
    d.name = name;
    const double roughness = std::clamp(m.roughnessFactor, 0.0, 1.0);
    for (const std::string& ext : m.otherExtensions)
      note(scene, inc, m.path + ".extensions." + ext + ": not supported, ignored");
    // doubleSided needs nothing: camsim's surfaces reflect on both sides (single-sided
    // culling is a rasteriser's optimisation, not a material property).
    if (m.transmission > 0.0) {
      d.type = MaterialDescription::Type::kDielectric;
      d.eta = Spectrum::constant(m.ior > 0.0 ? m.ior : 1.5);
      d.roughness = TextureDescription::constant(roughness * roughness);
      note(scene, inc,
           m.path + ": KHR_materials_transmission " + std::to_string(m.transmission) +
               " → a clear dielectric (η " + std::to_string(m.ior) +
               "); the base colour tint and partial transmission are not modelled");
      return withCutout(m, std::move(d));
    }
    d.type = MaterialDescription::Type::kMetallicRoughness;
    const glm::dvec3 base(m.baseColorFactor);
    if (m.baseColorTexture.image >= 0) {
      d.reflectance = transformed(
          texture(m.baseColorTexture.image, Use::kBaseColor, base, 3,
                  [&](const float* t, int c) {
                    return std::clamp(srgbDecode(static_cast<double>(t[c])) * base[c], 0.0, 1.0);
                  }),
          m.baseColorTexture);
    } else {  // base in [0, 1] (gltf_read_materials.cpp)
      d.reflectance.value = rgbToReflectance(base, RgbColorSpace::linearRec709());
    }
    const double metallic = std::clamp(m.metallicFactor, 0.0, 1.0);
    if (const int im = m.metallicRoughnessTexture.image; im >= 0) {
      d.metallic = transformed(
          texture(im, Use::kMetallic, glm::dvec3(metallic), 1,
                  [&](const float* t, int) { return static_cast<double>(t[2]) * metallic; }),
          m.metallicRoughnessTexture);
      d.roughness = transformed(
          texture(im, Use::kRoughness, glm::dvec3(roughness), 1,
                  [&](const float* t, int) { return static_cast<double>(t[1]) * roughness; }),
          m.metallicRoughnessTexture);
    } else {
      d.metallic = TextureDescription::constant(metallic);
      d.roughness = TextureDescription::constant(roughness);
    }
    if (m.normalTexture.image >= 0) {
      d.normalMap = transformed(texture(m.normalTexture.image, Use::kNormal, glm::dvec3(1.0), 3,
                                        [](const float* t, int c) { return t[c]; }),
                                m.normalTexture);
      d.normalScale = static_cast<float>(m.normalTexture.scale);
    }
    return withCutout(m, std::move(d));
  }

  // The parts every converted material shares: the occlusion note and the alpha cut-out.
  MaterialDescription withCutout(const GltfMaterial& m, MaterialDescription d) {
    if (m.occlusionTexture.image >= 0)
      note(scene, inc, m.path + ".occlusionTexture: ignored (the path tracer computes occlusion)");
    if (m.alphaMode == GltfMaterial::AlphaMode::kOpaque) return d;
    if (lumaOf(m.emissiveFactor * m.emissiveStrength) > 0.0) {
      note(scene, inc,
           m.path +
               ".alphaMode: ignored on an emissive material (camsim's emitters cannot be "
               "cut out)");
      return d;
    }
    MaterialDescription::AlphaCutout a;
    a.factor = static_cast<float>(m.baseColorFactor.a);
    a.cutoff =
        m.alphaMode == GltfMaterial::AlphaMode::kMask ? static_cast<float>(m.alphaCutoff) : 0.5f;
    if (m.baseColorTexture.image >= 0)
      a.texture = transformed(texture(m.baseColorTexture.image, Use::kAlpha, glm::dvec3(1.0), 1,
                                      [](const float* t, int) { return t[3]; }),
                              m.baseColorTexture);
    d.alphaCutout = a;
    if (m.alphaMode == GltfMaterial::AlphaMode::kBlend)
      note(scene, inc, m.path + ".alphaMode: BLEND is treated as MASK with alphaCutoff 0.5");
    return d;
  }
};

}  // namespace

std::vector<int> addGltfMaterials(const GltfInclude& inc, SceneDescription& scene) {
  MaterialConverter converter{inc, scene, {}};
  std::vector<int> index;
  for (const GltfMaterial& m : inc.doc.materials) {
    index.push_back(static_cast<int>(scene.materials.size()));
    const std::string name =
        uniqueName(scene, inc.label + ":" + (m.name.empty() ? m.path : m.name));
    scene.materials.push_back(converter.convert(m, name));
  }
  return index;
}

int addGltfDefaultMaterial(const GltfInclude& inc, SceneDescription& scene) {
  // glTF's default material (§3.9.6): base colour 1, metallic 1, roughness 1.
  GltfMaterial fallback;
  fallback.path = "default material";
  const std::string name = uniqueName(scene, inc.label + ":default");
  scene.materials.push_back(MaterialConverter{inc, scene, {}}.convert(fallback, name));
  return static_cast<int>(scene.materials.size()) - 1;
}

std::optional<EmissionDescription> gltfEmission(const GltfInclude& inc, int material,
                                                SceneDescription& scene) {
  if (material < 0) return std::nullopt;
  const GltfMaterial& m = inc.doc.materials[static_cast<size_t>(material)];
  glm::dvec3 e = m.emissiveFactor * m.emissiveStrength;
  if (m.emissiveTexture.image >= 0 && lumaOf(e) > 0.0) {
    const TextureImage& t = *inc.doc.images[static_cast<size_t>(m.emissiveTexture.image)].texels;
    glm::dvec3 mean(0.0);
    const size_t n = static_cast<size_t>(t.width) * static_cast<size_t>(t.height);
    for (size_t p = 0; p < n; ++p)
      for (int c = 0; c < 3; ++c)
        mean[c] += srgbDecode(static_cast<double>(t.values[p * 4 + static_cast<size_t>(c)]));
    e *= mean / static_cast<double>(n);
    note(scene, inc,
         m.emissiveTexture.path + ": camsim's emitters are uniform; the texture's mean (" +
             std::to_string(mean.r / n) + ", " + std::to_string(mean.g / n) + ", " +
             std::to_string(mean.b / n) + ") scales emissiveFactor");
  }
  if (!(lumaOf(e) > 0.0)) return std::nullopt;
  // The scene format's limit on an emitter's luminance (SceneLimits): past it a float
  // spectrum overflows, and every path that sees the shape is infinite. The error names the
  // strength when it is what lifted the factor past 1.
  const double target = inc.emissiveLuminance * lumaOf(e);
  if (!(target <= SceneLimits::kMaxLuminance))
    throw InputError({inc.doc.file.string(), 0, 0},
                     m.path + (m.emissiveStrength > 1.0 ? kEmissiveStrengthKey : ".emissiveFactor"),
                     "emissiveFactor × emissiveStrength × the include's emissive_luminance give " +
                         formatNumber(target) + " cd/m², above the " +
                         formatNumber(SceneLimits::kMaxLuminance) + " cd/m² an emitter may have");
  EmissionDescription d;
  // The colour's shape from e scaled to a largest component of 1 (e itself may be ~1e300:
  // the float spectrum overflowed); the luminance is applied next.
  const double largest = std::max({e.r, e.g, e.b});
  const Spectrum shape = rgbToEmissionShape(e / largest, RgbColorSpace::linearRec709());
  d.radiance = shape * (target / luminance(shape));
  d.twoSided = m.doubleSided;
  return d;
}

LightDescription gltfLight(const GltfInclude& inc, const GltfLight& l,
                           const glm::dmat4& renderFromNode, SceneDescription& scene) {
  LightDescription d;
  d.label = inc.label + ":" + (l.name.empty() ? l.path : l.name);
  d.position = glm::vec3(renderFromNode[3]);
  // The node's −z, divided by its largest component before normalising: its length under a
  // scale of 1e155 overflowed to inf, normalize() gave 0 and the light aborted (found by
  // probing); under 1e-200 it underflowed to 0, "a zero scale".
  const glm::dvec3 dir = -glm::dvec3(renderFromNode[2]);
  const double largest = std::max({std::abs(dir.x), std::abs(dir.y), std::abs(dir.z)});
  if (!(largest > 0.0) || !std::isfinite(largest))
    throw InputError({inc.doc.file.string(), 0, 0}, l.path,
                     largest > 0.0 ? "the light's node has a scale beyond double's range"
                                   : "the light's node has a zero scale");
  d.direction = glm::vec3(glm::normalize(dir / largest));
  const double photometric = l.intensity * lumaOf(l.color);
  if (!(photometric > 0.0)) {
    d.spectrum = Spectrum::constant(0.0);
  } else {
    const Spectrum shape = rgbToEmissionShape(l.color, RgbColorSpace::linearRec709());
    // luminance() is 683 Σ S ȳ Δλ: per sr for intensity, per m² for illuminance alike.
    d.spectrum = shape * (photometric / luminance(shape));
  }
  switch (l.type) {
    case GltfLight::Type::kPoint:
      d.kind = LightDescription::Kind::kPoint;
      break;
    case GltfLight::Type::kSpot:
      d.kind = LightDescription::Kind::kSpot;
      d.coneAngle = static_cast<float>(l.outerConeAngle);
      d.falloffStart = static_cast<float>(l.innerConeAngle);
      break;
    case GltfLight::Type::kDirectional:
      d.kind = LightDescription::Kind::kDistant;
      break;
  }
  if (l.range > 0.0)
    note(scene, inc, l.path + ".range: ignored (camsim keeps the physical inverse-square falloff)");
  return d;
}

}  // namespace camsim
