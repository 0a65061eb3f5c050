// Tests for integrator/geometry/ply_reader.cpp and mesh_io.cpp: PLY parsing (ASCII and
// binary, both endiannesses), readMeshFile, and the InputError (with line numbers) raised
// for malformed or mutated files. Binary PLY fixtures are written byte by byte here.
#include "integrator/geometry/mesh_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "sensor/base/input_error.h"
#include "tests/integrator/geometry/mesh_test_support.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

using Indices = std::vector<std::uint32_t>;
using test::expectError;
using test::expectPlyError;

// ---- PLY -------------------------------------------------------------------------------

// A 5-vertex mesh: a quad (0 1 2 3) and a triangle (1 4 2).
const float kXyz[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0.5f, -1}};
const std::vector<std::vector<int>> kFaces = {{0, 1, 2, 3}, {1, 4, 2}};
const Indices kTriangles = {0, 1, 2, 0, 2, 3, 1, 4, 2};

std::string asciiPly() {
  std::string s =
      "ply\nformat ascii 1.0\ncomment made by a test\nelement vertex 5\nproperty float x\n"
      "property float y\nproperty float z\nelement face 2\n"
      "property list uchar int vertex_indices\nend_header\n";  // 10 header lines
  s += "0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0.5 -1\n4 0 1 2 3\n3 1 4 2\n";
  return s;
}

class BinaryWriter {
 public:
  explicit BinaryWriter(bool bigEndian)
      : swap_(bigEndian != (std::endian::native == std::endian::big)) {}
  template <class T>
  void put(T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (swap_) std::reverse(b, b + sizeof(T));
    for (unsigned char c : b) bytes.push_back(static_cast<char>(c));
  }
  std::string bytes;

 private:
  bool swap_;
};

struct BinaryOptions {
  bool bigEndian = false;
  bool doubles = false;
  bool intCounts = false;  // list count type int instead of uchar
  bool extras = false;     // unused properties and elements to be skipped
};

std::string binaryPly(const BinaryOptions& o) {
  std::string h = "ply\nformat ";
  h += o.bigEndian ? "binary_big_endian" : "binary_little_endian";
  h += " 1.0\nelement vertex 5\n";
  const std::string coord = o.doubles ? "double" : "float";
  if (o.extras) h += "property uchar red\n";
  h += "property " + coord + " x\nproperty " + coord + " y\nproperty " + coord + " z\n";
  if (o.extras) h += "property list uchar float weights\n";
  if (o.extras) h += "element edge 1\nproperty int v1\nproperty int v2\n";
  h += "element face 2\n";
  if (o.extras) h += "property short flags\n";
  h += std::string("property list ") + (o.intCounts ? "int" : "uchar") + " uint vertex_indices\n";
  h += "end_header\n";
  BinaryWriter w(o.bigEndian);
  for (const auto& v : kXyz) {
    if (o.extras) w.put<std::uint8_t>(200);
    for (float c : v) o.doubles ? w.put(static_cast<double>(c)) : w.put(c);
    if (o.extras) {
      w.put<std::uint8_t>(2);
      w.put(1.5f);
      w.put(2.5f);
    }
  }
  if (o.extras) {
    w.put<std::int32_t>(0);
    w.put<std::int32_t>(1);
  }
  for (const auto& f : kFaces) {
    if (o.extras) w.put<std::int16_t>(-7);
    o.intCounts ? w.put(static_cast<std::int32_t>(f.size()))
                : w.put(static_cast<std::uint8_t>(f.size()));
    for (int i : f) w.put(static_cast<std::uint32_t>(i));
  }
  return h + w.bytes;
}

void expectReferenceMesh(const MeshData& m) {
  ASSERT_EQ(m.positions.size(), 5u);
  for (int i = 0; i < 5; ++i)
    EXPECT_EQ(m.positions[i], glm::vec3(kXyz[i][0], kXyz[i][1], kXyz[i][2])) << i;
  EXPECT_EQ(m.indices, kTriangles);
  EXPECT_TRUE(m.normals.empty());
}

