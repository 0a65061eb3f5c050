// Stanford PLY reader (accepted subset: see mesh_io.h). The header is parsed into element and
// property descriptions; the body is then read by one generic loop over an ASCII or a binary
// value reader. Every element count from the header is capped and checked against the bytes
// left before anything is reserved, so a hostile file fails with InputError instead of
// allocating or looping without bound. ASCII bodies hold one element row per line (blank
// lines are skipped) and must not have data after the last row; trailing bytes after a
// binary body are ignored.
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "integrator/geometry/mesh_io.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace mesh_io_detail {
std::string readWholeFile(const std::filesystem::path& path);  // mesh_io.cpp
}

namespace {

constexpr std::uint64_t kMaxElementCount = 100'000'000;
constexpr int kIndicesSlot = 8;  // vertex slots 0..7 are x y z nx ny nz u v

enum class Type : std::uint8_t { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat, kDouble };
enum class Format : std::uint8_t { kAscii, kBinaryLittle, kBinaryBig };

struct Property {
  std::string name;
  Type type = Type::kFloat;  // scalar type, or the item type of a list
  bool isList = false;
  Type countType = Type::kUint8;
  int slot = -1;  // where the value goes (see kIndicesSlot); -1 = skipped
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  int line = 0;  // header line declaring it
  std::vector<Property> properties;
};

struct Header {
  Format format = Format::kAscii;
  std::vector<Element> elements;
  std::size_t bodyOffset = 0;
  int lines = 0;
};

struct TypeInfo {
  std::string_view name, alias;
  std::size_t size;
  std::int64_t min, max;  // integer types only
};
// Indexed by Type.
constexpr TypeInfo kTypes[] = {{"char", "int8", 1, INT8_MIN, INT8_MAX},
                               {"uchar", "uint8", 1, 0, UINT8_MAX},
                               {"short", "int16", 2, INT16_MIN, INT16_MAX},
                               {"ushort", "uint16", 2, 0, UINT16_MAX},
                               {"int", "int32", 4, INT32_MIN, INT32_MAX},
                               {"uint", "uint32", 4, 0, UINT32_MAX},
                               {"float", "float32", 4, 0, 0},
                               {"double", "float64", 8, 0, 0}};

const TypeInfo& info(Type t) {
  return kTypes[static_cast<std::size_t>(t)];
}
bool isInteger(Type t) {
  return t != Type::kFloat && t != Type::kDouble;
}

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
  const Element* face = nullptr;
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
      face = &e;
      for (Property& p : e.properties) {
        if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
        if (!p.isList || !isInteger(p.type))
          failAt(src, e.line, "face property '" + p.name + "' must be a list of integers");
        p.slot = kIndicesSlot;
        break;
      }
      if (std::none_of(e.properties.begin(), e.properties.end(),
                       [](const Property& p) { return p.slot == kIndicesSlot; }))
        failAt(src, e.line, "face element has no 'vertex_indices' list property");
    }
  }
  if (vertex == nullptr) failAt(src, h.lines, "PLY file has no 'vertex' element");
  if (face == nullptr) failAt(src, h.lines, "PLY file has no 'face' element (no triangles)");
  return vertex->count;
}

[[noreturn]] void rowFail(const std::string& src, int line, const Element& e, std::uint64_t row,
                          const std::string& message) {
  failAt(src, line, "element '" + e.name + "' index " + std::to_string(row) + ": " + message);
}

// Reader interface used by readBody: beginRow/endRow delimit a row, number/integer/skip/
// skipList consume values (false = missing, malformed or out of range for the type),
// line() is the current line (0 for binary), moreRows() reports leftover data.
class BinaryReader {
 public:
  BinaryReader(std::string_view body, bool bigEndian)
      : p_(body.data()),
        end_(body.data() + body.size()),
        swap_(bigEndian != (std::endian::native == std::endian::big)) {}

  bool beginRow() { return true; }
  bool endRow() { return true; }
  bool moreRows() { return false; }  // trailing bytes are ignored
  int line() const { return 0; }
  std::size_t bytesLeft() const { return static_cast<std::size_t>(end_ - p_); }
  static std::size_t minRowBytes(const Element& e) {
    std::size_t n = 0;
    for (const Property& p : e.properties) n += info(p.isList ? p.countType : p.type).size;
    return n;
  }

  bool number(Type t, double& out) { return read(t, out); }
  bool integer(Type t, std::int64_t& out) { return isInteger(t) && read(t, out); }
  bool skip(Type t) { return skipList(t, 1); }
  bool skipList(Type t, std::uint64_t n) {
    if (n > bytesLeft() / info(t).size) return false;
    p_ += n * info(t).size;
    return true;
  }

 private:
  template <class Out>
  bool read(Type t, Out& out) {
    // clang-format off
    switch (t) {
      case Type::kInt8: return load<std::int8_t>(out);
      case Type::kUint8: return load<std::uint8_t>(out);
      case Type::kInt16: return load<std::int16_t>(out);
      case Type::kUint16: return load<std::uint16_t>(out);
      case Type::kInt32: return load<std::int32_t>(out);
      case Type::kUint32: return load<std::uint32_t>(out);
      case Type::kFloat: return load<float>(out);
      case Type::kDouble: return load<double>(out);
    }
    // clang-format on
    return false;
  }

