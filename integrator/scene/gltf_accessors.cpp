// Accessor data of a glTF file into GltfDocument: mesh primitives (as triangles, with the
// texture coordinates their material reads and COLOR_0) and animation channels. The structure (indices, extents) was checked by gltf_validate.cpp;
// here the values are: index values below the vertex count, finite attributes, unit-length
// normals and tangents (renormalised, as renderers do, but zero or NaN refused), strictly
// increasing key times.
//   component types (glTF 2.0 §3.6.2): float, and for normalized attributes unsigned
//   c / (2ⁿ − 1) and signed max(c / (2ⁿ⁻¹ − 1), −1)
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include <tiny_gltf.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "integrator/scene/gltf_document.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace {

struct Reader {
  const tinygltf::Model& model;
  const std::string& file;

  [[noreturn]] void fail(const std::string& path, const std::string& m) const {
    throw InputError({file, 0, 0}, path, m);
  }

  static int components(int type) {
    switch (type) {
      case TINYGLTF_TYPE_SCALAR:
        return 1;
      case TINYGLTF_TYPE_VEC2:
        return 2;
      case TINYGLTF_TYPE_VEC3:
        return 3;
      case TINYGLTF_TYPE_VEC4:
        return 4;
      default:
        return 0;
    }
  }

  // Elements of accessor `index` as up to 4 doubles each; `want` components (a different
  // type is an error naming `use`), float or (normalized) integers as `allowInts`.
  std::vector<glm::dvec4> read(int index, int want, bool allowInts, const std::string& use) const {
    const std::string path = "accessors[" + std::to_string(index) + "]";
    const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(index)];
    const int comps = components(a.type);
    if (comps != want)
      fail(path + ".type",
           use + " needs " + (want == 1 ? std::string("SCALAR") : "VEC" + std::to_string(want)));
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !allowInts)
      fail(path + ".componentType", use + " must be FLOAT");
    std::vector<glm::dvec4> out(a.count, glm::dvec4(0.0));
    if (a.bufferView < 0) return out;  // all zeros (glTF 2.0 §3.6.2.3)
    const tinygltf::BufferView& v = model.bufferViews[static_cast<size_t>(a.bufferView)];
    const tinygltf::Buffer& b = model.buffers[static_cast<size_t>(v.buffer)];
    const size_t size = static_cast<size_t>(
        tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType)));
    const size_t stride = v.byteStride ? v.byteStride : size * static_cast<size_t>(comps);
    const size_t start = v.byteOffset + a.byteOffset;
    if (start + stride * (a.count - 1) + size * static_cast<size_t>(comps) > b.data.size())
      fail(path + ".count",
           "the data runs past the end of buffers[" + std::to_string(v.buffer) + "]");
    for (size_t e = 0; e < a.count; ++e) {
      const unsigned char* p = b.data.data() + start + e * stride;
      for (int c = 0; c < comps; ++c) {
        const unsigned char* q = p + static_cast<size_t>(c) * size;
        double x = 0.0;
        switch (a.componentType) {
          case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float f;
            std::memcpy(&f, q, 4);
            x = static_cast<double>(f);
            break;
          }
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            x = *q;
            if (a.normalized) x /= 255.0;
            break;
          case TINYGLTF_COMPONENT_TYPE_BYTE:
            x = static_cast<std::int8_t>(*q);
            if (a.normalized) x = std::max(x / 127.0, -1.0);
            break;
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            std::uint16_t u;
            std::memcpy(&u, q, 2);
            x = u;
            if (a.normalized) x /= 65535.0;
            break;
          }
          case TINYGLTF_COMPONENT_TYPE_SHORT: {
            std::int16_t s;
            std::memcpy(&s, q, 2);
            x = s;
            if (a.normalized) x = std::max(x / 32767.0, -1.0);
            break;
          }
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            std::uint32_t u;
            std::memcpy(&u, q, 4);
            x = u;
            break;
          }
          default:
            fail(path + ".componentType", "unsupported component type");
        }
        if (!std::isfinite(x))
          fail(path, use + ": element " + std::to_string(e) + " is not finite (NaN or infinity)");
        out[e][c] = x;
      }
    }
    return out;
  }

  std::vector<std::uint32_t> indices(int index, size_t vertexCount) const {
    const std::string path = "accessors[" + std::to_string(index) + "]";
    const tinygltf::Accessor& a = model.accessors[static_cast<size_t>(index)];
    if (a.type != TINYGLTF_TYPE_SCALAR) fail(path + ".type", "indices must be SCALAR");
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(path + ".componentType", "indices must be unsigned bytes, shorts or ints");
    if (a.normalized) fail(path + ".normalized", "indices must not be normalized");
    std::vector<std::uint32_t> out;
    out.reserve(a.count);
    for (size_t e = 0; const glm::dvec4& v : read(index, 1, true, "indices")) {
      if (!(v.x < static_cast<double>(vertexCount)))
        fail(path, "index " + std::to_string(static_cast<std::uint64_t>(v.x)) + " at element " +
                       std::to_string(e) + " is out of range: the primitive has " +
                       std::to_string(vertexCount) + " vertices");
      out.push_back(static_cast<std::uint32_t>(v.x));
      ++e;
    }
    return out;
  }
};

