// Reads a glTF 2.0 file through tinygltf (Debian's libtinygltf) after gltf_validate.cpp
// has checked its structure, and copies what camsim uses into GltfDocument: images,
// cameras, lights and nodes here, materials in gltf_read_materials.cpp, accessor data
// (with the checks that need the values: index values inside the vertex count, finite
// positions, normals and keys, increasing key times) in gltf_accessors.cpp.
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <set>

#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "integrator/scene/gltf_document.h"
#include "sensor/base/input_error.h"
#include "sensor/base/input_file.h"

namespace camsim {

// obj[key] as a number, or fallback where obj has no such number (also used by
// gltf_read_materials.cpp).
double gltfNumber(const tinygltf::Value& obj, const char* key, double fallback) {
  if (!obj.IsObject() || !obj.Has(key)) return fallback;
  const tinygltf::Value& v = obj.Get(key);
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

glm::dmat4 GltfNode::local() const {
  if (hasMatrix) return matrix;
  return glm::translate(glm::dmat4(1.0), translation) * glm::mat4_cast(rotation) *
         glm::scale(glm::dmat4(1.0), scale);
}

void readGltfMaterials(const tinygltf::Model& model, GltfDocument& doc, const std::string& name);
void readGltfMeshes(const tinygltf::Model& model, GltfDocument& doc, const std::string& name);
void readGltfAnimations(const tinygltf::Model& model, GltfDocument& doc, const std::string& name);

namespace {

std::uint32_t le32(const std::string& b, size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i)
    v = (v << 8) | static_cast<unsigned char>(b[at + static_cast<size_t>(i)]);
  return v;
}

// tinygltf names objects as "image[1]", "accessor[0]": the JSON path "images[1]", if any.
std::string jsonPathIn(const std::string& message) {
  for (const char* kind : {"image", "buffer", "accessor", "bufferView", "texture", "material",
                           "mesh", "node", "animation", "camera"}) {
    const std::string tag = std::string(kind) + "[";
    const size_t at = message.find(tag);
    if (at == std::string::npos) continue;
    const size_t close = message.find(']', at);
    const std::string digits = message.substr(at + tag.size(), close - at - tag.size());
    if (close == std::string::npos || digits.empty() ||
        digits.find_first_not_of("0123456789") != std::string::npos)
      continue;
    return std::string(kind) + "s[" + digits + "]";
  }
  return "";
}

std::string at(const char* array, size_t i) {
  return std::string(array) + "[" + std::to_string(i) + "]";
}

void readImages(const tinygltf::Model& model, GltfDocument& doc, const std::string& name,
                const std::filesystem::path& baseDir) {
  for (size_t i = 0; i < model.images.size(); ++i) {
    const tinygltf::Image& im = model.images[i];
    GltfImage g;
    g.path = at("images", i);
    g.name = im.name;
    if (!im.uri.empty() && im.uri.rfind("data:", 0) != 0) g.file = baseDir / im.uri;
    if (im.image.empty() || im.width <= 0 || im.height <= 0 || im.component <= 0 ||
        (im.bits != 8 && im.bits != 16))
      throw InputError({name, 0, 0}, g.path,
                       "the image could not be decoded (camsim reads PNG and JPEG images)");
    auto texels = std::make_shared<TextureImage>();
    texels->width = im.width;
    texels->height = im.height;
    texels->channels = 4;
    const size_t n = static_cast<size_t>(im.width) * static_cast<size_t>(im.height);
    const size_t comps = static_cast<size_t>(im.component);
    const size_t bytes = static_cast<size_t>(im.bits / 8);
    if (im.image.size() < n * comps * bytes)
      throw InputError({name, 0, 0}, g.path, "decoded image is shorter than its size");
    texels->values.resize(n * 4);
    const double scale = im.bits == 8 ? 1.0 / 255.0 : 1.0 / 65535.0;
    for (size_t p = 0; p < n; ++p) {
      for (size_t c = 0; c < 4; ++c) {
        double v = 1.0;  // missing alpha is opaque
        if (c < comps) {
          const size_t o = (p * comps + c) * bytes;
          const unsigned raw = bytes == 1 ? im.image[o]
                                          : static_cast<unsigned>(im.image[o]) |
                                                static_cast<unsigned>(im.image[o + 1]) << 8;
          v = raw * scale;
        } else if (c < 3 && comps < 3) {
          v = static_cast<double>(texels->values[p * 4]);  // grey: R = G = B
        }
        texels->values[p * 4 + c] = static_cast<float>(v);
      }
    }
    g.texels = std::move(texels);
    doc.images.push_back(std::move(g));
  }
}

void readCamerasAndLights(const tinygltf::Model& model, GltfDocument& doc,
                          const std::string& name) {
  for (size_t i = 0; i < model.cameras.size(); ++i) {
    const tinygltf::Camera& c = model.cameras[i];
    GltfCamera g;
    g.name = c.name;
    g.path = at("cameras", i);
    if (c.type == "perspective") {
      g.yfov = c.perspective.yfov;
      g.aspectRatio = c.perspective.aspectRatio;
      g.znear = c.perspective.znear;
      g.zfar = c.perspective.zfar;
      if (!(g.yfov > 0.0 && g.yfov < 3.14159))
        throw InputError({name, 0, 0}, g.path + ".perspective.yfov", "must lie in (0, π) radians");
      if (!(g.aspectRatio >= 0.0) || !std::isfinite(g.aspectRatio))
        throw InputError({name, 0, 0}, g.path + ".perspective.aspectRatio", "must be > 0");
    } else if (c.type == "orthographic") {
      g.perspective = false;
    } else {
      throw InputError({name, 0, 0}, g.path + ".type",
                       "must be perspective or orthographic (it is '" + c.type + "')");
    }
    doc.cameras.push_back(g);
  }
  for (size_t i = 0; i < model.lights.size(); ++i) {
    const tinygltf::Light& l = model.lights[i];
    GltfLight g;
    g.name = l.name;
    g.path = "extensions.KHR_lights_punctual." + at("lights", i);
    if (l.type == "point")
      g.type = GltfLight::Type::kPoint;
    else if (l.type == "spot")
      g.type = GltfLight::Type::kSpot;
    else if (l.type == "directional")
      g.type = GltfLight::Type::kDirectional;
    else
      throw InputError({name, 0, 0}, g.path + ".type",
                       "must be point, spot or directional (it is '" + l.type + "')");
    for (size_t c = 0; c < 3 && c < l.color.size(); ++c) g.color[static_cast<int>(c)] = l.color[c];
    g.intensity = l.intensity;
    g.range = l.range;
    g.innerConeAngle = l.spot.innerConeAngle;
    g.outerConeAngle = l.spot.outerConeAngle;
    // The scene file's lights' bound (cd or lx): found by probing, an intensity of 1e45 gave
    // NaN samples (dropped, exit 0). The colour is the extension's linear RGB in [0, 1].
    if (!(g.intensity >= 0.0 && g.intensity <= 1e30))
      throw InputError({name, 0, 0}, g.path + ".intensity",
                       "must be a number in [0, 1e30] (cd, or lx for a directional light)");
    for (int c = 0; c < 3; ++c)
      if (!(g.color[c] >= 0.0 && g.color[c] <= 1.0))
        throw InputError({name, 0, 0}, g.path + ".color",
                         "components must be in [0, 1] (linear RGB; the intensity scales it)");
    if (g.type == GltfLight::Type::kSpot &&
        !(g.innerConeAngle >= 0.0 && g.innerConeAngle < g.outerConeAngle &&
          g.outerConeAngle <= 1.5707963267948966))
      throw InputError({name, 0, 0}, g.path + ".spot",
                       "needs 0 <= innerConeAngle < outerConeAngle <= π/2");
    doc.lights.push_back(g);
  }
}

void readNodes(const tinygltf::Model& model, GltfDocument& doc, const std::string& name) {
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    const tinygltf::Node& n = model.nodes[i];
    GltfNode g;
    g.name = n.name;
    g.path = at("nodes", i);
    auto bad = [&](const char* key, const char* what) {
      throw InputError({name, 0, 0}, g.path + "." + key, what);
    };
    auto finite = [](const std::vector<double>& v) {
      for (double x : v)
        if (!std::isfinite(x)) return false;
      return true;
    };
    if (!n.matrix.empty()) {
      if (n.matrix.size() != 16 || !finite(n.matrix)) bad("matrix", "needs 16 finite numbers");
      g.matrix = glm::make_mat4(n.matrix.data());  // column-major, as glTF stores it
      g.hasMatrix = true;
      // An affine map, given instead of TRS (found by probing: a projective bottom row was
      // read and the mesh landed where the render origin put it).
      if (g.matrix[0][3] != 0.0 || g.matrix[1][3] != 0.0 || g.matrix[2][3] != 0.0 ||
          g.matrix[3][3] != 1.0)
        bad("matrix", "must be affine: its last row (elements 3, 7, 11, 15) 0, 0, 0, 1");
    }
    if (!n.translation.empty()) {
      if (n.translation.size() != 3 || !finite(n.translation))
        bad("translation", "needs 3 finite numbers");
      g.translation = glm::dvec3(n.translation[0], n.translation[1], n.translation[2]);
    }
    if (!n.rotation.empty()) {
      if (n.rotation.size() != 4 || !finite(n.rotation)) bad("rotation", "needs 4 finite numbers");
      g.rotation = glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
      const double len = glm::length(g.rotation);
      if (!(std::abs(len - 1.0) < 1e-2)) bad("rotation", "must be a unit quaternion (x, y, z, w)");
      g.rotation /= len;
    }
    if (!n.scale.empty()) {
      if (n.scale.size() != 3 || !finite(n.scale)) bad("scale", "needs 3 finite numbers");
      g.scale = glm::dvec3(n.scale[0], n.scale[1], n.scale[2]);
    }
    g.children = n.children;
    g.mesh = n.mesh;
    g.camera = n.camera;
    g.skinned = n.skin >= 0;
    g.morphed = !n.weights.empty();
    if (const auto ext = n.extensions.find("KHR_lights_punctual"); ext != n.extensions.end())
      g.light = static_cast<int>(gltfNumber(ext->second, "light", -1.0));
    doc.nodes.push_back(std::move(g));
  }
  for (const tinygltf::Scene& s : model.scenes) doc.scenes.push_back(s.nodes);
  doc.defaultScene = model.defaultScene >= 0 ? model.defaultScene : 0;
  // A node may have one parent and must not be its own ancestor.
  std::vector<int> parent(doc.nodes.size(), -1);
  for (size_t i = 0; i < doc.nodes.size(); ++i)
    for (int c : doc.nodes[i].children) {
      if (parent[static_cast<size_t>(c)] >= 0 || c == static_cast<int>(i))
        throw InputError({name, 0, 0}, doc.nodes[i].path + ".children",
                         "node " + std::to_string(c) + " has more than one parent, or is its own");
      parent[static_cast<size_t>(c)] = static_cast<int>(i);
    }
  // Each node's depth, once (found by probing: walking every node's ancestors took 9.5 s for
  // a chain of 100,000), and no deeper than the loader's recursion may go (2,000 levels
  // overflowed the stack).
  std::vector<int> depth(doc.nodes.size(), -1);
  std::vector<size_t> path;
  for (size_t i = 0; i < doc.nodes.size(); ++i) {
    path.clear();
    int p = static_cast<int>(i);
    while (p >= 0 && depth[static_cast<size_t>(p)] < 0) {
      path.push_back(static_cast<size_t>(p));
      if (path.size() > doc.nodes.size())
        throw InputError({name, 0, 0}, doc.nodes[i].path, "the node hierarchy has a cycle");
      p = parent[static_cast<size_t>(p)];
    }
    int d = p < 0 ? 0 : depth[static_cast<size_t>(p)] + 1;
    for (auto it = path.rbegin(); it != path.rend(); ++it) {
      if (d >= kMaxGltfNodeDepth)
        throw InputError({name, 0, 0}, doc.nodes[*it].path,
                         "nests " + std::to_string(d + 1) + " nodes deep; camsim reads at most " +
                             std::to_string(kMaxGltfNodeDepth));
      depth[*it] = d++;
    }
  }
  // A scene's nodes are distinct roots (found by probing: one listed twice, or also a child,
  // was placed twice).
  std::vector<bool> listed(doc.nodes.size(), false);
  for (size_t s = 0; s < doc.scenes.size(); ++s) {
    for (int r : doc.scenes[s]) listed[static_cast<size_t>(r)] = false;  // this scene's only
    for (size_t k = 0; k < doc.scenes[s].size(); ++k) {
      const auto r = static_cast<size_t>(doc.scenes[s][k]);
      const std::string where = at("scenes", s) + ".nodes[" + std::to_string(k) + "]";
      if (listed[r])
        throw InputError({name, 0, 0}, where, "node " + std::to_string(r) + " is listed twice");
      if (parent[r] >= 0)
        throw InputError({name, 0, 0}, where,
                         "node " + std::to_string(r) + " is a child of " +
                             doc.nodes[static_cast<size_t>(parent[r])].path +
                             ": a scene's nodes are roots");
      listed[r] = true;
    }
  }
}

}  // namespace