  template <class T, class Out>
  bool load(Out& out) {
    if (bytesLeft() < sizeof(T)) return false;
    unsigned char buf[sizeof(T)];
    std::memcpy(buf, p_, sizeof(T));
    if (swap_) std::reverse(buf, buf + sizeof(T));
    T v;
    std::memcpy(&v, buf, sizeof(T));
    p_ += sizeof(T);
    out = static_cast<Out>(v);
    return true;
  }

  const char* p_;
  const char* end_;
  bool swap_;
};

// One element row per line; blank lines are skipped.
class AsciiReader {
 public:
  AsciiReader(std::string_view body, int headerLines)
      : next_(body.data()), end_(body.data() + body.size()), line_(headerLines) {}

  bool beginRow() {  // moves to the next non-blank line
    while (next_ < end_) {
      const void* nl = std::memchr(next_, '\n', static_cast<std::size_t>(end_ - next_));
      cur_ = next_;
      lineEnd_ = nl != nullptr ? static_cast<const char*>(nl) : end_;
      next_ = nl != nullptr ? lineEnd_ + 1 : end_;
      if (line_ < std::numeric_limits<int>::max()) ++line_;
      skipSpace();
      if (cur_ != lineEnd_) return true;
    }
    return false;
  }
  bool endRow() {
    skipSpace();
    return cur_ == lineEnd_;
  }
  bool moreRows() { return beginRow(); }
  int line() const { return line_; }
  std::size_t bytesLeft() const { return static_cast<std::size_t>(end_ - next_) + 1; }
  // Each value takes at least one character and one separator.
  static std::size_t minRowBytes(const Element& e) { return 2 * e.properties.size(); }

  bool number(Type t, double& out) {
    if (isInteger(t)) {
      std::int64_t i = 0;
      const bool ok = integer(t, i);
      out = static_cast<double>(i);
      return ok;
    }
    const std::string_view tok = token();
    const char* first = tok.data();
    const char* last = first + tok.size();
    if (last - first > 1 && *first == '+' && first[1] != '-') ++first;
    auto [ptr, ec] = std::from_chars(first, last, out);
    if (ec == std::errc::result_out_of_range) {  // rare: let strtod decide (inf or tiny)
      out = std::strtod(std::string(first, last).c_str(), nullptr);
      ec = std::errc();
    }
    return !tok.empty() && ec == std::errc() && ptr == last;
  }
  bool integer(Type t, std::int64_t& out) {
    const std::string_view tok = token();
    auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
    if (tok.empty() || ec != std::errc() || ptr != tok.data() + tok.size()) return false;
    return isInteger(t) && out >= info(t).min && out <= info(t).max;
  }
  bool skip(Type t) {
    double d = 0.0;
    return number(t, d);
  }
  bool skipList(Type t, std::uint64_t n) {
    for (std::uint64_t i = 0; i < n; ++i)  // bounded: each value consumes a token of the line
      if (!skip(t)) return false;
    return true;
  }

 private:
  static bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
  }
  void skipSpace() {
    while (cur_ < lineEnd_ && isSpace(*cur_)) ++cur_;
  }
  std::string_view token() {
    skipSpace();
    const char* start = cur_;
    while (cur_ < lineEnd_ && !isSpace(*cur_)) ++cur_;
    return {start, static_cast<std::size_t>(cur_ - start)};
  }

  const char* next_;
  const char* end_;
  const char* cur_ = nullptr;
  const char* lineEnd_ = nullptr;
  int line_;
};

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
        } else if (p.isList && p.slot == kIndicesSlot) {  // fan-triangulate the polygon
          if (n < 3)
            rowFail(src, in.line(), e, row,
                    "face has " + std::to_string(n) + " vertices (at least 3 needed)");
          std::uint32_t first = 0;
          std::uint32_t prev = 0;
          for (std::int64_t k = 0; k < n; ++k) {  // bounded: every index consumes input
            std::int64_t index = 0;
            if (!in.integer(p.type, index))
              rowFail(src, in.line(), e, row, "missing or malformed vertex index");
            if (index < 0 || static_cast<std::uint64_t>(index) >= vertexCount)
              rowFail(src, in.line(), e, row,
                      "vertex index " + std::to_string(index) + " out of range (" +
                          std::to_string(vertexCount) + " vertices)");
            const auto u = static_cast<std::uint32_t>(index);
            if (k == 0) first = u;
            if (k >= 2) mesh.indices.insert(mesh.indices.end(), {first, prev, u});
            prev = u;
          }
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

}  // namespace

MeshData parsePly(std::string_view bytes, const std::string& sourceName,
                  const MeshPlacement& placement) {
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
  if (mesh.indices.empty()) failAt(sourceName, 0, "PLY file has no faces (no triangles)");
  return mesh;
}

MeshData readPly(const std::filesystem::path& path, const MeshPlacement& placement) {
  const std::string bytes = mesh_io_detail::readWholeFile(path);
  return parsePly(bytes, path.string(), placement);
}

}  // namespace camsim