// COLOR_0 (glTF 2.0 §3.7.2.1): VEC3 or VEC4 of float, or of normalized unsigned bytes or
// shorts; linear RGB, clamped to [0, 1] (a reflectance), alpha only noted.
void readColors(const Reader& r, int index, GltfPrimitive& g) {
  const std::string path = "accessors[" + std::to_string(index) + "]";
  const tinygltf::Accessor& a = r.model.accessors[static_cast<size_t>(index)];
  if (a.type != TINYGLTF_TYPE_VEC3 && a.type != TINYGLTF_TYPE_VEC4)
    r.fail(path + ".type", "COLOR_0 must be VEC3 or VEC4");
  const bool integer = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                       a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  if (!integer && a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    r.fail(path + ".componentType",
           "COLOR_0 must be FLOAT, or normalized UNSIGNED_BYTE or UNSIGNED_SHORT");
  if (integer && !a.normalized)
    r.fail(path + ".normalized", "COLOR_0 of unsigned bytes or shorts must be normalized");
  const int comps = a.type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
  for (const glm::dvec4& c : r.read(index, comps, true, "COLOR_0")) {
    g.mesh.colors.emplace_back(glm::clamp(glm::dvec3(c), 0.0, 1.0));
    g.colorAlpha = g.colorAlpha || (comps == 4 && c.w < 1.0);
  }
}

// Triangles from a primitive's vertex order (glTF 2.0 §3.7.2.1): lists as they are, strips
// with every second triangle's first two vertices swapped so all keep the strip's winding,
// fans around the first vertex. Degenerate triangles (a repeated index) are dropped.
std::vector<std::uint32_t> triangles(const std::vector<std::uint32_t>& v, int mode) {
  std::vector<std::uint32_t> t;
  auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (a != b && b != c && a != c) t.insert(t.end(), {a, b, c});
  };
  if (mode == TINYGLTF_MODE_TRIANGLES)
    for (size_t i = 0; i + 2 < v.size(); i += 3) add(v[i], v[i + 1], v[i + 2]);
  else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
    for (size_t i = 0; i + 2 < v.size(); ++i)
      i % 2 == 0 ? add(v[i], v[i + 1], v[i + 2]) : add(v[i + 1], v[i], v[i + 2]);
  else
    for (size_t i = 1; i + 1 < v.size(); ++i) add(v[0], v[i], v[i + 1]);
  return t;
}

}  // namespace

