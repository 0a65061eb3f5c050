// Wavefront OBJ reader (accepted subset: see mesh_io.h). One pass over the text held in
// memory: lines and tokens are views into it and numbers go through std::from_chars, so the
// hot loop allocates nothing apart from growing the output vectors.
//
// Indices must refer to vertices/normals defined earlier in the file (positive = absolute,
// negative = relative to the current end); forward references are rejected.
//
// Normals: OBJ attaches `vn` indices to face corners, MeshData holds one normal per
// position. Normals are kept only if every face corner references a normal and each
// position is always paired with the same normal (same index or an identical vector);
// otherwise MeshData::normals is left empty and the caller computes geometric normals.
// Positions used by no face get a zero normal.
//
// Texture coordinates: likewise attached to face corners. They are kept only if every face
// corner references a defined `vt`; a position used with several distinct uvs is then split: the
// first uv stays with the original vertex, every further (position, uv) pair gets a new
// vertex (a copy of the position and its normal) appended after the file's positions.
// Positions used by no face get uv (0, 0).
//
// Materials: `mtllib` lines are recorded as written and `usemtl` starts a new triangle group
// (MeshData::materialGroups, in triangle order; groups left empty are dropped). The .mtl
// files are not read here: the scene loader reads them only when the shape has no material
// of its own (integrator/scene/scene_loader_mtl.cpp).
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "integrator/geometry/mesh_io.h"
#include "sensor/base/input_error.h"
#include "sensor/base/input_file.h"

namespace camsim {

namespace {

constexpr std::size_t kMaxCount = 100'000'000;
constexpr std::uint32_t kNoNormal = std::numeric_limits<std::uint32_t>::max();
constexpr std::uint32_t kNoUv = kNoNormal;

// Parses a real number token starting at p (which must not be whitespace). Returns the end
// of the token, or nullptr if it is not a number. Over/underflow: strtod semantics (an
// overflow gives inf, which the caller rejects; an underflow gives 0 or a denormal).
const char* parseReal(const char* p, const char* end, double& out) {
  if (p < end && *p == '+') {
    ++p;
    if (p < end && *p == '-') return nullptr;
  }
  auto [ptr, ec] = std::from_chars(p, end, out);
  if (ec == std::errc::result_out_of_range) {
    const std::string copy(p, static_cast<std::size_t>(ptr - p));  // rare: re-parse with strtod
    out = std::strtod(copy.c_str(), nullptr);
  } else if (ec != std::errc()) {
    return nullptr;
  }
  if (ptr < end && !isObjSpace(*ptr)) return nullptr;
  return ptr;
}

class ObjParser {
 public:
  ObjParser(std::string_view text, const std::string& source, const MeshPlacement& placement)
      : text_(text), source_(source), placement_(placement) {}
  MeshData run();

 private:
  void parseLine(const char* p, const char* end);
  std::string restOfLine(const char* p, const char* end) const;
  void startGroup(std::string name);
  glm::dvec3 parseVec3(const char* p, const char* end, const char* what);
  glm::vec2 parseUv(const char* p, const char* end);
  double parseCoord(const char*& p, const char* end, const char* what);
  void splitByUv(MeshData& mesh) const;
  void parseFace(const char* p, const char* end);
  const char* parseIndex(const char* p, const char* end, const char* tokenStart, std::int64_t& out);
  std::uint32_t resolve(std::int64_t index, std::size_t count, const char* what, const char* at);
  void trackNormal(std::uint32_t position, std::uint32_t normal, bool hasNormal);
  [[noreturn]] void fail(const char* at, const std::string& message) const;
  std::string tokenAt(const char* p, const char* end) const;