TEST(PlyTest, AsciiAndBinaryEndiannessesGiveSameMesh) {
  expectReferenceMesh(parsePly(asciiPly(), "test"));
  expectReferenceMesh(parsePly(binaryPly({.bigEndian = false}), "test"));
  expectReferenceMesh(parsePly(binaryPly({.bigEndian = true}), "test"));
}

TEST(PlyTest, UcharAndIntListCountTypes) {
  for (bool big : {false, true}) {
    expectReferenceMesh(parsePly(binaryPly({.bigEndian = big, .intCounts = false}), "test"));
    expectReferenceMesh(parsePly(binaryPly({.bigEndian = big, .intCounts = true}), "test"));
  }
  std::string ascii = asciiPly();
  ascii.replace(ascii.find("list uchar int"), 14, "list int uint");
  expectReferenceMesh(parsePly(ascii, "test"));
}

TEST(PlyTest, FloatAndDoubleCoordinates) {
  for (bool big : {false, true}) {
    expectReferenceMesh(parsePly(binaryPly({.bigEndian = big, .doubles = false}), "test"));
    expectReferenceMesh(parsePly(binaryPly({.bigEndian = big, .doubles = true}), "test"));
  }
  std::string ascii = asciiPly();
  ascii.replace(ascii.find("float x"), 5, "double");
  expectReferenceMesh(parsePly(ascii, "test"));
}

TEST(PlyTest, SkipsOtherElementsAndProperties) {
  expectReferenceMesh(parsePly(binaryPly({.extras = true}), "test"));
  expectReferenceMesh(
      parsePly(binaryPly({.bigEndian = true, .doubles = true, .extras = true}), "test"));
}

TEST(PlyTest, ReadsNormalsCrlfAndVertexIndexName) {
  const MeshData m = parsePly(
      "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float x\r\nproperty float y\r\n"
      "property float z\r\nproperty float nx\r\nproperty float ny\r\nproperty float nz\r\n"
      "property uchar red\r\nelement face 1\r\nproperty list uchar uint vertex_index\r\n"
      "end_header\r\n0 0 0 0 0 1 255\r\n1 0 0 0 0 1 0\r\n\r\n0 1 0 0 1 0 7\r\n3 2 1 0\r\n",
      "test");
  ASSERT_EQ(m.normals.size(), 3u);
  EXPECT_EQ(m.normals[2], glm::vec3(0, 1, 0));
  EXPECT_EQ(m.indices, (Indices{2, 1, 0}));
}

// Texture coordinates under each accepted pair of names, as float or double.
TEST(PlyTest, ReadsTextureCoordinates) {
  for (const auto& [u, v] : {std::pair{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}}) {
    SCOPED_TRACE(u);
    const std::string ply = std::string(
                                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                "property float y\nproperty float z\nproperty float ") +
                            u + "\nproperty double " + v +
                            "\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                            "0 0 0 0 0\n1 0 0 0.5 0\n0 1 0 0.25 1\n3 0 1 2\n";
    const MeshData m = parsePly(ply, "test");
    ASSERT_EQ(m.uvs.size(), 3u);
    EXPECT_EQ(m.uvs[1], glm::vec2(0.5f, 0));
    EXPECT_EQ(m.uvs[2], glm::vec2(0.25f, 1));
  }
  EXPECT_TRUE(parsePly(asciiPly(), "test").uvs.empty());
  BinaryWriter w(true);
  for (float f : {0.f, 0.f, 0.f, 0.1f, 0.2f, 1.f, 0.f, 0.f, 0.3f, 0.4f, 0.f, 1.f, 0.f, 0.5f, 0.6f})
    w.put(f);
  for (std::uint8_t b : {std::uint8_t{3}, std::uint8_t{0}, std::uint8_t{1}, std::uint8_t{2}})
    w.put(b);
  const MeshData b = parsePly(
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nproperty float s\nproperty float t\n"
      "element face 1\nproperty list uchar uchar vertex_indices\nend_header\n" +
          w.bytes,
      "test");
  ASSERT_EQ(b.uvs.size(), 3u);
  EXPECT_EQ(b.uvs[2], glm::vec2(0.5f, 0.6f));
  expectPlyError(
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float u\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n",
      3, "only one texture coordinate");
}