void readGltfMeshes(const tinygltf::Model& model, GltfDocument& doc, const std::string& name) {
  const Reader r{model, name};
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    GltfMesh mesh;
    mesh.name = model.meshes[m].name;
    mesh.path = "meshes[" + std::to_string(m) + "]";
    for (size_t k = 0; k < model.meshes[m].primitives.size(); ++k) {
      const tinygltf::Primitive& p = model.meshes[m].primitives[k];
      GltfPrimitive g;
      g.path = mesh.path + ".primitives[" + std::to_string(k) + "]";
      if (!p.targets.empty()) r.fail(g.path + ".targets", "morph targets are not supported");
      if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
          p.mode != TINYGLTF_MODE_TRIANGLE_FAN)
        r.fail(g.path + ".mode",
               "points and lines are not surfaces: camsim renders triangles (modes 4, 5, 6)");
      g.material = p.material;
      const int position = p.attributes.at("POSITION");
      for (const glm::dvec4& v : r.read(position, 3, false, "POSITION"))
        g.mesh.positions.emplace_back(v.x, v.y, v.z);
      const size_t n = g.mesh.positions.size();
      auto attribute = [&](const char* key) {
        const auto it = p.attributes.find(key);
        if (it == p.attributes.end()) return -1;
        if (model.accessors[static_cast<size_t>(it->second)].count != n)
          r.fail(g.path + ".attributes." + key,
                 std::string(key) + " has a different count than POSITION");
        return it->second;
      };
      if (const int a = attribute("NORMAL"); a >= 0)
        for (const glm::dvec4& v : r.read(a, 3, false, "NORMAL")) {
          const double len = glm::length(glm::dvec3(v));
          if (!(len > 1e-6))
            r.fail("accessors[" + std::to_string(a) + "]", "NORMAL has a zero vector");
          g.mesh.normals.emplace_back(glm::dvec3(v) / len);
        }
      if (const int a = attribute("TANGENT"); a >= 0)
        for (const glm::dvec4& v : r.read(a, 4, false, "TANGENT")) {
          const double len = glm::length(glm::dvec3(v));
          if (!(len > 1e-6))
            r.fail("accessors[" + std::to_string(a) + "]", "TANGENT has a zero vector");
          g.mesh.tangents.emplace_back(glm::dvec3(v) / len, v.w < 0.0 ? -1.0f : 1.0f);
        }
      // The one set of texture coordinates the material's textures read.
      const int set = g.material >= 0 ? doc.materials[static_cast<size_t>(g.material)].texCoord : 0;
      const std::string texcoord = "TEXCOORD_" + std::to_string(set);
      if (const int a = attribute(texcoord.c_str()); a >= 0)
        for (const glm::dvec4& v : r.read(a, 2, true, texcoord))
          g.mesh.uvs.emplace_back(v.x, 1.0 - v.y);  // glTF v runs down the image; camsim's up
      else if (set > 0)
        doc.notes.push_back(g.path + ": its material's textures read " + texcoord +
                            ", which it lacks: they read camsim's per-triangle default uvs");
      if (const int a = attribute("COLOR_0"); a >= 0) readColors(r, a, g);
      std::vector<std::uint32_t> order;
      if (p.indices >= 0) {
        order = r.indices(p.indices, n);
      } else {
        for (std::uint32_t i = 0; i < n; ++i) order.push_back(i);
      }
      // A triangle list's count should be a multiple of 3 (the Khronos validator warns): the
      // leftover vertices are dropped, and said so (found by probing: they were dropped
      // silently).
      if (p.mode == TINYGLTF_MODE_TRIANGLES && order.size() % 3 != 0)
        doc.notes.push_back("accessors[" + std::to_string(p.indices >= 0 ? p.indices : position) +
                            "].count: " + std::to_string(order.size()) + " vertices of " + g.path +
                            " (TRIANGLES) are no multiple of 3: the last " +
                            std::to_string(order.size() % 3) + " dropped");
      g.mesh.indices = triangles(order, p.mode);
      if (g.mesh.indices.empty()) r.fail(g.path, "has no triangles");
      mesh.primitives.push_back(std::move(g));
    }
    doc.meshes.push_back(std::move(mesh));
  }
}

