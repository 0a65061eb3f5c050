// glTF materials into GltfDocument (gltf_document.h): the metallic-roughness core, the
// textures with their KHR_texture_transform and the one TEXCOORD set they read, the
// material extensions camsim reads (emissive strength, transmission, ior), checked values.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <tiny_gltf.h>

#include "integrator/scene/gltf_document.h"
#include "sensor/base/input_error.h"

namespace camsim {

double gltfNumber(const tinygltf::Value& obj, const char* key,
                  double fallback);  // gltf_document.cpp

namespace {

// A textureInfo (its extensions: KHR_texture_transform, checked by gltf_validate.cpp).
GltfTextureRef textureRef(const tinygltf::Model& model, int textureIndex, int texCoord,
                          double scale, const tinygltf::ExtensionMap& extensions,
                          std::string path) {
  GltfTextureRef r;
  if (textureIndex < 0) return r;
  r.image = model.textures[static_cast<size_t>(textureIndex)].source;
  r.texCoord = texCoord;
  r.scale = scale;
  r.path = std::move(path);
  if (const auto t = extensions.find("KHR_texture_transform"); t != extensions.end()) {
    auto pair = [&](const char* key, glm::dvec2& out) {
      if (!t->second.Has(key)) return;
      const tinygltf::Value& v = t->second.Get(key);
      for (int c = 0; c < 2; ++c) out[c] = v.Get(c).GetNumberAsDouble();
    };
    pair("offset", r.uvOffset);
    pair("scale", r.uvScale);
    r.uvRotation = gltfNumber(t->second, "rotation", 0.0);
    r.texCoord = static_cast<int>(gltfNumber(t->second, "texCoord", texCoord));
  }
  return r;
}

// The one TEXCOORD set a material's textures read (camsim's meshes carry one), noting a
// material whose textures disagree. The emissive texture counts only by its mean and the
// occlusion texture not at all.
int materialTexCoord(const GltfMaterial& m, std::vector<std::string>& notes) {
  std::vector<const GltfTextureRef*> used;
  for (const GltfTextureRef* t :
       {&m.baseColorTexture, &m.metallicRoughnessTexture, &m.normalTexture})
    if (t->image >= 0) used.push_back(t);
  if (used.empty()) return 0;
  const int set = used.front()->texCoord;
  for (const GltfTextureRef* t : used)
    if (t->texCoord != set) {
      notes.push_back(t->path + " reads TEXCOORD_" + std::to_string(t->texCoord) + " but " +
                      used.front()->path + " TEXCOORD_" + std::to_string(set) +
                      ": camsim's meshes carry one set of texture coordinates, so it reads " +
                      "TEXCOORD_" + std::to_string(set));
    }
  return set;
}

}  // namespace

void readGltfMaterials(const tinygltf::Model& model, GltfDocument& doc, const std::string& name) {
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const tinygltf::Material& m = model.materials[i];
    GltfMaterial g;
    g.name = m.name;
    g.path = "materials[" + std::to_string(i) + "]";
    const auto& pbr = m.pbrMetallicRoughness;
    // All four in [0, 1], with a texture or without (found by probing: alpha −1 hid a MASK
    // material's geometry, and [50, −3, 0.8] with a texture was clamped silently).
    for (size_t c = 0; c < 4 && c < pbr.baseColorFactor.size(); ++c) {
      g.baseColorFactor[static_cast<int>(c)] = pbr.baseColorFactor[c];
      if (!(pbr.baseColorFactor[c] >= 0.0 && pbr.baseColorFactor[c] <= 1.0))
        throw InputError(
            {name, 0, 0},
            g.path + ".pbrMetallicRoughness.baseColorFactor[" + std::to_string(c) + "]",
            "must lie in [0, 1]");
    }
    g.metallicFactor = pbr.metallicFactor;
    g.roughnessFactor = pbr.roughnessFactor;
    g.baseColorTexture = textureRef(
        model, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, 1.0,
        pbr.baseColorTexture.extensions, g.path + ".pbrMetallicRoughness.baseColorTexture");
    g.metallicRoughnessTexture =
        textureRef(model, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                   1.0, pbr.metallicRoughnessTexture.extensions,
                   g.path + ".pbrMetallicRoughness.metallicRoughnessTexture");
    g.normalTexture =
        textureRef(model, m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.scale,
                   m.normalTexture.extensions, g.path + ".normalTexture");
    g.occlusionTexture = textureRef(model, m.occlusionTexture.index, m.occlusionTexture.texCoord,
                                    m.occlusionTexture.strength, m.occlusionTexture.extensions,
                                    g.path + ".occlusionTexture");
    g.emissiveTexture = textureRef(model, m.emissiveTexture.index, m.emissiveTexture.texCoord, 1.0,
                                   m.emissiveTexture.extensions, g.path + ".emissiveTexture");
    // The scene file's normal_scale bound, where a normal texture uses it.
    if (m.normalTexture.index >= 0 && !(std::abs(m.normalTexture.scale) <= 100.0))
      throw InputError({name, 0, 0}, g.path + ".normalTexture.scale", "must lie in [-100, 100]");
    g.texCoord = materialTexCoord(g, doc.notes);
    for (size_t c = 0; c < 3 && c < m.emissiveFactor.size(); ++c) {
      g.emissiveFactor[static_cast<int>(c)] = m.emissiveFactor[c];
      if (!std::isfinite(m.emissiveFactor[c]) || m.emissiveFactor[c] < 0.0)
        throw InputError({name, 0, 0}, g.path + ".emissiveFactor[" + std::to_string(c) + "]",
                         "must be a finite number >= 0");
    }
    if (m.alphaMode == "MASK")
      g.alphaMode = GltfMaterial::AlphaMode::kMask;
    else if (m.alphaMode == "BLEND")
      g.alphaMode = GltfMaterial::AlphaMode::kBlend;
    else if (m.alphaMode != "OPAQUE")
      throw InputError({name, 0, 0}, g.path + ".alphaMode",
                       "must be OPAQUE, MASK or BLEND (it is '" + m.alphaMode + "')");
    g.alphaCutoff = m.alphaCutoff;
    g.doubleSided = m.doubleSided;
    for (const auto& [ext, value] : m.extensions) {
      if (ext == "KHR_materials_emissive_strength")
        g.emissiveStrength = gltfNumber(value, "emissiveStrength", 1.0);
      else if (ext == "KHR_materials_transmission")
        g.transmission = gltfNumber(value, "transmissionFactor", 0.0);
      else if (ext == "KHR_materials_ior")
        g.ior = gltfNumber(value, "ior", 1.5);
      else
        g.otherExtensions.push_back(ext);
    }
    for (const auto& [key, v] : std::initializer_list<std::pair<const char*, double>>{
             {".pbrMetallicRoughness.metallicFactor", g.metallicFactor},
             {".pbrMetallicRoughness.roughnessFactor", g.roughnessFactor},
             {".alphaCutoff", g.alphaCutoff},
             {kEmissiveStrengthKey, g.emissiveStrength},
             {kTransmissionKey, g.transmission},
             {kIorKey, g.ior}})
      if (!std::isfinite(v) || v < 0.0)
        throw InputError({name, 0, 0}, g.path + key, "must be a finite number >= 0");
    // Factors glTF bounds to [0, 1] (a roughness of 2 was clamped to 1 without a word).
    for (const auto& [key, v] : std::initializer_list<std::pair<const char*, double>>{
             {".pbrMetallicRoughness.metallicFactor", g.metallicFactor},
             {".pbrMetallicRoughness.roughnessFactor", g.roughnessFactor},
             {kTransmissionKey, g.transmission}})
      if (v > 1.0) throw InputError({name, 0, 0}, g.path + key, "must lie in [0, 1]");
    if (g.ior < 1.0 && g.ior != 0.0)
      throw InputError({name, 0, 0}, g.path + kIorKey, "must be >= 1 (or 0)");
    doc.materials.push_back(std::move(g));
  }
}

}  // namespace camsim
