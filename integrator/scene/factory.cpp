#include "integrator/scene/factory.h"

#include <atomic>

#include "integrator/lights/distant_light.h"
#include "integrator/lights/environment_light.h"
#include "integrator/lights/point_light.h"
#include "integrator/lights/spot_light.h"
#include "integrator/materials/conductor_material.h"
#include "integrator/materials/dielectric_material.h"
#include "integrator/materials/diffuse_material.h"
#include "integrator/materials/metallic_roughness_material.h"
#include "integrator/materials/mirror_material.h"
#include "integrator/materials/plastic_material.h"
#include "integrator/textures/alpha_cutout.h"
#include "integrator/textures/checkerboard_texture.h"
#include "integrator/textures/image_texture.h"
#include "sensor/base/check.h"
#include "sensor/io/exr_io.h"

namespace camsim {
namespace {

std::atomic<std::uint64_t> filesRead{0};  // sceneFilesRead()

// The image the loader decoded, else (a description built in code, or one whose images
// were released) read now. Shared, never copied.
template <typename T, typename Read>
std::shared_ptr<const T> decodedOr(const std::shared_ptr<const T>& decoded, Read read) {
  if (decoded) return decoded;
  filesRead.fetch_add(1, std::memory_order_relaxed);
  return std::make_shared<const T>(read());
}
std::shared_ptr<const TextureImage> texelsOf(const TextureDescription& d) {
  return decodedOr(d.image, [&] { return loadTextureImage(d.file, d.encoding); });
}

}  // namespace

std::shared_ptr<const UpliftedTexels> TextureCache::uplifted(const TextureDescription& d) {
  CAMSIM_CHECK(d.kind == TextureDescription::Kind::kImage);
  Entry* entry = d.file.empty() ? nullptr : &entries_[{d.file.string(), d.encoding}];
  // A hit: the same file read again (no decoded texels), or texels equal to the cached ones
  // (the loader decodes a file once per material naming it: other pointers, equal values).
  if (entry && entry->texels && (!d.image || *d.image == *entry->image)) return entry->texels;
  const std::shared_ptr<const TextureImage> image = texelsOf(d);
  auto texels = std::make_shared<const UpliftedTexels>(upliftTexels(*image));
  if (entry && !entry->texels) *entry = {image, texels};
  return texels;
}

std::unique_ptr<SpectrumTexture> makeSpectrumTexture(const TextureDescription& d,
                                                     TextureCache* cache) {
  switch (d.kind) {
    case TextureDescription::Kind::kConstant:
      return std::make_unique<ConstantSpectrumTexture>(d.value);
    case TextureDescription::Kind::kImage: {
      TextureCache own;  // without a shared cache: an uplift of its own
      return std::make_unique<ImageSpectrumTexture>((cache ? *cache : own).uplifted(d), d.uvScale,
                                                    d.uvOffset, d.uvRotation);
    }
    case TextureDescription::Kind::kCheckerboard:
      return std::make_unique<CheckerboardSpectrumTexture>(d.checkerA, d.checkerB, d.checks,
                                                           d.uvScale, d.uvOffset);
  }
  CAMSIM_CHECK(false);
  return nullptr;
}

std::unique_ptr<FloatTexture> makeFloatTexture(const TextureDescription& d) {
  switch (d.kind) {
    case TextureDescription::Kind::kConstant:
      return std::make_unique<ConstantFloatTexture>(d.value(550.0f));
    case TextureDescription::Kind::kImage:
      return std::make_unique<ImageFloatTexture>(*texelsOf(d), d.uvScale, d.uvOffset, d.channel,
                                                 d.uvRotation);
    case TextureDescription::Kind::
        kCheckerboard:  // constants as for kConstant: the value at 550 nm
      return std::make_unique<CheckerboardFloatTexture>(d.checkerA(550.0f), d.checkerB(550.0f),
                                                        d.checks, d.uvScale, d.uvOffset);
  }
  CAMSIM_CHECK(false);
  return nullptr;
}

namespace {

std::unique_ptr<Material> makeBsdf(const MaterialDescription& d, TextureCache* cache) {
  switch (d.type) {
    case MaterialDescription::Type::kDiffuse:
      return std::make_unique<DiffuseMaterial>(makeSpectrumTexture(d.reflectance, cache));
    case MaterialDescription::Type::kDielectric:
      return std::make_unique<DielectricMaterial>(d.eta, makeFloatTexture(d.roughness),
                                                  d.anisotropy, d.distribution, d.masking);
    case MaterialDescription::Type::kConductor: {
      ConductorParameters p;
      p.roughness = makeFloatTexture(d.roughness);
      p.anisotropy = d.anisotropy;
      p.distribution = d.distribution;
      p.masking = d.masking;
      p.fresnel = d.fresnel;
      p.eta = d.eta;
      p.k = d.k;
      if (d.fresnel == FresnelModel::kSchlick) p.r0 = makeSpectrumTexture(d.reflectance, cache);
      return std::make_unique<ConductorMaterial>(std::move(p));
    }
    case MaterialDescription::Type::kMirror:
      return std::make_unique<MirrorMaterial>(makeSpectrumTexture(d.reflectance, cache));
    case MaterialDescription::Type::kPlastic: {
      PlasticParameters p;
      p.reflectance = makeSpectrumTexture(d.reflectance, cache);
      p.roughness = makeFloatTexture(d.roughness);
      p.specularWeight = d.specularWeight;
      p.anisotropy = d.anisotropy;
      p.distribution = d.distribution;
      p.masking = d.masking;
      return std::make_unique<PlasticMaterial>(std::move(p));
    }
    case MaterialDescription::Type::kMetallicRoughness: {
      MetallicRoughnessParameters p;
      p.baseColor = makeSpectrumTexture(d.reflectance, cache);
      p.metallic = makeFloatTexture(d.metallic);
      p.roughness = makeFloatTexture(d.roughness);
      return std::make_unique<MetallicRoughnessMaterial>(std::move(p));
    }
  }
  CAMSIM_CHECK(false);
  return nullptr;
}

}  // namespace

std::unique_ptr<NormalMap> makeNormalMap(const TextureDescription& d, float strength) {
  CAMSIM_CHECK(d.kind == TextureDescription::Kind::kImage);
  return std::make_unique<NormalMap>(*texelsOf(d), d.uvScale, d.uvOffset, strength, d.uvRotation);
}

std::unique_ptr<Material> makeMaterial(const MaterialDescription& d, TextureCache* cache) {
  std::unique_ptr<Material> m = makeBsdf(d, cache);
  if (d.normalMap) m->setNormalMap(makeNormalMap(*d.normalMap, d.normalScale));
  return m;
}

std::unique_ptr<Light> makeLight(const LightDescription& d) {
  switch (d.kind) {
    case LightDescription::Kind::kPoint:
      return std::make_unique<PointLight>(d.position, d.spectrum);
    case LightDescription::Kind::kSpot:
      return std::make_unique<SpotLight>(d.position, d.direction, d.spectrum, d.coneAngle,
                                         d.falloffStart);
    case LightDescription::Kind::kDistant:
      return std::make_unique<DistantLight>(d.spectrum, d.direction, d.angularDiameter);
    case LightDescription::Kind::kEnvironment:
      return std::make_unique<EnvironmentLight>(
          *decodedOr(d.image, [&] { return readExr(d.file).image; }), d.spectrum,
          glm::mat3(d.worldFromLight));
  }
  CAMSIM_CHECK(false);
  return nullptr;
}

std::shared_ptr<const FloatTexture> makeAlphaTexture(const MaterialDescription::AlphaCutout& d) {
  if (!d.texture && d.factor >= d.cutoff) return nullptr;
  if (d.texture) return makeFloatTexture(*d.texture);
  return std::make_shared<const ConstantFloatTexture>(1.0f);
}

std::unique_ptr<HitFilter> makeAlphaCutout(const MaterialDescription::AlphaCutout& d,
                                           std::shared_ptr<const FloatTexture> alpha,
                                           const TriangleMesh& mesh) {
  CAMSIM_CHECK(alpha != nullptr);
  return std::make_unique<AlphaCutout>(mesh, std::move(alpha), d.factor, d.cutoff);
}

std::uint64_t sceneFilesRead() {
  return filesRead.load(std::memory_order_relaxed);
}

}  // namespace camsim
