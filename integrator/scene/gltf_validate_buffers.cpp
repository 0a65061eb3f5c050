// The glTF structural check's part for the data (gltf_json_checker.h): buffers, buffer
// views and accessors, each extent and length named by its JSON path.
#include <cctype>
#include <system_error>
#include <vector>

#include "integrator/scene/gltf_json_checker.h"

namespace camsim::gltf_check {
namespace {

// A buffer's data holds exactly byteLength bytes (tinygltf refuses any other length with
// its raw text): a data URI's decoded base64, or the external file's size.
void checkBufferData(const Checker& c, const Json& b, const std::string& path,
                     std::int64_t byteLength) {
  if (!b.at("uri").is_string()) c.fail(path + ".uri", "must be a string");
  const std::string u = b.at("uri").get<std::string>();
  std::int64_t bytes = 0;
  std::string what;
  if (u.rfind("data:", 0) == 0) {
    // The media types tinygltf decodes (glTF's are application/octet-stream and
    // application/gltf-buffer); base64 characters up to the first '=' or other character.
    size_t at = std::string::npos;
    for (const char* type : {"application/octet-stream", "application/gltf-buffer", "image/jpeg",
                             "image/png", "image/bmp", "image/gif", "text/plain"}) {
      const std::string header = std::string("data:") + type + ";base64,";
      if (u.rfind(header, 0) == 0) at = header.size();
    }
    if (at == std::string::npos)
      c.fail(path + ".uri",
             "a data URI must be base64: data:application/octet-stream;base64,… (or "
             "application/gltf-buffer)");
    std::int64_t chars = 0;
    for (size_t i = at; i < u.size(); ++i) {
      const unsigned char ch = static_cast<unsigned char>(u[i]);
      if (!(std::isalnum(ch) || ch == '+' || ch == '/')) break;
      ++chars;
    }
    bytes = chars / 4 * 3 + (chars % 4 > 1 ? chars % 4 - 1 : 0);
    what = "its data URI decodes to ";
  } else {
    std::error_code ec;
    const std::filesystem::path file = c.externalFile(b, path);
    bytes = static_cast<std::int64_t>(std::filesystem::file_size(file, ec));
    if (ec) c.fail(path + ".uri", "cannot read the size of '" + file.string() + "'");
    what = "its file '" + file.string() + "' holds ";
  }
  if (bytes < byteLength)
    c.fail(path, what + std::to_string(bytes) + " bytes, fewer than its byteLength " +
                     std::to_string(byteLength) + ": the buffer is truncated");
  if (bytes > byteLength)
    c.fail(path, what + std::to_string(bytes) + " bytes but its byteLength is " +
                     std::to_string(byteLength) + " (they must be equal)");
}

// Accessors that primitives use as indices, each with the first such primitive's path
// ("meshes[0].primitives[1].indices"); a malformed mesh is skipped (the mesh check names it).
std::vector<std::string> indexUses(const Checker& c) {
  std::vector<std::string> uses(c.count("accessors"));
  const auto meshes = c.root.find("meshes");
  if (meshes == c.root.end() || !meshes->is_array()) return uses;
  for (size_t i = 0; i < meshes->size(); ++i) {
    const Json& m = (*meshes)[i];
    const auto prims = m.is_object() ? m.find("primitives") : m.end();
    if (!m.is_object() || prims == m.end() || !prims->is_array()) continue;
    for (size_t k = 0; k < prims->size(); ++k) {
      const Json& prim = (*prims)[k];
      const auto ind = prim.is_object() ? prim.find("indices") : prim.end();
      if (!prim.is_object() || ind == prim.end() || !ind->is_number_unsigned()) continue;
      const auto a = ind->get<std::uint64_t>();
      if (a < uses.size() && uses[a].empty())
        uses[a] = Checker::at("meshes", i) + ".primitives[" + std::to_string(k) + "].indices";
    }
  }
  return uses;
}

}  // namespace

void checkBuffers(const Checker& c, std::size_t glbBinBytes, bool isGlb) {
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
    const size_t cb = componentBytes(ct);
    if (cb == 0) c.fail(p + ".componentType", "is not a glTF component type");
    if (!usedAsIndices[i].empty() && ct != 5121 && ct != 5123 && ct != 5125)
      c.fail(p + ".componentType", std::string("is ") + componentName(ct) + " but " +
                                       usedAsIndices[i] +
                                       " needs UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    const auto type = a.find("type");
    if (type == a.end() || !type->is_string() || componentCount(type->get<std::string>()) == 0)
      c.fail(p + ".type", "must be SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4");
    const std::int64_t count = c.integer(a, p, "count", 1, std::int64_t(1) << 32, true);
    if (a.contains("sparse")) c.fail(p + ".sparse", "sparse accessors are not supported");
    const std::int64_t view = c.index(a, p, "bufferView", "bufferViews", false);
    if (view < 0) continue;  // all zeros
    const std::int64_t offset = c.integer(a, p, "byteOffset", 0, std::int64_t(1) << 40, false);
    const Json& v = c.root.at("bufferViews").at(static_cast<size_t>(view));
    const std::int64_t element =
        static_cast<std::int64_t>(cb * componentCount(type->get<std::string>()));
    const std::int64_t stride =
        v.contains("byteStride") ? v["byteStride"].get<std::int64_t>() : element;
    if (stride < element)
      c.fail(Checker::at("bufferViews", static_cast<size_t>(view)) + ".byteStride",
             "is " + std::to_string(stride) + " bytes, less than the " + std::to_string(element) +
                 "-byte elements of " + p + " (" + type->get<std::string>() + " of " +
                 componentName(ct) + "): they would overlap");
    const std::int64_t end = offset + stride * (count - 1) + element;
    if (end > viewBytes[static_cast<size_t>(view)])
      c.fail(p + ".count", std::to_string(count) + " elements from byteOffset " +
                               std::to_string(offset) + " end at byte " + std::to_string(end) +
                               ", past bufferViews[" + std::to_string(view) + "].byteLength = " +
                               std::to_string(viewBytes[static_cast<size_t>(view)]));
  }
}

}  // namespace camsim::gltf_check
