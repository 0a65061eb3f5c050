// The type check of a glTF material's values, part of the structural check of the JSON
// (gltf_validate.cpp): tinygltf drops a mistyped value for its default silently
// (roughnessFactor "x" rendered as roughness 1), so each is checked here by JSON path.
//
// | JSON path (below materials[i])                               | type                |
// |--------------------------------------------------------------|---------------------|
// | pbrMetallicRoughness.baseColorFactor                          | array of 4 numbers  |
// | pbrMetallicRoughness.metallicFactor, .roughnessFactor         | number              |
// | emissiveFactor                                               | array of 3 numbers  |
// | alphaCutoff                                                  | number              |
// | alphaMode                                                    | string              |
// | doubleSided                                                  | boolean             |
// | extensions                                                   | object              |
// | extensions.KHR_materials_emissive_strength.emissiveStrength  | number (its object) |
// | extensions.KHR_materials_transmission.transmissionFactor     | number (its object) |
// | extensions.KHR_materials_ior.ior                             | number (its object) |
//
// Their ranges are checked as the values are read (gltf_read_materials.cpp).
#include <algorithm>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "sensor/base/input_error.h"

namespace camsim {
namespace {

using Json = nlohmann::json;

}  // namespace

// obj[key], when present (or required: else "is missing"), a number (n = 0) or an array of n
// numbers (gltf_validate.cpp's values of their types too).
void checkGltfNumbers(const std::string& file, const Json& obj, const std::string& path,
                      const char* key, size_t n, bool required) {
  const auto v = obj.find(key);
  if (v == obj.end()) {
    if (required) throw InputError({file, 0, 0}, path + "." + key, "is missing");
    return;
  }
  const bool ok =
      n == 0 ? v->is_number()
             : v->is_array() && v->size() == n &&
                   std::all_of(v->begin(), v->end(), [](const Json& x) { return x.is_number(); });
  if (!ok)
    throw InputError(
        {file, 0, 0}, path + "." + key,
        n == 0 ? "must be a number" : "must be an array of " + std::to_string(n) + " numbers");
}

void checkGltfMaterialValues(const Json& m, const std::string& p, const std::string& file) {
  const auto fail = [&](const std::string& path, const std::string& message) {
    throw InputError({file, 0, 0}, path, message);
  };
  if (const auto pbr = m.find("pbrMetallicRoughness"); pbr != m.end()) {
    checkGltfNumbers(file, *pbr, p + ".pbrMetallicRoughness", "baseColorFactor", 4, false);
    for (const char* key : {"metallicFactor", "roughnessFactor"})
      checkGltfNumbers(file, *pbr, p + ".pbrMetallicRoughness", key, 0, false);
  }
  checkGltfNumbers(file, m, p, "emissiveFactor", 3, false);
  checkGltfNumbers(file, m, p, "alphaCutoff", 0, false);
  if (const auto a = m.find("alphaMode"); a != m.end() && !a->is_string())
    fail(p + ".alphaMode", "must be a string");
  if (const auto d = m.find("doubleSided"); d != m.end() && !d->is_boolean())
    fail(p + ".doubleSided", "must be true or false");
  const auto ext = m.find("extensions");
  if (ext == m.end()) return;
  if (!ext->is_object()) fail(p + ".extensions", "must be an object");
  for (const auto& [name, key] : {std::pair{"KHR_materials_emissive_strength", "emissiveStrength"},
                                  {"KHR_materials_transmission", "transmissionFactor"},
                                  {"KHR_materials_ior", "ior"}}) {
    const auto e = ext->find(name);
    if (e == ext->end()) continue;
    const std::string ep = p + ".extensions." + name;
    if (!e->is_object()) fail(ep, "must be an object");
    checkGltfNumbers(file, *e, ep, key, 0, false);
  }
}

}  // namespace camsim