std::int64_t gltfDataUriBytes(const std::string& uri) {
  size_t at = std::string::npos;
  for (const char* type : {"application/octet-stream", "application/gltf-buffer", "image/jpeg",
                           "image/png", "image/bmp", "image/gif", "text/plain"}) {
    const std::string header = std::string("data:") + type + ";base64,";
    if (uri.rfind(header, 0) == 0) at = header.size();
  }
  if (at == std::string::npos) return -1;
  std::int64_t chars = 0;
  while (at < uri.size() &&
         (std::isalnum(static_cast<unsigned char>(uri[at])) || uri[at] == '+' || uri[at] == '/')) {
    ++chars;
    ++at;
  }
  return chars / 4 * 3 + (chars % 4 > 1 ? chars % 4 - 1 : 0);  // a last 2 or 3 give 1 or 2
}

GltfDocument parseGltf(const std::string& bytes, const std::string& displayName,
                       const std::filesystem::path& baseDir) {
  const bool glb = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
  std::string json;
  size_t binBytes = 0;
  if (glb) {
    auto fail = [&](const std::string& m) { throw InputError({displayName, 0, 0}, "", m); };
    if (bytes.size() < 20) fail("truncated .glb: " + std::to_string(bytes.size()) + " bytes");
    if (le32(bytes, 4) != 2)
      fail("a .glb of version " + std::to_string(le32(bytes, 4)) + " (camsim reads 2)");
    if (le32(bytes, 8) != bytes.size())
      fail("truncated .glb: its header says " + std::to_string(le32(bytes, 8)) +
           " bytes, the file has " + std::to_string(bytes.size()));
    const size_t jsonBytes = le32(bytes, 12);
    if (le32(bytes, 16) != 0x4E4F534Au || 20 + jsonBytes > bytes.size())
      fail("malformed .glb: the first chunk must be JSON and fit in the file");
    json = bytes.substr(20, jsonBytes);
    const size_t bin = 20 + ((jsonBytes + 3) & ~size_t(3));
    if (bin + 8 <= bytes.size()) {
      if (le32(bytes, bin + 4) != 0x004E4942u) fail("malformed .glb: the second chunk must be BIN");
      binBytes = le32(bytes, bin);
      if (bin + 8 + binBytes > bytes.size())
        fail("truncated .glb: the BIN chunk of " + std::to_string(binBytes) +
             " bytes does not fit");
    }
  } else {
    json = bytes;
  }
  validateGltfJson(json, displayName, baseDir, binBytes, glb);

  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  const bool ok =
      glb ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                        reinterpret_cast<const unsigned char*>(bytes.data()),
                                        static_cast<unsigned>(bytes.size()), baseDir.string())
          : loader.LoadASCIIFromString(&model, &err, &warn, json.data(),
                                       static_cast<unsigned>(json.size()), baseDir.string());
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw InputError({displayName, 0, 0}, jsonPathIn(err), "tinygltf: " + err);
  }
  GltfDocument doc;
  doc.file = displayName;
  std::set<std::string> seen;
  auto noteFile = [&](const std::string& uri) {
    if (!uri.empty() && uri.rfind("data:", 0) != 0 && seen.insert(uri).second)
      doc.filesRead.push_back(baseDir / uri);
  };
  for (const tinygltf::Buffer& b : model.buffers) noteFile(b.uri);
  for (const tinygltf::Image& im : model.images) noteFile(im.uri);
  for (const std::string& ext : model.extensionsRequired)
    if (ext != "KHR_lights_punctual" && ext != "KHR_materials_emissive_strength" &&
        ext != "KHR_materials_transmission" && ext != "KHR_materials_ior" &&
        ext != "KHR_texture_transform")
      throw InputError({displayName, 0, 0}, "extensionsRequired",
                       "requires " + ext + ", which camsim does not read");
  readImages(model, doc, displayName, baseDir);
  readGltfMaterials(model, doc, displayName);
  readCamerasAndLights(model, doc, displayName);
  readNodes(model, doc, displayName);
  readGltfMeshes(model, doc, displayName);
  readGltfAnimations(model, doc, displayName);
  return doc;
}

GltfDocument readGltf(const std::filesystem::path& file) {
  const std::string text = readInputFile(file, "glTF file");
  const std::filesystem::path dir = file.parent_path().empty() ? "." : file.parent_path();
  return parseGltf(text, file.string(), dir);
}

}  // namespace camsim
