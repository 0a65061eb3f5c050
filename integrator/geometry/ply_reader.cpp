// Stanford PLY reader (accepted subset: see mesh_io.h). The header is parsed into element and
// property descriptions; the body is then read by one generic loop over an ASCII or a binary
// value reader. Every element count from the header is capped and checked against the bytes
// left before anything is reserved, so a hostile file fails with InputError instead of
// allocating or looping without bound. ASCII bodies hold one element row per line (blank
// lines are skipped) and must not have data after the last row; trailing bytes after a
// binary body are ignored. Faces are fan-triangulated and triangle strips (the `tristrips`
// element) unrolled with alternating winding as the rows are read (mesh_io.h).
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "integrator/geometry/mesh_io.h"
#include "integrator/geometry/ply_values.h"
#include "sensor/base/input_error.h"
#include "sensor/base/input_file.h"

namespace camsim {

// The reader's steps join ply_values.h's namespace (not an anonymous one, whose names a
// unity build would share with the files compiled beside this one).
namespace ply_detail {

constexpr std::uint64_t kMaxElementCount = 100'000'000;
constexpr int kIndicesSlot = 8;  // vertex slots 0..7 are x y z nx ny nz u v
constexpr int kStripSlot = 9;    // tristrips vertex_indices

enum class Format : std::uint8_t { kAscii, kBinaryLittle, kBinaryBig };

struct Header {
  Format format = Format::kAscii;
  std::vector<Element> elements;
  std::size_t bodyOffset = 0;
  int lines = 0;
};

bool parseType(std::string_view s, Type& t) {
  for (std::size_t i = 0; i < std::size(kTypes); ++i) {
    if (kTypes[i].name == s || kTypes[i].alias == s) {
      t = static_cast<Type>(i);
      return true;
    }
  }
  return false;
}

[[noreturn]] void failAt(const std::string& source, int line, const std::string& message) {
  throw InputError({source, line, 0}, "", message);
}

std::vector<std::string_view> splitWords(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

Property parseProperty(const std::vector<std::string_view>& w, const std::string& src, int line) {
  Property p;
  bool ok = false;
  if (w.size() == 5 && w[1] == "list") {
    ok = parseType(w[2], p.countType) && parseType(w[3], p.type);
    p.isList = true;
    p.name = std::string(w[4]);
    if (ok && !isInteger(p.countType)) failAt(src, line, "list count type must be an integer type");
  } else if (w.size() == 3) {
    ok = parseType(w[1], p.type);
    p.name = std::string(w[2]);
  }
  if (!ok)
    failAt(src, line,
           "expected 'property <type> <name>' or 'property list <count type> <type> <name>' with "
           "types char, uchar, short, ushort, int, uint, float or double");
  return p;
}

Header parseHeader(std::string_view bytes, const std::string& src) {
  Header h;
  bool haveFormat = false;
  std::size_t pos = 0;
  int line = 0;
  while (true) {
    if (pos >= bytes.size() && line == 0) failAt(src, 1, "not a PLY file (empty)");
    if (pos >= bytes.size()) failAt(src, line, "PLY header has no 'end_header' line");
    std::size_t nl = bytes.find('\n', pos);
    if (nl == std::string_view::npos) nl = bytes.size();
    std::string_view text = bytes.substr(pos, nl - pos);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    pos = std::min(nl + 1, bytes.size());
    ++line;
    if (line == 1) {
      if (text != "ply") failAt(src, 1, "not a PLY file (the first line must be 'ply')");
      continue;
    }
    const std::vector<std::string_view> w = splitWords(text);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "format") {
      if (haveFormat || w.size() != 3) failAt(src, line, "expected one 'format <type> 1.0' line");
      constexpr std::string_view kFormats[] = {"ascii", "binary_little_endian",
                                               "binary_big_endian"};  // indexed by Format
      const auto* f = std::find(std::begin(kFormats), std::end(kFormats), w[1]);
      h.format = static_cast<Format>(f - std::begin(kFormats));
      if (f == std::end(kFormats))
        failAt(src, line,
               "unknown PLY format '" + std::string(w[1]) +
                   "' (expected ascii, binary_little_endian or binary_big_endian)");
      if (w[2] != "1.0") failAt(src, line, "unsupported PLY version '" + std::string(w[2]) + "'");
      haveFormat = true;
    } else if (w[0] == "element") {
      if (w.size() != 3) failAt(src, line, "expected 'element <name> <count>'");
      Element e;
      e.name = std::string(w[1]);
      e.line = line;
      auto [ptr, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (ec != std::errc() || ptr != w[2].data() + w[2].size())
        failAt(src, line, "bad element count '" + std::string(w[2]) + "'");
      if (e.count > kMaxElementCount)
        failAt(src, line,
               "element '" + e.name + "' count " + std::to_string(e.count) +
                   " exceeds the limit of 100000000");
      for (const Element& other : h.elements)
        if (other.name == e.name) failAt(src, line, "duplicate element '" + e.name + "'");
      h.elements.push_back(std::move(e));
    } else if (w[0] == "property") {
      if (h.elements.empty()) failAt(src, line, "property before any element");
      Property p = parseProperty(w, src, line);
      for (const Property& other : h.elements.back().properties)
        if (other.name == p.name) failAt(src, line, "duplicate property '" + p.name + "'");
      h.elements.back().properties.push_back(std::move(p));
    } else if (w[0] == "end_header" && w.size() == 1) {
      if (!haveFormat) failAt(src, line, "PLY header has no 'format' line");
      h.bodyOffset = pos;
      h.lines = line;
      return h;
    } else {
      failAt(src, line, "unknown PLY header line '" + std::string(text.substr(0, 40)) + "'");
    }
  }
}

// The element's integer list property `names[0]` (or names[1]) gets `slot`; InputError if it
// has none or it is not a list of integers.
void assignIndexList(Element& e, std::initializer_list<std::string_view> names, int slot,
                     const std::string& src) {
  for (Property& p : e.properties) {
    if (std::find(names.begin(), names.end(), p.name) == names.end()) continue;
    if (!p.isList || !isInteger(p.type))
      failAt(src, e.line, e.name + " property '" + p.name + "' must be a list of integers");
    p.slot = slot;
    return;
  }
  failAt(src, e.line, e.name + " element has no 'vertex_indices' list property");
}

// Marks the properties we use (Property::slot) and checks that they are present and usable.
// Returns the vertex count; sets hasNormals and hasUvs.
std::uint64_t assignSlots(Header& h, const std::string& src, bool& hasNormals, bool& hasUvs) {
  // Names per slot; the texture coordinates have alternatives (the first one present wins).
  static constexpr std::string_view kVertexNames[8][3] = {{"x"},
                                                          {"y"},
                                                          {"z"},
                                                          {"nx"},
                                                          {"ny"},
                                                          {"nz"},
                                                          {"u", "s", "texture_u"},
                                                          {"v", "t", "texture_v"}};
  const Element* vertex = nullptr;
  bool haveTriangles = false;  // a face or a tristrips element
  for (Element& e : h.elements) {
    if (e.name == "vertex") {
      vertex = &e;
      bool found[8] = {};
      for (Property& p : e.properties) {
        for (int s = 0; s < 8; ++s) {
          const auto& names = kVertexNames[s];
          if (found[s] || std::find(std::begin(names), std::end(names), p.name) == std::end(names))
            continue;
          if (p.isList) failAt(src, e.line, "vertex property '" + p.name + "' must not be a list");
          p.slot = s;
          found[s] = true;
        }
      }
      if (!found[0] || !found[1] || !found[2])
        failAt(src, e.line, "vertex element lacks one of the properties x, y, z");
      hasNormals = found[3] && found[4] && found[5];
      if (!hasNormals && (found[3] || found[4] || found[5]))
        failAt(src, e.line, "vertex element has some but not all of nx, ny, nz");
      hasUvs = found[6] && found[7];
      if (found[6] != found[7])
        failAt(src, e.line, "vertex element has only one texture coordinate (need u and v)");
    } else if (e.name == "face") {
      assignIndexList(e, {"vertex_indices", "vertex_index"}, kIndicesSlot, src);
      haveTriangles = true;
    } else if (e.name == "tristrips") {
      assignIndexList(e, {"vertex_indices"}, kStripSlot, src);
      haveTriangles = true;
    }
  }
  if (vertex == nullptr) failAt(src, h.lines, "PLY file has no 'vertex' element");
  if (!haveTriangles)
    failAt(src, h.lines, "PLY file has no 'face' or 'tristrips' element (no triangles)");
  return vertex->count;
}

[[noreturn]] void rowFail(const std::string& src, int line, const Element& e, std::uint64_t row,
                          const std::string& message) {
  failAt(src, line, "element '" + e.name + "' index " + std::to_string(row) + ": " + message);
}

template <class Reader>
std::int64_t readIndex(Reader& in, const Property& p, const std::string& src, const Element& e,
                       std::uint64_t row, std::uint64_t vertexCount) {
  std::int64_t index = 0;
  if (!in.integer(p.type, index))
    rowFail(src, in.line(), e, row, "missing or malformed vertex index");
  const bool strip = p.slot == kStripSlot;
  if (strip && (index == -1 || (p.type == Type::kUint32 && index == UINT32_MAX))) return -1;
  if (index < 0 || static_cast<std::uint64_t>(index) >= vertexCount)
    rowFail(src, in.line(), e, row,
            "vertex index " + std::to_string(index) + " out of range (" +
                std::to_string(vertexCount) + " vertices" +
                (strip ? "; −1 restarts a strip)" : ")"));
  return index;
}

// A face list of n indices, fan-triangulated: (v₀ v₁ v₂), (v₀ v₂ v₃), …
template <class Reader>
void readFace(Reader& in, const Property& p, std::int64_t n, const std::string& src,
              const Element& e, std::uint64_t row, std::uint64_t vertexCount,
              std::vector<std::uint32_t>& indices) {
  if (n < 3)
    rowFail(src, in.line(), e, row,
            "face has " + std::to_string(n) + " vertices (at least 3 needed)");
  std::uint32_t first = 0;
  std::uint32_t prev = 0;
  for (std::int64_t k = 0; k < n; ++k) {  // bounded: every index consumes input
    const auto u = static_cast<std::uint32_t>(readIndex(in, p, src, e, row, vertexCount));
    if (k == 0) first = u;
    if (k >= 2) indices.insert(indices.end(), {first, prev, u});
    prev = u;
  }
}

// A strip list of n indices (mesh_io.h): run position j ≥ 2 gives (s[j−2], s[j−1], s[j]) for
// even j and (s[j−1], s[j−2], s[j]) for odd j, so all triangles keep the first one's
// orientation; −1 starts a new run; a triangle with a repeated index is dropped.
template <class Reader>
void readStrip(Reader& in, const Property& p, std::int64_t n, const std::string& src,
               const Element& e, std::uint64_t row, std::uint64_t vertexCount,
               std::vector<std::uint32_t>& indices) {
  std::int64_t j = 0;                     // position in the current run
  std::uint32_t a = 0, b = 0;             // s[j−2], s[j−1]
  for (std::int64_t k = 0; k < n; ++k) {  // bounded: every index consumes input
    const std::int64_t index = readIndex(in, p, src, e, row, vertexCount);
    if (index < 0) {
      j = 0;
      continue;
    }
    const auto c = static_cast<std::uint32_t>(index);
    if (j >= 2 && a != b && b != c && a != c) {
      if (j % 2 == 0)
        indices.insert(indices.end(), {a, b, c});
      else
        indices.insert(indices.end(), {b, a, c});
    }
    a = b;
    b = c;
    ++j;
  }
}

template <class Reader>
MeshData readBody(const Header& h, Reader& in, const std::string& src, std::uint64_t vertexCount,
                  bool hasNormals, bool hasUvs, const MeshPlacement& placement) {
  MeshData mesh;
  for (const Element& e : h.elements) {
    if (e.properties.empty() || e.count == 0) continue;
    // Bounds the reservations and loops below by the file size.
    const std::size_t minRow = Reader::minRowBytes(e);
    if (e.count > in.bytesLeft() / minRow)
      failAt(src, e.line,
             "element '" + e.name + "' declares " + std::to_string(e.count) +
                 " rows but the file has only " + std::to_string(in.bytesLeft()) +
                 " bytes left (truncated file?)");
    const bool isVertex = e.name == "vertex";
    if (isVertex) {
      mesh.positions.reserve(e.count);
      if (hasNormals) mesh.normals.reserve(e.count);
      if (hasUvs) mesh.uvs.reserve(e.count);
    } else if (e.name == "face") {
      mesh.indices.reserve(3 * e.count);
    }
    for (std::uint64_t row = 0; row < e.count; ++row) {
      if (!in.beginRow()) rowFail(src, in.line(), e, row, "file ends before this row");
      double v[8] = {};  // x y z (placed in double), nx ny nz, u v
      for (const Property& p : e.properties) {
        std::int64_t n = 0;  // list length
        double d = 0.0;      // scalar value
        if (p.isList && (!in.integer(p.countType, n) || n < 0)) {
          rowFail(src, in.line(), e, row, "missing or malformed list count for '" + p.name + "'");
        } else if (p.isList && p.slot == kIndicesSlot) {
          readFace(in, p, n, src, e, row, vertexCount, mesh.indices);
        } else if (p.isList && p.slot == kStripSlot) {
          readStrip(in, p, n, src, e, row, vertexCount, mesh.indices);
        } else if (p.isList ? !in.skipList(p.type, static_cast<std::uint64_t>(n))
                            : !in.number(p.type, d)) {
          rowFail(src, in.line(), e, row, "missing or malformed value for '" + p.name + "'");
        } else if (!p.isList && p.slot >= 0) {
          if (!std::isfinite(d) ||
              std::fabs(d) > static_cast<double>(std::numeric_limits<float>::max()))
            rowFail(src, in.line(), e, row, "'" + p.name + "' is not a finite float");
          v[p.slot] = d;
        }
      }
      if (!in.endRow()) rowFail(src, in.line(), e, row, "too many values on the line");
      if (isVertex) {
        glm::vec3 placed;
        if (!placement.place({v[0], v[1], v[2]}, placed))
          rowFail(src, in.line(), e, row,
                  "vertex leaves the single-precision range once scaled and translated");
        mesh.positions.push_back(placed);
        if (hasNormals) mesh.normals.emplace_back(glm::dvec3(v[3], v[4], v[5]));
        if (hasUvs) mesh.uvs.emplace_back(glm::dvec2(v[6], v[7]));
      }
    }
  }
  if (in.moreRows()) failAt(src, in.line(), "unexpected data after the last PLY element");
  return mesh;
}

}  // namespace ply_detail

MeshData parsePly(std::string_view bytes, const std::string& sourceName,
                  const MeshPlacement& placement) {
  using namespace ply_detail;
  Header header = parseHeader(bytes, sourceName);
  bool hasNormals = false, hasUvs = false;
  const std::uint64_t vertexCount = assignSlots(header, sourceName, hasNormals, hasUvs);
  const std::string_view body = bytes.substr(header.bodyOffset);
  MeshData mesh;
  if (header.format == Format::kAscii) {
    AsciiReader reader(body, header.lines);
    mesh = readBody(header, reader, sourceName, vertexCount, hasNormals, hasUvs, placement);
  } else {
    BinaryReader reader(body, header.format == Format::kBinaryBig);
    mesh = readBody(header, reader, sourceName, vertexCount, hasNormals, hasUvs, placement);
  }
  if (mesh.indices.empty())
    failAt(sourceName, 0, "PLY file has no triangles (no faces, or only degenerate strips)");
  return mesh;
}

MeshData readPly(const std::filesystem::path& path, const MeshPlacement& placement) {
  const std::string bytes = readInputFile(path, "mesh file");
  return parsePly(bytes, path.string(), placement);
}

}  // namespace camsim
