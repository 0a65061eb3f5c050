// Tests for the `tristrips` element of integrator/geometry/ply_reader.cpp (mesh_io.h): a
// grid written as strips (with −1 restarts and a degenerate swap) reads as the same
// triangles, in the same orientation, as the grid written as faces, in ASCII and in both
// binary byte orders; the alternation, the restarts and the dropped degenerate triangles on a
// hand-worked strip; a file with faces and strips; the errors (file, line or element index).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "integrator/geometry/mesh_io.h"
#include "sensor/base/input_error.h"
#include "tests/integrator/geometry/mesh_test_support.h"

namespace camsim {
namespace {

using Indices = std::vector<std::uint32_t>;
using test::expectPlyError;

// A 4 × 3 grid of vertices in z = 0 (vertex r·4 + c at (c, r)): 3 × 2 quads.
constexpr int kCols = 4, kRows = 3;

// The grid's quads as faces, each split into two counter-clockwise triangles seen from +z.
std::vector<std::array<int, 3>> gridFaces() {
  std::vector<std::array<int, 3>> f;
  for (int r = 0; r + 1 < kRows; ++r)
    for (int c = 0; c + 1 < kCols; ++c) {
      const int a = r * kCols + c, b = a + 1, d = a + kCols, e = d + 1;
      f.push_back({a, b, e});
      f.push_back({a, e, d});
    }
  return f;
}

// The same grid as strips in one list: row 0 as one run, −1, row 1 as a second run; each
// run zig-zags between the row above (even positions) and the row itself.
std::vector<int> gridStrip() {
  std::vector<int> s;
  for (int c = 0; c < kCols; ++c) s.insert(s.end(), {kCols + c, c});  // row 0: 4 0 5 1 6 2 7 3
  s.push_back(-1);
  for (int c = 0; c < kCols; ++c) s.insert(s.end(), {2 * kCols + c, kCols + c});  // row 1
  return s;
}

std::string header(const std::string& format, int faces, int strips, const std::string& index) {
  std::string h = "ply\nformat " + format + " 1.0\ncomment grid\nelement vertex " +
                  std::to_string(kCols * kRows) +
                  "\nproperty float x\nproperty float y\nproperty float z\n";
  if (faces > 0)
    h += "element face " + std::to_string(faces) + "\nproperty list uchar int vertex_indices\n";
  if (strips > 0)
    h += "element tristrips " + std::to_string(strips) + "\nproperty list int " + index +
         " vertex_indices\n";
  return h + "end_header\n";
}

std::string asciiGrid(bool asStrips) {
  const std::vector<std::array<int, 3>> faces = gridFaces();
  std::string s =
      header("ascii", asStrips ? 0 : static_cast<int>(faces.size()), asStrips ? 1 : 0, "int");
  for (int v = 0; v < kCols * kRows; ++v)
    s += std::to_string(v % kCols) + " " + std::to_string(v / kCols) + " 0\n";
  if (asStrips) {
    const std::vector<int> strip = gridStrip();
    s += std::to_string(strip.size());
    for (int i : strip) s += " " + std::to_string(i);
    s += "\n";
  } else {
    for (const auto& f : faces)
      s += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) +
           "\n";
  }
  return s;
}

template <class T>
void put(std::string& out, T v, bool bigEndian) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (bigEndian != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
  out.append(reinterpret_cast<const char*>(b), sizeof(T));
}

// The strips in binary; `uintRestart`: a uint index list whose restart is 4294967295.
std::string binaryGridStrips(bool bigEndian, bool uintRestart) {
  std::string s = header(bigEndian ? "binary_big_endian" : "binary_little_endian", 0, 1,
                         uintRestart ? "uint" : "int");
  for (int v = 0; v < kCols * kRows; ++v) {
    put<float>(s, static_cast<float>(v % kCols), bigEndian);
    put<float>(s, static_cast<float>(v / kCols), bigEndian);
    put<float>(s, 0.0f, bigEndian);
  }
  const std::vector<int> strip = gridStrip();
  put<std::int32_t>(s, static_cast<std::int32_t>(strip.size()), bigEndian);
  for (int i : strip) {
    if (uintRestart)
      put<std::uint32_t>(s, i < 0 ? UINT32_MAX : static_cast<std::uint32_t>(i), bigEndian);
    else
      put<std::int32_t>(s, i, bigEndian);
  }
  return s;
}

// Triangles with their cyclic order kept (smallest index first), so that an orientation flip
// changes the triangle.
std::vector<std::array<std::uint32_t, 3>> canonical(const Indices& idx) {
  std::vector<std::array<std::uint32_t, 3>> t;
  for (std::size_t k = 0; k + 2 < idx.size(); k += 3) {
    std::array<std::uint32_t, 3> tri = {idx[k], idx[k + 1], idx[k + 2]};
    std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
    t.push_back(tri);
  }
  std::sort(t.begin(), t.end());
  return t;
}

TEST(PlyTristripsTest, StripsEqualTheSameMeshAsFaces) {
  const MeshData faces = parsePly(asciiGrid(false), "test");
  ASSERT_EQ(faces.indices.size(), 3u * 12u);
  const std::vector<std::string> files = {asciiGrid(true), binaryGridStrips(false, false),
                                          binaryGridStrips(true, false),
                                          binaryGridStrips(false, true)};
  for (const std::string& file : files) {
    SCOPED_TRACE(file.substr(0, file.find("end_header")));
    const MeshData strips = parsePly(file, "test");
    EXPECT_EQ(strips.positions, faces.positions);
    EXPECT_EQ(strips.indices.size(), faces.indices.size());  // 12 triangles, none degenerate
    EXPECT_EQ(canonical(strips.indices), canonical(faces.indices));
    // Every triangle faces +z, as the strip's first one (a wrong alternation flips half).
    for (std::size_t k = 0; k < strips.indices.size(); k += 3) {
      const glm::vec3 a = strips.positions[strips.indices[k]],
                      b = strips.positions[strips.indices[k + 1]],
                      c = strips.positions[strips.indices[k + 2]];
      EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << "triangle " << k / 3;
    }
  }
}

// By hand: 4 0 5 1 gives (4 0 5) at run position 2 (even) and (5 0 1) at 3 (odd); −1
// restarts; 0 1 1 5 2 gives (0 1 1) and (1 1 5), both dropped, then (1 5 2) at position 4.
TEST(PlyTristripsTest, AlternatesRestartsAndDropsDegenerateTriangles) {
  std::string s = header("ascii", 0, 2, "int");
  for (int v = 0; v < kCols * kRows; ++v)
    s += std::to_string(v % kCols) + " " + std::to_string(v / kCols) + " 0\n";
  s += "10 4 0 5 1 -1 0 1 1 5 2\n";
  s += "2 3 7\n";  // a run too short for a triangle: nothing
  const MeshData m = parsePly(s, "test");
  EXPECT_EQ(m.indices, (Indices{4, 0, 5, 5, 0, 1, 1, 5, 2}));
}

TEST(PlyTristripsTest, FacesAndStripsTogetherFollowTheElementOrder) {
  std::string s = header("ascii", 1, 1, "int");
  for (int v = 0; v < kCols * kRows; ++v)
    s += std::to_string(v % kCols) + " " + std::to_string(v / kCols) + " 0\n";
  s += "3 0 1 5\n5 1 2 6 3 7\n";
  const MeshData m = parsePly(s, "test");
  EXPECT_EQ(m.indices, (Indices{0, 1, 5, 1, 2, 6, 6, 2, 3, 6, 3, 7}));
}

TEST(PlyTristripsTest, ErrorsNameTheFileAndTheLineOrElement) {
  const std::string good = asciiGrid(true);  // 10 header lines, 12 vertices, the strip on 23
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = good;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  expectPlyError(replaced(" -1 8", " -2 8"), 23, "'tristrips' index 0: vertex index -2");
  expectPlyError(replaced(" -1 8", " 12 8"), 23, "out of range (12 vertices; −1 restarts");
  expectPlyError(replaced("17 4 0", "18 4 0"), 23, "missing or malformed vertex index");
  expectPlyError(replaced("list int int vertex_indices", "list int float vertex_indices"), 8,
                 "tristrips property 'vertex_indices' must be a list of integers");
  expectPlyError(replaced("vertex_indices", "indices"), 8,
                 "tristrips element has no 'vertex_indices'");
  expectPlyError(replaced("17 4 0 5 1 6 2 7 3 -1 8 4 9 5 10 6 11 7", "5 0 1 1 2 2"), 0,
                 "no triangles");  // only degenerate triangles
  const std::string binary = binaryGridStrips(false, false);
  expectPlyError(binary.substr(0, binary.size() - 2), 0, "'tristrips' index 0");
  std::string outOfRange = binary;
  outOfRange.replace(outOfRange.size() - 4, 4, std::string("\x0c\0\0\0", 4));  // last: 12
  expectPlyError(outOfRange, 0, "'tristrips' index 0: vertex index 12 out of range");
}

}  // namespace
}  // namespace camsim
