// The structural check of a glTF file's JSON, before tinygltf reads it: tinygltf rejects
// many malformed files itself, but its messages seldom say where ("'byteLength' property is
// not a positive integer"), and a user needs the JSON path to fix the file. Each check here
// names it: every index in range, every byte extent inside its view and its buffer, counts
// and lengths positive integers, external files present (buffers, views and accessors:
// gltf_validate_buffers.cpp). Value checks that need the data (index values, NaN
// positions) are done as the data is read (gltf_accessors.cpp).
#include "integrator/scene/gltf_document.h"
#include "integrator/scene/gltf_json_checker.h"

namespace camsim {
namespace {

using gltf_check::Checker;
using gltf_check::Json;

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

  gltf_check::checkBuffers(c, glbBinBytes, isGlb);
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
  for (size_t i = 0; i < c.count("cameras"); ++i) c.item("cameras", i);
  size_t lightCount = 0;
  if (const auto ext = root.find("extensions"); ext != root.end() && ext->is_object()) {
    if (const auto lp = ext->find("KHR_lights_punctual"); lp != ext->end()) {
      const auto lights = lp->find("lights");
      if (lights == lp->end() || !lights->is_array())
        c.fail("extensions.KHR_lights_punctual.lights", "must be an array");
      lightCount = lights->size();
    }
  }
  for (size_t i = 0; i < c.count("nodes"); ++i) {
    const Json& n = c.item("nodes", i);
    const std::string p = Checker::at("nodes", i);
    c.index(n, p, "mesh", "meshes", false);
    c.index(n, p, "camera", "cameras", false);
    c.index(n, p, "skin", "skins", false);
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