TEST(PlyTest, MalformedHeader) {
  auto withHeaderLine = [&](const std::string& from, const std::string& to) {
    std::string s = asciiPly();
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  expectPlyError("plx\nformat ascii 1.0\nend_header\n", 1, "not a PLY file");
  expectPlyError("", 1, "not a PLY file");
  expectPlyError(withHeaderLine("format ascii 1.0", "format binary_middle_endian 1.0"), 2,
                 "unknown PLY format");
  expectPlyError(withHeaderLine("format ascii 1.0", "format ascii 2.0"), 2, "version");
  expectPlyError(withHeaderLine("format ascii 1.0\n", ""), 9, "no 'format'");
  expectPlyError(withHeaderLine("end_header\n", ""), 10, "unknown PLY header line '0 0 0'");
  expectPlyError(asciiPly().substr(0, asciiPly().find("end_header")), 9, "no 'end_header'");
  expectPlyError(withHeaderLine("property float y", "property half y"), 6, "expected 'property");
  expectPlyError(withHeaderLine("comment", "bogus"), 3, "unknown PLY header line");
  expectPlyError("ply\nformat ascii 1.0\nproperty float x\nend_header\n", 3, "before any element");
  expectPlyError(withHeaderLine("vertex 5", "vertex -5"), 4, "bad element count");
  expectPlyError(withHeaderLine("face 2", "face 100000001"), 8, "exceeds the limit");
  expectPlyError(withHeaderLine("property float z\n", ""), 4, "x, y, z");
  expectPlyError(withHeaderLine("vertex_indices", "indices"), 8, "no 'vertex_indices'");
  expectPlyError(withHeaderLine("list uchar int", "list float int"), 9, "count type");
  expectPlyError(withHeaderLine("list uchar int", "list uchar float"), 8, "list of integers");
  expectPlyError(withHeaderLine("element face 2\nproperty list uchar int vertex_indices\n", ""), 8,
                 "no 'face' or 'tristrips' element");
}

TEST(PlyTest, MalformedAsciiBody) {
  const std::string s = asciiPly();
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = s;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  expectPlyError(replaced("3 1 4 2", "3 1 5 2"), 17, "index 5 out of range");
  expectPlyError(replaced("3 1 4 2", "3 1 -1 2"), 17, "out of range");
  expectPlyError(replaced("3 1 4 2", "2 1 4"), 17, "at least 3");
  expectPlyError(replaced("3 1 4 2", "3 1 4"), 17, "vertex index");
  expectPlyError(replaced("3 1 4 2", "3 1 4 2 0"), 17, "too many values");
  expectPlyError(replaced("3 1 4 2", "256 1 4 2"), 17, "list count");
  expectPlyError(replaced("1 1 0\n", "1 nan 0\n"), 13, "not a finite");
  expectPlyError(replaced("1 1 0\n", "1 1e300 0\n"), 13, "not a finite");
  expectPlyError(replaced("1 1 0\n", "1 one 0\n"), 13, "malformed value for 'y'");
  expectPlyError(replaced("3 1 4 2\n", ""), 16, "file ends");
  expectPlyError(s + "0 0 0\n", 18, "after the last");
  expectPlyError(replaced("vertex 5", "vertex 5000"), 4, "declares 5000 rows");
  std::string noFaces = replaced("face 2", "face 0");
  noFaces.erase(noFaces.find("4 0 1 2 3"));
  expectPlyError(noFaces, 0, "no triangles");
}

TEST(PlyTest, MalformedBinaryBody) {
  for (bool big : {false, true}) {
    SCOPED_TRACE(big);
    const std::string good = binaryPly({.bigEndian = big});
    // Truncated inside the second face (3 indices of 4 bytes + count = 13 bytes).
    expectPlyError(good.substr(0, good.size() - 5), 0, "'face' index 1");
    // Every strict prefix fails cleanly.
    for (std::size_t n = 0; n < good.size(); ++n)
      EXPECT_THROW(parsePly(good.substr(0, n), "test"), InputError) << n;

    std::string badIndex = good;
    BinaryWriter w(big);
    w.put<std::uint32_t>(5);
    badIndex.replace(badIndex.size() - 8, 4, w.bytes);  // face 1, second index
    expectPlyError(badIndex, 0, "'face' index 1: vertex index 5 out of range");

    std::string nan = good;
    BinaryWriter n(big);
    n.put(std::numeric_limits<float>::quiet_NaN());
    nan.replace(nan.find("end_header\n") + 11 + 4 * 4, 4, n.bytes);  // vertex 1, y
    expectPlyError(nan, 0, "'vertex' index 1: 'y' is not a finite");

    std::string huge = good;
    huge.replace(huge.find("vertex 5"), 8, "vertex 99999999");
    expectPlyError(huge, 3, "declares 99999999 rows");
    std::string hugeFace = good;
    hugeFace.replace(hugeFace.find("face 2"), 6, "face 100000000");
    expectPlyError(hugeFace, 7, "declares 100000000 rows");
  }
}

TEST(PlyTest, HugeListCountFailsWithoutAllocating) {
  BinaryOptions o;
  o.intCounts = true;
  std::string s = binaryPly(o);
  BinaryWriter w(false);
  w.put<std::int32_t>(2000000000);
  s.replace(s.size() - 16, 4, w.bytes);  // count of face 1
  expectPlyError(s, 0, "'face' index 1");
}

// ---- readMeshFile and robustness --------------------------------------------------------

TEST(MeshFileTest, ReadsByExtension) {
  const test::TempDir temp;
  const std::filesystem::path& dir = temp.path();
  std::ofstream(dir / "a.OBJ") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir / "b.ply", std::ios::binary) << binaryPly({.bigEndian = true});
  std::ofstream(dir / "c.stl") << "solid";
  std::ofstream(dir / "d.obj") << "v 0 0 0\nf 1 1 2\n";
  EXPECT_EQ(readMeshFile(dir / "a.OBJ").indices, (Indices{0, 1, 2}));
  expectReferenceMesh(readMeshFile(dir / "b.ply"));
  EXPECT_THROW(readMeshFile(dir / "c.stl"), InputError);
  EXPECT_THROW(readMeshFile(dir / "missing.obj"), InputError);
  EXPECT_THROW(readMeshFile(dir), InputError);
  try {
    readObj(dir / "d.obj");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, (dir / "d.obj").string());
    EXPECT_EQ(e.where().line, 2);
  }
}