void readGltfAnimations(const tinygltf::Model& model, GltfDocument& doc, const std::string& name) {
  const Reader r{model, name};
  for (size_t i = 0; i < model.animations.size(); ++i) {
    const tinygltf::Animation& a = model.animations[i];
    GltfAnimation g;
    g.name = a.name;
    g.path = "animations[" + std::to_string(i) + "]";
    for (size_t k = 0; k < a.channels.size(); ++k) {
      const tinygltf::AnimationChannel& ch = a.channels[k];
      GltfChannel c;
      c.path = g.path + ".channels[" + std::to_string(k) + "]";
      c.node = ch.target_node;
      if (c.node < 0) continue;  // no target: ignored, as the spec allows
      if (ch.target_path == "translation")
        c.target = GltfChannel::Path::kTranslation;
      else if (ch.target_path == "rotation")
        c.target = GltfChannel::Path::kRotation;
      else if (ch.target_path == "scale")
        c.target = GltfChannel::Path::kScale;
      else if (ch.target_path == "weights")
        r.fail(c.path + ".target.path",
               "morph-target weights cannot be animated: morph targets are not supported");
      else
        r.fail(c.path + ".target.path", "must be translation, rotation, scale or weights");
      const tinygltf::AnimationSampler& s = a.samplers[static_cast<size_t>(ch.sampler)];
      const std::string sp = g.path + ".samplers[" + std::to_string(ch.sampler) + "]";
      if (s.interpolation == "LINEAR")
        c.interpolation = GltfChannel::Interpolation::kLinear;
      else if (s.interpolation == "STEP")
        c.interpolation = GltfChannel::Interpolation::kStep;
      else if (s.interpolation == "CUBICSPLINE")
        c.interpolation = GltfChannel::Interpolation::kCubicSpline;
      else
        r.fail(sp + ".interpolation", "must be LINEAR, STEP or CUBICSPLINE");
      for (const glm::dvec4& t : r.read(s.input, 1, false, "animation input (times)")) {
        if (!c.times.empty() && !(t.x > c.times.back()))
          r.fail("accessors[" + std::to_string(s.input) + "]",
                 "key times must be strictly increasing");
        if (!(t.x >= 0.0))  // glTF 2.0 §3.11 (found by probing: −1 s was accepted)
          r.fail("accessors[" + std::to_string(s.input) + "]", "key times must be >= 0 s");
        c.times.push_back(t.x);
      }
      const int comps = c.target == GltfChannel::Path::kRotation ? 4 : 3;
      c.values =
          r.read(s.output, comps, c.target == GltfChannel::Path::kRotation, "animation output");
      const size_t per = c.interpolation == GltfChannel::Interpolation::kCubicSpline ? 3 : 1;
      // A rotation key is a unit quaternion, to the rounding of normalised integers (found
      // by probing: zero keys were accepted); a cubic spline's tangents are any length.
      if (c.target == GltfChannel::Path::kRotation)
        for (size_t j = per == 3 ? 1 : 0; j < c.values.size(); j += per)
          if (!(std::abs(glm::length(c.values[j]) - 1.0) < 0.1))
            r.fail(
                "accessors[" + std::to_string(s.output) + "]",
                "rotation key " + std::to_string(j / per) + " is no unit quaternion (x, y, z, w)");
      if (c.values.size() != per * c.times.size())
        r.fail(sp + ".output", "has " + std::to_string(c.values.size()) + " values for " +
                                   std::to_string(c.times.size()) + " key times (needs " +
                                   std::to_string(per * c.times.size()) + ")");
      g.channels.push_back(std::move(c));
    }
    doc.animations.push_back(std::move(g));
  }
}

}  // namespace camsim