  std::string_view text_;
  const std::string& source_;
  const MeshPlacement& placement_;
  std::int64_t line_ = 0;
  const char* lineStart_ = nullptr;
  const char* lineEnd_ = nullptr;
  std::vector<glm::vec3> positions_;
  std::vector<glm::vec3> normals_;
  std::vector<std::uint32_t> indices_;
  std::vector<std::uint32_t> normalOf_;  // per position: the vn index used with it
  bool normalsUsable_ = true;
  std::vector<glm::vec2> texcoords_;
  std::vector<std::uint32_t> cornerUv_;  // per entry of indices_: its vt index
  bool uvsUsable_ = true;
  std::vector<MeshMaterialGroup> groups_;  // firstTriangle set; counts filled in by run()
  std::vector<MeshMaterialLibrary> libraries_;
};

void ObjParser::fail(const char* at, const std::string& message) const {
  const int line = static_cast<int>(std::min<std::int64_t>(line_, std::numeric_limits<int>::max()));
  int column = 0;
  if (at != nullptr && at >= lineStart_ && at - lineStart_ < std::numeric_limits<int>::max())
    column = static_cast<int>(at - lineStart_) + 1;
  throw InputError({source_, line, column}, "", message);
}

std::string ObjParser::tokenAt(const char* p, const char* end) const {
  const char* q = p;
  while (q < end && !isObjSpace(*q) && q - p < 40) ++q;
  return std::string(p, static_cast<std::size_t>(q - p));
}

MeshData ObjParser::run() {
  const char* p = text_.data();
  const char* const end = p + text_.size();
  while (p < end) {
    ++line_;
    const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(end - p));
    const char* eol = nl != nullptr ? static_cast<const char*>(nl) : end;
    lineStart_ = p;
    lineEnd_ = eol;
    parseLine(p, eol);
    p = eol == end ? end : eol + 1;
  }
  if (indices_.empty())
    throw InputError({source_, 0, 0}, "", "OBJ file has no faces (no triangles)");

  MeshData mesh;
  const auto triangles = static_cast<std::uint32_t>(indices_.size() / 3);
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    MeshMaterialGroup& group = groups_[g];
    const std::uint32_t next = g + 1 < groups_.size() ? groups_[g + 1].firstTriangle : triangles;
    group.triangleCount = next - group.firstTriangle;
    if (group.triangleCount > 0) mesh.materialGroups.push_back(std::move(group));
  }
  mesh.materialLibraries = std::move(libraries_);
  mesh.positions = std::move(positions_);
  mesh.indices = std::move(indices_);
  if (normalsUsable_ && !normals_.empty()) {
    mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
    for (std::size_t i = 0; i < normalOf_.size(); ++i)
      if (normalOf_[i] != kNoNormal) mesh.normals[i] = normals_[normalOf_[i]];
  }
  if (uvsUsable_ && cornerUv_.size() == mesh.indices.size()) splitByUv(mesh);
  return mesh;
}

void ObjParser::splitByUv(MeshData& mesh) const {
  const std::size_t original = mesh.positions.size();
  std::vector<std::uint32_t> uvOf(original, kNoUv);        // vt index kept by the original vertex
  std::unordered_map<std::uint64_t, std::uint32_t> extra;  // (position, vt) → new vertex
  std::vector<glm::vec2> extraUvs;
  for (std::size_t k = 0; k < mesh.indices.size(); ++k) {
    const std::uint32_t pos = mesh.indices[k], vt = cornerUv_[k];
    std::uint32_t& kept = uvOf[pos];
    if (kept == kNoUv) kept = vt;
    if (kept == vt || texcoords_[kept] == texcoords_[vt]) continue;
    const std::uint64_t key = (std::uint64_t{pos} << 32) | vt;
    auto [it, inserted] = extra.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
    if (inserted) {  // at most 4·10⁸ vertices in all (kMaxCount): fits in uint32
      mesh.positions.push_back(mesh.positions[pos]);
      if (!mesh.normals.empty()) mesh.normals.push_back(mesh.normals[pos]);
      extraUvs.push_back(texcoords_[vt]);
    }
    mesh.indices[k] = it->second;
  }
  mesh.uvs.assign(original, glm::vec2(0.0f));
  for (std::size_t i = 0; i < original; ++i)
    if (uvOf[i] != kNoUv) mesh.uvs[i] = texcoords_[uvOf[i]];
  mesh.uvs.insert(mesh.uvs.end(), extraUvs.begin(), extraUvs.end());
}

