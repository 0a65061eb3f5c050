// The structural check of a glTF file's JSON, before tinygltf reads it: tinygltf rejects
// many malformed files itself, but its messages seldom say where ("'byteLength' property is
// not a positive integer", "Failed to decode 'uri' : data:…"), and a user needs the JSON
// path to fix the file. Each check here names it: every index in range, every byte extent
// inside its view and its buffer, each buffer's data of its byteLength, strides that fit
// their elements, index accessors of unsigned integers, counts and lengths positive
// integers, external files present. Value checks that need the data (index values, NaN
// positions) are done as the data is read (gltf_accessors.cpp).
#include <cctype>
#include <cmath>
#include <cstdint>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "integrator/scene/gltf_document.h"
#include "sensor/base/file_status.h"
#include "sensor/base/input_error.h"

namespace camsim {

// gltf_validate_materials.cpp: a material's values of their types; obj[key], when present
// (or required: else "is missing"), a number (n = 0) or an array of n numbers.
void checkGltfMaterialValues(const nlohmann::json& material, const std::string& path,
                             const std::string& file);
void checkGltfNumbers(const std::string& file, const nlohmann::json& obj, const std::string& path,
                      const char* key, size_t n, bool required);

namespace {

using Json = nlohmann::json;

constexpr std::int64_t kMaxZeroAccessorCount = std::int64_t(1) << 20;

struct Checker {
  std::string file;
  std::filesystem::path baseDir;
  const Json& root;

  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    throw InputError({file, 0, 0}, path, message);
  }
  size_t count(const char* array) const {
    const auto it = root.find(array);
    if (it == root.end()) return 0;
    if (!it->is_array()) fail(array, "must be an array");
    return it->size();
  }
  // An integer in [lo, hi] at obj[key] (required or optional); returns fallback if absent.
  std::int64_t integer(const Json& obj, const std::string& path, const char* key, std::int64_t lo,
                       std::int64_t hi, bool required, std::int64_t fallback = 0) const {
    const auto it = obj.find(key);
    const std::string where = path + "." + key;
    if (it == obj.end()) {
      if (required) fail(where, "is missing");
      return fallback;
    }
    if (!it->is_number()) fail(where, "must be a number");
    const double v = it->get<double>();
    if (!(std::floor(v) == v) || !(v >= static_cast<double>(lo)) || !(v <= static_cast<double>(hi)))
      fail(where, "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                      "] (it is " + it->dump() + ")");
    return static_cast<std::int64_t>(v);
  }
  // A reference obj[key] into the top-level array `array`.
  std::int64_t index(const Json& obj, const std::string& path, const char* key, const char* array,
                     bool required) const {
    const size_t n = count(array);
    const auto it = obj.find(key);
    if (it == obj.end()) {
      if (required) fail(path + "." + key, "is missing");
      return -1;
    }
    if (n == 0) fail(path + "." + key, std::string("refers to ") + array + ", which is empty");
    return integer(obj, path, key, 0, static_cast<std::int64_t>(n) - 1, required);
  }
  const Json& item(const char* array, size_t i) const {
    const Json& v = root[array][i];
    if (!v.is_object())
      fail(std::string(array) + "[" + std::to_string(i) + "]", "must be an object");
    return v;
  }
  static std::string at(const char* array, size_t i) {
    return std::string(array) + "[" + std::to_string(i) + "]";
  }
  // The external file obj.uri names (it must exist); empty for none or a data URI.
  std::filesystem::path externalFile(const Json& obj, const std::string& path) const {
    const auto uri = obj.find("uri");
    if (uri == obj.end()) return {};
    if (!uri->is_string()) fail(path + ".uri", "must be a string");
    const std::string u = uri->get<std::string>();
    if (u.rfind("data:", 0) == 0) return {};
    std::string decoded;  // percent-encoding, as tinygltf decodes it
    for (size_t i = 0; i < u.size(); ++i) {
      if (u[i] == '%' && i + 2 < u.size() && std::isxdigit(static_cast<unsigned char>(u[i + 1])) &&
          std::isxdigit(static_cast<unsigned char>(u[i + 2]))) {
        decoded += static_cast<char>(std::stoi(u.substr(i + 1, 2), nullptr, 16));
        i += 2;
      } else {
        decoded += u[i];
      }
    }
    const std::filesystem::path p = baseDir / decoded;
    if (!isRegularFile(p)) fail(path + ".uri", "file '" + p.string() + "' not found");
    return p;
  }
};

// glTF component types 5120 … 5126 (5124 is none): size in bytes (0: not a type), name.
struct ComponentType {
  size_t bytes;
  const char* name;
};
ComponentType componentType(std::int64_t type) {
  static const ComponentType types[] = {
      {1, "BYTE"}, {1, "UNSIGNED_BYTE"}, {2, "SHORT"}, {2, "UNSIGNED_SHORT"},
      {0, ""},     {4, "UNSIGNED_INT"},  {4, "FLOAT"}};
  return type >= 5120 && type <= 5126 ? types[type - 5120] : ComponentType{0, ""};
}

size_t componentCount(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

void checkTextureInfo(const Checker& c, const Json& obj, const std::string& path, const char* key) {
  const auto it = obj.find(key);
  if (it == obj.end()) return;
  if (!it->is_object()) c.fail(path + "." + key, "must be an object");
  c.index(*it, path + "." + key, "index", "textures", true);
  c.integer(*it, path + "." + key, "texCoord", 0, 16, false);
  const auto ext = it->find("extensions");
  if (ext == it->end() || !ext->is_object()) return;
  const auto tt = ext->find("KHR_texture_transform");
  if (tt == ext->end()) return;
  const std::string tp = path + "." + key + ".extensions.KHR_texture_transform";
  if (!tt->is_object()) c.fail(tp, "must be an object");
  for (const char* k : {"offset", "scale"}) {
    const auto v = tt->find(k);
    if (v != tt->end() &&
        (!v->is_array() || v->size() != 2 || !(*v)[0].is_number() || !(*v)[1].is_number()))
      c.fail(tp + "." + k, "must be an array of 2 numbers");
  }
  if (const auto r = tt->find("rotation"); r != tt->end() && !r->is_number())
    c.fail(tp + ".rotation", "must be a number (radians)");
  c.integer(*tt, tp, "texCoord", 0, 16, false);
}

// A buffer's data holds exactly byteLength bytes (tinygltf refuses any other length with
// its raw text): a data URI's decoded base64, or the external file's size.
void checkBufferData(const Checker& c, const Json& b, const std::string& path,
                     std::int64_t byteLength) {
  if (!b.at("uri").is_string()) c.fail(path + ".uri", "must be a string");
  const std::string u = b.at("uri").get<std::string>();
  std::int64_t bytes = 0;
  std::string what;
  if (u.rfind("data:", 0) == 0) {
    bytes = gltfDataUriBytes(u);
    if (bytes < 0)
      c.fail(path + ".uri",
             "a data URI must be base64: data:application/octet-stream;base64,… (or "
             "application/gltf-buffer)");
    what = "its data URI decodes to ";
  } else {
    std::error_code ec;
    const std::filesystem::path file = c.externalFile(b, path);
    bytes = static_cast<std::int64_t>(std::filesystem::file_size(file, ec));
    if (ec) c.fail(path + ".uri", "cannot read the size of '" + file.string() + "'");
    what = "its file '" + file.string() + "' holds ";
  }
  if (bytes != byteLength)
    c.fail(path, what + std::to_string(bytes) + " bytes but its byteLength is " +
                     std::to_string(byteLength) +
                     (bytes < byteLength ? ": the buffer is truncated" : " (they must be equal)"));
}

// Accessors that primitives use as indices, each with the first such primitive's path
// ("meshes[0].primitives[1].indices"); a malformed mesh is skipped (the mesh check names it).
std::vector<std::string> indexUses(const Checker& c) {
  std::vector<std::string> uses(c.count("accessors"));
  const auto meshes = c.root.find("meshes");
  if (meshes == c.root.end() || !meshes->is_array()) return uses;
  for (size_t i = 0; i < meshes->size(); ++i) {  // find() on a non-object gives end()
    const auto prims = (*meshes)[i].find("primitives");
    if (prims == (*meshes)[i].end() || !prims->is_array()) continue;
    for (size_t k = 0; k < prims->size(); ++k) {
      const auto ind = (*prims)[k].find("indices");
      if (ind == (*prims)[k].end() || !ind->is_number_unsigned()) continue;
      const auto a = ind->get<std::uint64_t>();
      if (a < uses.size() && uses[a].empty())
        uses[a] = Checker::at("meshes", i) + ".primitives[" + std::to_string(k) + "].indices";
    }
  }
  return uses;
}

}  // namespace

void validateGltfJson(const std::string& json, const std::string& displayName,
                      const std::filesystem::path& baseDir, std::size_t glbBinBytes, bool isGlb) {
  Json root;
  try {
    root = Json::parse(json);
  } catch (const Json::parse_error& e) {
    // nlohmann reports the byte; the line is what an editor shows.
    int line = 1;
    for (size_t i = 0; i < e.byte && i < json.size(); ++i) line += json[i] == '\n';
    throw InputError({displayName, line, 0}, "", std::string("not valid JSON: ") + e.what());
  } catch (const Json::exception& e) {  // e.g. out_of_range: a number beyond double's range
    throw InputError({displayName, 0, 0}, "", std::string("not valid JSON: ") + e.what());
  }
  if (!root.is_object()) throw InputError({displayName, 1, 0}, "", "a glTF file is a JSON object");
  const Checker c{displayName, baseDir, root};
  const auto asset = root.find("asset");
  if (asset == root.end() || !asset->is_object())
    c.fail("asset", "is missing (every glTF has one)");
  const auto version = asset->find("version");
  if (version == asset->end() || !version->is_string() ||
      version->get<std::string>().rfind("2.", 0) != 0)
    c.fail("asset.version", "camsim reads glTF 2.x");

  std::vector<std::int64_t> bufferBytes;
  for (size_t i = 0; i < c.count("buffers"); ++i) {
    const Json& b = c.item("buffers", i);
    const std::string p = Checker::at("buffers", i);
    bufferBytes.push_back(c.integer(b, p, "byteLength", 1, std::int64_t(1) << 40, true));
    if (b.contains("uri")) {
      checkBufferData(c, b, p, bufferBytes.back());
    } else if (!(isGlb && i == 0)) {
      c.fail(p + ".uri", "is missing (only a .glb's first buffer may omit it)");
    } else if (static_cast<std::size_t>(bufferBytes.back()) > glbBinBytes) {
      c.fail(p + ".byteLength", "is " + std::to_string(bufferBytes.back()) +
                                    " bytes but the .glb's BIN chunk holds " +
                                    std::to_string(glbBinBytes));
    }
  }
  std::vector<std::int64_t> viewBytes;
  for (size_t i = 0; i < c.count("bufferViews"); ++i) {
    const Json& v = c.item("bufferViews", i);
    const std::string p = Checker::at("bufferViews", i);
    const std::int64_t b = c.index(v, p, "buffer", "buffers", true);
    const std::int64_t offset = c.integer(v, p, "byteOffset", 0, std::int64_t(1) << 40, false);
    const std::int64_t length = c.integer(v, p, "byteLength", 1, std::int64_t(1) << 40, true);
    if (offset + length > bufferBytes[static_cast<size_t>(b)])
      c.fail(p + ".byteLength", "byteOffset + byteLength = " + std::to_string(offset + length) +
                                    " exceeds buffers[" + std::to_string(b) + "].byteLength = " +
                                    std::to_string(bufferBytes[static_cast<size_t>(b)]));
    if (v.contains("byteStride")) {
      const std::int64_t s = c.integer(v, p, "byteStride", 4, 252, false);
      if (s % 4 != 0) c.fail(p + ".byteStride", "must be a multiple of 4");
    }
    viewBytes.push_back(length);
  }
  const std::vector<std::string> usedAsIndices = indexUses(c);
  for (size_t i = 0; i < c.count("accessors"); ++i) {
    const Json& a = c.item("accessors", i);
    const std::string p = Checker::at("accessors", i);
    const std::int64_t ct = c.integer(a, p, "componentType", 5120, 5126, true);
    const size_t cb = componentType(ct).bytes;
    if (cb == 0) c.fail(p + ".componentType", "is not a glTF component type");
    if (!usedAsIndices[i].empty() && ct != 5121 && ct != 5123 && ct != 5125)
      c.fail(p + ".componentType", std::string("is ") + componentType(ct).name + " (" +
                                       std::to_string(ct) + ") but " + usedAsIndices[i] +
                                       " needs UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    const auto type = a.find("type");
    if (type == a.end() || !type->is_string() || componentCount(type->get<std::string>()) == 0)
      c.fail(p + ".type", "must be SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4");
    const std::int64_t count = c.integer(a, p, "count", 1, std::int64_t(1) << 32, true);
    if (a.contains("sparse")) c.fail(p + ".sparse", "sparse accessors are not supported");
    if (const auto nz = a.find("normalized"); nz != a.end() && !nz->is_boolean())
      c.fail(p + ".normalized", "must be true or false");
    const std::int64_t view = c.index(a, p, "bufferView", "bufferViews", false);
    // Without a view the elements are zeros, which no file stores: a 1.2 KB file asked for
    // 2^32 of them, 137 GB (found by probing).
    if (view < 0 && count > kMaxZeroAccessorCount)
      c.fail(p + ".count", std::to_string(count) +
                               " elements without a bufferView (all zeros); camsim reads at most " +
                               std::to_string(kMaxZeroAccessorCount));
    if (view < 0) continue;  // all zeros
    const std::int64_t offset = c.integer(a, p, "byteOffset", 0, std::int64_t(1) << 40, false);
    const Json& v = root.at("bufferViews").at(static_cast<size_t>(view));
    const std::int64_t element =
        static_cast<std::int64_t>(cb * componentCount(type->get<std::string>()));
    const std::int64_t stride =
        v.contains("byteStride") ? v["byteStride"].get<std::int64_t>() : element;
    if (stride < element)
      c.fail(Checker::at("bufferViews", static_cast<size_t>(view)) + ".byteStride",
             "is " + std::to_string(stride) + " bytes, less than the " + std::to_string(element) +
                 "-byte elements of " + p + " (" + type->get<std::string>() + " of " +
                 componentType(ct).name + "): they would overlap");
    const std::int64_t end = offset + stride * (count - 1) + element;
    if (end > viewBytes[static_cast<size_t>(view)])
      c.fail(p + ".count", std::to_string(count) + " elements from byteOffset " +
                               std::to_string(offset) + " end at byte " + std::to_string(end) +
                               ", past bufferViews[" + std::to_string(view) + "].byteLength = " +
                               std::to_string(viewBytes[static_cast<size_t>(view)]));
  }
  for (size_t i = 0; i < c.count("images"); ++i) {
    const Json& im = c.item("images", i);
    const std::string p = Checker::at("images", i);
    if (im.contains("bufferView"))
      c.index(im, p, "bufferView", "bufferViews", true);
    else if (im.contains("uri"))
      c.externalFile(im, p);
    else
      c.fail(p, "needs a uri or a bufferView");
  }
  for (size_t i = 0; i < c.count("textures"); ++i) {
    const Json& t = c.item("textures", i);
    const std::string p = Checker::at("textures", i);
    c.index(t, p, "source", "images", false);
    c.index(t, p, "sampler", "samplers", false);
  }
  for (size_t i = 0; i < c.count("materials"); ++i) {
    const Json& m = c.item("materials", i);
    const std::string p = Checker::at("materials", i);
    if (const auto pbr = m.find("pbrMetallicRoughness"); pbr != m.end()) {
      if (!pbr->is_object()) c.fail(p + ".pbrMetallicRoughness", "must be an object");
      checkTextureInfo(c, *pbr, p + ".pbrMetallicRoughness", "baseColorTexture");
      checkTextureInfo(c, *pbr, p + ".pbrMetallicRoughness", "metallicRoughnessTexture");
    }
    for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"})
      checkTextureInfo(c, m, p, key);
    checkGltfMaterialValues(m, p, c.file);
  }
  for (size_t i = 0; i < c.count("meshes"); ++i) {
    const Json& mesh = c.item("meshes", i);
    const std::string p = Checker::at("meshes", i);
    const auto prims = mesh.find("primitives");
    if (prims == mesh.end() || !prims->is_array() || prims->empty())
      c.fail(p + ".primitives", "must be a non-empty array");
    for (size_t k = 0; k < prims->size(); ++k) {
      const Json& prim = (*prims)[k];
      const std::string pp = p + ".primitives[" + std::to_string(k) + "]";
      if (!prim.is_object()) c.fail(pp, "must be an object");
      const auto attrs = prim.find("attributes");
      if (attrs == prim.end() || !attrs->is_object())
        c.fail(pp + ".attributes", "must be an object");
      for (auto it = attrs->begin(); it != attrs->end(); ++it)
        c.index(*attrs, pp + ".attributes", it.key().c_str(), "accessors", true);
      if (!attrs->contains("POSITION")) c.fail(pp + ".attributes.POSITION", "is missing");
      c.index(prim, pp, "indices", "accessors", false);
      c.index(prim, pp, "material", "materials", false);
      c.integer(prim, pp, "mode", 0, 6, false, 4);
    }
  }
  // Cameras' and lights' values of their types: tinygltf's messages name no path, or it
  // reads a wrong type as the default (found by probing: an intensity "500" became 1 cd).
  for (size_t i = 0; i < c.count("cameras"); ++i) {
    const Json& cam = c.item("cameras", i);
    const std::string p = Checker::at("cameras", i);
    const auto type = cam.find("type");
    if (type == cam.end() || !type->is_string())
      c.fail(p + ".type", "must be \"perspective\" or \"orthographic\"");
    const std::string t = type->get<std::string>();
    if (t != "perspective" && t != "orthographic")
      c.fail(p + ".type", "must be \"perspective\" or \"orthographic\" (it is \"" + t + "\")");
    const auto block = cam.find(t);
    if (block == cam.end() || !block->is_object()) c.fail(p + "." + t, "is missing");
    const std::string bp = p + "." + t;
    // glTF 2.0 §5.12–5.14: perspective needs yfov and znear, orthographic all but yfov.
    for (const std::string key : {"yfov", "aspectRatio", "xmag", "ymag", "znear", "zfar"})
      checkGltfNumbers(c.file, *block, bp, key.c_str(), 0,
                       t == "perspective" ? key == "yfov" || key == "znear"
                                          : key != "yfov" && key != "aspectRatio");
  }
  size_t lightCount = 0;
  if (const auto ext = root.find("extensions"); ext != root.end() && ext->is_object()) {
    if (const auto lp = ext->find("KHR_lights_punctual"); lp != ext->end()) {
      const auto lights = lp->find("lights");
      if (lights == lp->end() || !lights->is_array())
        c.fail("extensions.KHR_lights_punctual.lights", "must be an array");
      lightCount = lights->size();
      // tinygltf's own message for a spot light without its "spot" has no path.
      for (size_t i = 0; i < lightCount; ++i) {
        const Json& l = (*lights)[i];
        const std::string at = "extensions.KHR_lights_punctual.lights[" + std::to_string(i) + "]";
        if (!l.is_object()) c.fail(at, "must be an object");
        const auto type = l.find("type");
        if (type == l.end() || !type->is_string())
          c.fail(at + ".type", "must be \"point\", \"spot\" or \"directional\"");
        checkGltfNumbers(c.file, l, at, "color", 3, false);
        checkGltfNumbers(c.file, l, at, "intensity", 0, false);
        checkGltfNumbers(c.file, l, at, "range", 0, false);
        if (type->get<std::string>() == "spot") {
          const auto spot = l.find("spot");
          if (spot == l.end() || !spot->is_object())
            c.fail(at + ".spot", "a spot light needs its \"spot\" object (the cone angles)");
          checkGltfNumbers(c.file, *spot, at + ".spot", "innerConeAngle", 0, false);
          checkGltfNumbers(c.file, *spot, at + ".spot", "outerConeAngle", 0, false);
        }
      }
    }
  }
  for (size_t i = 0; i < c.count("nodes"); ++i) {
    const Json& n = c.item("nodes", i);
    const std::string p = Checker::at("nodes", i);
    c.index(n, p, "mesh", "meshes", false);
    c.index(n, p, "camera", "cameras", false);
    c.index(n, p, "skin", "skins", false);
    checkGltfNumbers(c.file, n, p, "translation", 3, false);
    checkGltfNumbers(c.file, n, p, "rotation", 4, false);
    checkGltfNumbers(c.file, n, p, "scale", 3, false);
    checkGltfNumbers(c.file, n, p, "matrix", 16, false);
    if (n.contains("matrix") &&
        (n.contains("translation") || n.contains("rotation") || n.contains("scale")))
      c.fail(p + ".matrix", "a node has a matrix or translation/rotation/scale, not both");
    if (const auto ch = n.find("children"); ch != n.end()) {
      if (!ch->is_array()) c.fail(p + ".children", "must be an array");
      for (size_t k = 0; k < ch->size(); ++k)
        if (!(*ch)[k].is_number_integer() || (*ch)[k].get<std::int64_t>() < 0 ||
            (*ch)[k].get<std::int64_t>() >= static_cast<std::int64_t>(c.count("nodes")))
          c.fail(p + ".children[" + std::to_string(k) + "]", "is not a node index");
    }
    if (const auto ext = n.find("extensions"); ext != n.end() && ext->is_object()) {
      if (const auto lp = ext->find("KHR_lights_punctual"); lp != ext->end()) {
        const std::int64_t l = c.integer(*lp, p + ".extensions.KHR_lights_punctual", "light", 0,
                                         static_cast<std::int64_t>(lightCount) - 1, true);
        (void)l;
      }
    }
  }
  for (size_t i = 0; i < c.count("scenes"); ++i) {
    const Json& s = c.item("scenes", i);
    const std::string p = Checker::at("scenes", i);
    if (const auto nodes = s.find("nodes"); nodes != s.end()) {
      if (!nodes->is_array()) c.fail(p + ".nodes", "must be an array");
      for (size_t k = 0; k < nodes->size(); ++k)
        if (!(*nodes)[k].is_number_integer() || (*nodes)[k].get<std::int64_t>() < 0 ||
            (*nodes)[k].get<std::int64_t>() >= static_cast<std::int64_t>(c.count("nodes")))
          c.fail(p + ".nodes[" + std::to_string(k) + "]", "is not a node index");
    }
  }
  c.index(root, "", "scene", "scenes", false);
  for (size_t i = 0; i < c.count("animations"); ++i) {
    const Json& a = c.item("animations", i);
    const std::string p = Checker::at("animations", i);
    const auto samplers = a.find("samplers");
    const auto channels = a.find("channels");
    if (samplers == a.end() || !samplers->is_array()) c.fail(p + ".samplers", "must be an array");
    if (channels == a.end() || !channels->is_array()) c.fail(p + ".channels", "must be an array");
    for (size_t k = 0; k < samplers->size(); ++k) {
      const std::string sp = p + ".samplers[" + std::to_string(k) + "]";
      if (!(*samplers)[k].is_object()) c.fail(sp, "must be an object");
      c.index((*samplers)[k], sp, "input", "accessors", true);
      c.index((*samplers)[k], sp, "output", "accessors", true);
    }
    for (size_t k = 0; k < channels->size(); ++k) {
      const std::string cp = p + ".channels[" + std::to_string(k) + "]";
      const Json& ch = (*channels)[k];
      if (!ch.is_object()) c.fail(cp, "must be an object");
      c.integer(ch, cp, "sampler", 0, static_cast<std::int64_t>(samplers->size()) - 1, true);
      const auto target = ch.find("target");
      if (target == ch.end() || !target->is_object()) c.fail(cp + ".target", "is missing");
      c.index(*target, cp + ".target", "node", "nodes", false);
    }
  }
}

}  // namespace camsim
