// Tests for integrator/geometry/obj_reader.cpp (through mesh_io.h): OBJ parsing, fan
// triangulation, normals, texture coordinates, and the InputError (with line numbers)
// raised for malformed files.
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

namespace camsim {
namespace {

using Indices = std::vector<std::uint32_t>;
using test::expectError;
using test::expectObjError;

// ---- OBJ -------------------------------------------------------------------------------

TEST(ObjTest, QuadIsFanTriangulated) {
  const MeshData m = parseObj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", "test");
  ASSERT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.positions[2], glm::vec3(1, 1, 0));
  EXPECT_EQ(m.indices, (Indices{0, 1, 2, 0, 2, 3}));
  EXPECT_TRUE(m.normals.empty());
}

TEST(ObjTest, AcceptsAllFaceVertexForms) {
  const MeshData m = parseObj(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
      "f 1 2 3\nf 1/1 2/2 3/3\nf 1//1 2//1 3//1\nf 1/1/1 2/2/1 3/3/1\n",
      "test");
  EXPECT_EQ(m.indices, (Indices{0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2}));
  EXPECT_TRUE(m.normals.empty());  // the first faces have no normals
}

TEST(ObjTest, NegativeIndicesAreRelative) {
  const MeshData m =
      parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 5 5 5\nf -4/1 -1 -2\n", "test");
  EXPECT_EQ(m.indices, (Indices{0, 1, 2, 0, 3, 2}));
}

TEST(ObjTest, ConsistentNormalsArePerPosition) {
  const MeshData m = parseObj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 9 9 9\nvn 0 0 1\nvn 0 1 0\nvn 0 0 1\n"
      "f 1//1 2//2 3//1\nf 1//3 3//1 4//2\n",
      "test");  // vn 3 equals vn 1, so position 1 stays consistent
  ASSERT_EQ(m.normals.size(), 5u);
  EXPECT_EQ(m.normals[0], glm::vec3(0, 0, 1));
  EXPECT_EQ(m.normals[1], glm::vec3(0, 1, 0));
  EXPECT_EQ(m.normals[2], glm::vec3(0, 0, 1));
  EXPECT_EQ(m.normals[3], glm::vec3(0, 1, 0));
  EXPECT_EQ(m.normals[4], glm::vec3(0, 0, 0));  // unused position
}

TEST(ObjTest, InconsistentNormalsAreDropped) {
  const MeshData m = parseObj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvn 0 1 0\n"
      "f 1//1 2//1 3//1\nf 1//2 3//1 4//1\n",
      "test");
  EXPECT_EQ(m.indices.size(), 6u);
  EXPECT_TRUE(m.normals.empty());
}

TEST(ObjTest, CornerWithoutNormalDropsNormals) {
  const MeshData m = parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3\n", "test");
  EXPECT_TRUE(m.normals.empty());
}

TEST(ObjTest, IgnoresOtherStatementsCommentsAndCrlf) {
  const MeshData m = parseObj(
      "# comment\r\nmtllib a.mtl\r\no thing\r\ng group\r\ns 1\r\nusemtl red\r\n"
      "v 0 0 0 1\r\n  v\t+1.5 -0 0 0.5 0.5 0.5\r\nv 0 1e2 0\r\nvt 0 0\r\nl 1 2\r\np 1\r\n\r\n"
      "f 1 2 3 # trailing comment\r\n",
      "test");
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_EQ(m.positions[1], glm::vec3(1.5f, 0, 0));
  EXPECT_EQ(m.positions[2], glm::vec3(0, 100, 0));
  EXPECT_EQ(m.indices, (Indices{0, 1, 2}));
}