void ObjParser::parseLine(const char* p, const char* end) {
  while (p < end && isObjSpace(*p)) ++p;
  const char* keyword = p;
  while (p < end && !isObjSpace(*p)) ++p;
  const std::string_view kw(keyword, static_cast<std::size_t>(p - keyword));
  if (kw == "v") {
    if (positions_.size() >= kMaxCount) fail(keyword, "more than 100000000 vertices");
    glm::vec3 placed;
    if (!placement_.place(parseVec3(p, end, "vertex"), placed))
      fail(keyword, "vertex leaves the single-precision range once scaled and translated");
    positions_.push_back(placed);
  } else if (kw == "vn") {
    if (normals_.size() >= kMaxCount) fail(keyword, "more than 100000000 normals");
    normals_.push_back(glm::vec3(parseVec3(p, end, "normal")));
  } else if (kw == "vt") {
    if (texcoords_.size() >= kMaxCount) fail(keyword, "more than 100000000 texture coordinates");
    texcoords_.push_back(parseUv(p, end));
  } else if (kw == "f") {
    parseFace(p, end);
  } else if (kw == "usemtl") {
    startGroup(restOfLine(p, end));
  } else if (kw == "mtllib") {
    std::string files = restOfLine(p, end);
    if (files.empty()) fail(keyword, "mtllib needs a file name");
    libraries_.push_back({std::move(files), static_cast<int>(std::min<std::int64_t>(
                                                line_, std::numeric_limits<int>::max()))});
  }
  // Everything else (vp, o, g, s, l, p, comments, ...) is ignored.
}

// The text after the keyword without surrounding white space (names and file names may
// contain spaces; a '#' is part of them).
std::string ObjParser::restOfLine(const char* p, const char* end) const {
  while (p < end && isObjSpace(*p)) ++p;
  while (end > p && isObjSpace(end[-1])) --end;
  return std::string(p, static_cast<std::size_t>(end - p));
}

// `usemtl NAME`: the triangles from here on use NAME. The first one also opens a group ""
// for the triangles before it.
void ObjParser::startGroup(std::string name) {
  const auto first = static_cast<std::uint32_t>(indices_.size() / 3);
  if (groups_.empty() && first > 0) groups_.push_back({"", 0, 0, 0});
  if (groups_.size() >= kMaxCount) fail(lineStart_, "more than 100000000 usemtl statements");
  if (!groups_.empty() && groups_.back().firstTriangle == first) groups_.pop_back();  // empty
  const int line = static_cast<int>(std::min<std::int64_t>(line_, std::numeric_limits<int>::max()));
  groups_.push_back({std::move(name), first, 0, line});
}

// One coordinate at p (after spaces), finite in float; advances p past it.
double ObjParser::parseCoord(const char*& p, const char* end, const char* what) {
  double d = 0.0;
  const char* next = parseReal(p, end, d);
  if (next == nullptr) fail(p, "'" + tokenAt(p, end) + "' is not a number");
  if (!std::isfinite(d) || std::fabs(d) > static_cast<double>(std::numeric_limits<float>::max()))
    fail(p, std::string(what) + " coordinate '" + tokenAt(p, end) + "' is not a finite float");
  p = next;
  return d;
}

// Reads three coordinates; further tokens (w, vertex colours) are ignored.
glm::dvec3 ObjParser::parseVec3(const char* p, const char* end, const char* what) {
  double xyz[3] = {};
  for (double& c : xyz) {
    while (p < end && isObjSpace(*p)) ++p;
    if (p == end || *p == '#') fail(p, std::string(what) + " needs 3 coordinates");
    c = parseCoord(p, end, what);
  }
  return {xyz[0], xyz[1], xyz[2]};
}

// `vt u [v [w]]`: v defaults to 0, w is ignored.
glm::vec2 ObjParser::parseUv(const char* p, const char* end) {
  float uv[2] = {};
  for (int i = 0; i < 2; ++i) {
    while (p < end && isObjSpace(*p)) ++p;
    if (p == end || *p == '#') {
      if (i == 0) fail(p, "texture coordinate needs at least 1 value");
      break;
    }
    uv[i] = static_cast<float>(parseCoord(p, end, "texture"));
  }
  return {uv[0], uv[1]};
}

const char* ObjParser::parseIndex(const char* p, const char* end, const char* tokenStart,
                                  std::int64_t& out) {
  auto [ptr, ec] = std::from_chars(p, end, out);
  if (ec != std::errc())
    fail(tokenStart,
         "bad face vertex '" + tokenAt(tokenStart, end) + "' (expected i, i/t, i//n or i/t/n)");
  return ptr;
}