// A tiny deterministic mutation fuzzer: results must be a mesh or an InputError.
TEST(MeshFuzzTest, MutatedInputsFailCleanly) {
  const std::vector<std::string> seeds = {
      asciiPly(), binaryPly({.extras = true}), binaryPly({.bigEndian = true, .intCounts = true}),
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf -1/2/1 -2 -3\n"};
  std::uint64_t state = 12345;
  auto next = [&] {
    return (state = state * 6364136223846793005ull + 1442695040888963407ull) >> 33;
  };
  const char kAlphabet[] = "0123456789 -+./\n#enfvx\xff";
  for (const std::string& seed : seeds) {
    for (int iteration = 0; iteration < 3000; ++iteration) {
      std::string s = seed;
      const int edits = 1 + static_cast<int>(next() % 4);
      for (int k = 0; k < edits && !s.empty(); ++k) {
        const std::size_t at = next() % s.size();
        const auto c = kAlphabet[next() % (sizeof(kAlphabet) - 1)];
        switch (next() % 3) {
          case 0:
            s[at] = next() % 2 ? c : static_cast<char>(next());
            break;
          case 1:
            s.erase(at, 1 + next() % 8);
            break;
          default:
            s.insert(at, 1, c);
            break;
        }
      }
      for (auto* parse : {&parseObj, &parsePly}) {
        try {
          const MeshData m = parse(s, "fuzz", MeshPlacement{});
          ASSERT_FALSE(m.indices.empty());
          ASSERT_EQ(m.indices.size() % 3, 0u);
          for (std::uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
          ASSERT_TRUE(m.normals.empty() || m.normals.size() == m.positions.size());
        } catch (const InputError&) {
        }
      }
    }
  }
}

}  // namespace
}  // namespace camsim