TEST(ObjTest, MalformedInputReportsLine) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";  // lines 1-3
  expectObjError(tri + "f 0 1 2\n", 4, "index 0");
  expectObjError(tri + "f 1 2 4\n", 4, "out of range");
  expectObjError(tri + "f -4 -2 -1\n", 4, "out of range");
  expectObjError(tri + "f 1 2\n", 4, "at least 3");
  expectObjError(tri + "f 1 2 3\nf 1\n", 5, "at least 3");
  expectObjError("v 0 0 0\nv nan 0 0\n", 2, "not a finite");
  expectObjError("v 0 0 0\nv 0 inf 0\n", 2, "not a finite");
  expectObjError("v 0 0 1e39\n", 1, "not a finite");
  expectObjError("v 1 2\n", 1, "needs 3 coordinates");
  expectObjError("\n\nv 1 x 2\n", 3, "'x' is not a number");
  expectObjError("v 1 2.5.3 2\n", 1, "not a number");
  expectObjError(tri + "vn 0 0 1\nf 1/1/1/1 2 3\n", 5, "bad face vertex");
  expectObjError(tri + "f 1// 2// 3//\n", 4, "bad face vertex");
  expectObjError(tri + "f 1/ 2/ 3/\n", 4, "bad face vertex");
  expectObjError(tri + "f a b c\n", 4, "bad face vertex");
  expectObjError(tri + "f 1 2 3x\n", 4, "bad face vertex");
  expectObjError(tri + "f 1 2 99999999999999999999999\n", 4, "bad face vertex");
  expectObjError(tri + "vn 0 0 1\nf 1//1 2//2 3//1\n", 5, "normal index 2 out of range");
  expectObjError(tri + "vn 0 0 1\nf 1//0 2//1 3//1\n", 5, "normal index 0");
  expectObjError("f 1 2 3\n" + tri, 1, "out of range");  // forward reference
  expectObjError(tri + "vn 0 nan 1\n", 4, "not a finite");
}

TEST(ObjTest, ErrorHasColumn) {
  try {
    parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2  7\n", "test");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 4);
    EXPECT_EQ(e.where().column, 8);
  }
}

TEST(ObjTest, NoTrianglesIsAnError) {
  expectObjError("", 0, "no faces");
  expectObjError("v 0 0 0\nv 1 0 0\nv 0 1 0\n# f 1 2 3\n", 0, "no faces");
}

TEST(ObjTest, TextureCoordinatesPerPosition) {
  const MeshData m = parseObj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0 0.5\nvt 1 1\nvt 0.25\n"
      "f 1/1 2/2 3/3 4/-1\n",
      "test");  // vt 0.25: v = 0; w ignored
  ASSERT_EQ(m.uvs.size(), 4u);
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.uvs[1], glm::vec2(1, 0));
  EXPECT_EQ(m.uvs[2], glm::vec2(1, 1));
  EXPECT_EQ(m.uvs[3], glm::vec2(0.25f, 0));
  EXPECT_EQ(m.indices, (Indices{0, 1, 2, 0, 2, 3}));
}

// A position used with two different uvs becomes two vertices (the second appended, with
// a copy of the position and of its normal); an equal uv under another vt index does not.
TEST(ObjTest, TextureSeamSplitsVertices) {
  const MeshData m = parseObj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\nvt 1 1\n"
      "f 1/1/1 2/2/1 3/3/1\nf 1/5/1 3/6/1 4/4/1\nf 1/5/1 4/4/1 2/2/1\n",
      "test");
  ASSERT_EQ(m.positions.size(), 5u);
  ASSERT_EQ(m.uvs.size(), 5u);
  ASSERT_EQ(m.normals.size(), 5u);
  EXPECT_EQ(m.indices, (Indices{0, 1, 2, 4, 2, 3, 4, 3, 1}));
  EXPECT_EQ(m.positions[4], m.positions[0]);
  EXPECT_EQ(m.normals[4], glm::vec3(0, 0, 1));
  EXPECT_EQ(m.uvs[0], glm::vec2(0, 0));
  EXPECT_EQ(m.uvs[4], glm::vec2(0.5f, 0.5f));
  EXPECT_EQ(m.uvs[2], glm::vec2(1, 1));
}

TEST(ObjTest, CornerWithoutTextureCoordinateDropsUvs) {
  const MeshData m = parseObj(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
      "f 1/1 2/2 3/3\nf 2 4 3\n",
      "test");
  EXPECT_TRUE(m.uvs.empty());
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_TRUE(parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1 2 3\n", "test").uvs.empty());
}

TEST(ObjTest, MalformedTextureCoordinates) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expectObjError(tri + "vt\n", 4, "at least 1 value");
  expectObjError(tri + "vt 0 x\n", 4, "not a number");
  expectObjError(tri + "vt 0 inf\n", 4, "not a finite");
  expectObjError(tri + "vt 0 0\nf 1/1 2/ 3/1\n", 5, "bad face vertex");
  // A vt index naming no texture coordinate only drops the uvs (such files loaded before).
  EXPECT_TRUE(parseObj(tri + "vt 0 0\nf 1/1 2/2 3/1\n", "test").uvs.empty());
  EXPECT_TRUE(parseObj(tri + "vt 0 0\nf 1/0 2/1 3/1\n", "test").uvs.empty());
  EXPECT_EQ(parseObj(tri + "vt 0 0\nf 1/1 2/1 3/-1\n", "test").uvs.size(), 3u);
}

}  // namespace
}  // namespace camsim