std::uint32_t ObjParser::resolve(std::int64_t index, std::size_t count, const char* what,
                                 const char* at) {
  if (index == 0) fail(at, std::string(what) + " index 0 is invalid (OBJ indices start at 1)");
  const std::int64_t n = static_cast<std::int64_t>(count);
  const std::int64_t absolute = index > 0 ? index - 1 : n + index;
  if (absolute < 0 || absolute >= n)
    fail(at, std::string(what) + " index " + std::to_string(index) + " out of range (" +
                 std::to_string(count) + " defined so far)");
  return static_cast<std::uint32_t>(absolute);
}

void ObjParser::parseFace(const char* p, const char* end) {
  std::int64_t corners = 0;
  std::uint32_t first = 0, firstUv = kNoUv;
  std::uint32_t prev = 0, prevUv = kNoUv;
  while (true) {
    while (p < end && isObjSpace(*p)) ++p;
    if (p == end || *p == '#') break;
    const char* tokenStart = p;
    std::int64_t raw = 0;
    p = parseIndex(p, end, tokenStart, raw);
    const std::uint32_t pos = resolve(raw, positions_.size(), "vertex", tokenStart);
    std::uint32_t normal = 0;
    bool hasNormal = false;
    std::uint32_t uv = kNoUv;
    if (p < end && *p == '/') {
      ++p;
      // Texcoord index (required after one '/'; "i/" fails here). One that names no `vt`
      // (0 or out of range) only drops the uvs: such files loaded when vt was ignored.
      if (p == end || *p != '/') {
        p = parseIndex(p, end, tokenStart, raw);
        const std::int64_t n = static_cast<std::int64_t>(texcoords_.size());
        const std::int64_t absolute = raw > 0 ? raw - 1 : n + raw;
        if (raw != 0 && absolute >= 0 && absolute < n) uv = static_cast<std::uint32_t>(absolute);
      }
      if (p < end && *p == '/') {
        p = parseIndex(p + 1, end, tokenStart, raw);
        normal = resolve(raw, normals_.size(), "normal", tokenStart);
        hasNormal = true;
      }
    }
    if (p < end && !isObjSpace(*p))
      fail(tokenStart,
           "bad face vertex '" + tokenAt(tokenStart, end) + "' (expected i, i/t, i//n or i/t/n)");
    trackNormal(pos, normal, hasNormal);
    if (uv == kNoUv && uvsUsable_) {
      uvsUsable_ = false;
      cornerUv_ = {};
    }
    if (corners == 0) {
      first = pos;
      firstUv = uv;
    } else if (corners >= 2) {
      if (indices_.size() >= 3 * kMaxCount) fail(tokenStart, "more than 100000000 triangles");
      indices_.push_back(first);
      indices_.push_back(prev);
      indices_.push_back(pos);
      if (uvsUsable_) cornerUv_.insert(cornerUv_.end(), {firstUv, prevUv, uv});
    }
    prev = pos;
    prevUv = uv;
    ++corners;
  }
  if (corners < 3)
    fail(nullptr, "face has " + std::to_string(corners) + " vertices (at least 3 needed)");
}

void ObjParser::trackNormal(std::uint32_t position, std::uint32_t normal, bool hasNormal) {
  if (!normalsUsable_) return;
  if (!hasNormal) {
    normalsUsable_ = false;
    normalOf_.clear();
    return;
  }
  if (normalOf_.size() < positions_.size()) normalOf_.resize(positions_.size(), kNoNormal);
  std::uint32_t& slot = normalOf_[position];
  if (slot == kNoNormal) {
    slot = normal;
  } else if (slot != normal && normals_[slot] != normals_[normal]) {
    normalsUsable_ = false;
    normalOf_.clear();
  }
}

}  // namespace

MeshData parseObj(std::string_view text, const std::string& sourceName,
                  const MeshPlacement& placement) {
  return ObjParser(text, sourceName, placement).run();
}

MeshData readObj(const std::filesystem::path& path, const MeshPlacement& placement) {
  const std::string text = readInputFile(path, "mesh file");
  return parseObj(text, path.string(), placement);
}

}  // namespace camsim
