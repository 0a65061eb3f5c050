// Tests for integrator/geometry/mtl_reader.cpp (.mtl parsing: every field, the ignored
// statements with their lines and reasons, the InputError lines) and for the OBJ reader's
// material groups (usemtl/mtllib in integrator/geometry/obj_reader.cpp).
#include "integrator/geometry/mtl_reader.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "integrator/geometry/mesh_io.h"
#include "sensor/base/input_error.h"
#include "tests/integrator/geometry/mesh_test_support.h"

namespace camsim {
namespace {

using test::expectError;

void expectMtlError(const std::string& text, int line, const std::string& what) {
  SCOPED_TRACE(text);
  expectError([&] { parseMtl(text, "test"); }, line, what);
}

TEST(MtlReaderTest, ReadsEveryField) {
  const MtlLibrary lib = parseMtl(
      "# a comment\n"
      "newmtl Body Paint\n"  // 2: names may hold spaces
      "  Kd 0.8 0.1 0.05 # red\n"
      "Ks 0.5\n"  // 4: one value = grey
      "Ns 250\n"
      "Ni 1.45\n"
      "d 0.75\n"
      "illum 2\n"
      "MAP_KD -o 0.5 0.25 -s 2 4 1 -clamp on -bm 0.3 tex/my texture.png\n"  // 9
      "newmtl glass\n"
      "Tr 0.9\n",
      "test");
  ASSERT_EQ(lib.materials.size(), 2u);
  const MtlMaterial& m = lib.materials[0];
  EXPECT_EQ(m.name, "Body Paint");
  EXPECT_EQ(m.line, 2);
  ASSERT_TRUE(m.kd && m.ks && m.ns && m.ni && m.dissolve && m.illum && m.mapKd);
  EXPECT_EQ(m.kd->value, glm::dvec3(0.8, 0.1, 0.05));
  EXPECT_EQ(m.kd->line, 3);
  EXPECT_EQ(m.ks->value, glm::dvec3(0.5));
  EXPECT_EQ(m.ns->value, 250.0);
  EXPECT_EQ(m.ni->value, 1.45);
  EXPECT_EQ(m.dissolve->value, 0.75);
  EXPECT_EQ(m.illum->value, 2);
  EXPECT_EQ(m.mapKd->file, "tex/my texture.png");
  EXPECT_EQ(m.mapKd->scale, glm::dvec2(2, 4));
  EXPECT_EQ(m.mapKd->offset, glm::dvec2(0.5, 0.25));
  EXPECT_EQ(m.mapKd->line, 9);
  ASSERT_EQ(m.ignored.size(), 2u);  // the map options -clamp and -bm
  EXPECT_EQ(m.ignored[0].key, "MAP_KD -clamp");
  EXPECT_EQ(m.ignored[1].key, "MAP_KD -bm");
  EXPECT_EQ(m.ignored[1].line, 9);
  ASSERT_TRUE(lib.materials[1].dissolve);
  EXPECT_NEAR(lib.materials[1].dissolve->value, 0.1, 1e-15);  // d = 1 − Tr
}

TEST(MtlReaderTest, KeepsIgnoredStatementsWithLinesAndReasons) {
  const MtlLibrary lib = parseMtl(
      "Kd 1 1 1\n"  // before any newmtl
      "newmtl a\n"
      "Ka 0.1 0.1 0.1\n"
      "map_Bump -bm 2 normal.png\n"
      "Pr 0.4\n"
      "Kd spectral paint.rfl\n"
      "frobnicate 3\n",
      "test");
  ASSERT_EQ(lib.ignored.size(), 1u);
  EXPECT_EQ(lib.ignored[0].key, "Kd");
  EXPECT_EQ(lib.ignored[0].reason, "it comes before the first newmtl");
  const std::vector<MtlIgnored>& i = lib.materials[0].ignored;
  ASSERT_EQ(i.size(), 5u);
  EXPECT_EQ(i[0].key, "Ka");
  EXPECT_EQ(i[0].line, 3);
  EXPECT_EQ(i[0].reason, "camsim has no ambient term");
  EXPECT_EQ(i[1].key, "map_Bump");
  EXPECT_EQ(i[1].reason, "camsim has no bump maps");
  EXPECT_NE(i[2].reason.find("PBR"), std::string::npos);
  EXPECT_EQ(i[3].key, "Kd spectral");
  EXPECT_EQ(i[4].key, "frobnicate");
  EXPECT_EQ(i[4].line, 7);
  EXPECT_FALSE(lib.materials[0].kd);  // the spectral form is not read
}

TEST(MtlReaderTest, MalformedStatementsFailAtTheirLine) {
  expectMtlError("newmtl a\nKd 0.5 x 1\n", 2, "'x' is not a number (Kd)");
  expectMtlError("newmtl a\nKd 0.5 0.5\n", 2, "1 (grey) or 3 values");
  expectMtlError("newmtl a\nKd 1 1 1 1\n", 2, "more are given");
  expectMtlError("newmtl a\nKd -0.1 0 0\n", 2, "out of range");
  expectMtlError("newmtl a\nNs\n", 2, "Ns needs 1 value");
  expectMtlError("newmtl a\n\nNi 0\n", 3, "out of range (0.001 to 1000)");
  expectMtlError("newmtl a\nd 1.5\n", 2, "out of range (0 to 1)");
  expectMtlError("newmtl a\nillum 2.5\n", 2, "integer from 0 to 10");
  expectMtlError("newmtl a\nillum 11\n", 2, "out of range");
  expectMtlError("newmtl a\nmap_Kd\n", 2, "needs a file name");
  expectMtlError("newmtl a\nmap_Kd -s 2 t.png\n", 2, "-s needs u v [w]");
  expectMtlError("newmtl\n", 1, "newmtl needs a material name");
  expectMtlError("newmtl a\nnewmtl b\nnewmtl a\n", 3, "defined twice (first on line 1)");
}

TEST(ObjMaterialGroupsTest, UsemtlSplitsTheTrianglesInOrder) {
  const MeshData m = parseObj(
      "mtllib a b.mtl\n"
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "f 1 2 3\n"            // 6: before any usemtl
      "usemtl red\n"         // 7
      "usemtl  Blue Sky \n"  // 8: the empty red group is dropped
      "f 1 2 3 4\n"
      "usemtl red\n"  // 10
      "f 1 3 4\n"
      "usemtl red\n",  // 12: no triangles follow
      "test");
  ASSERT_EQ(m.materialLibraries.size(), 1u);
  EXPECT_EQ(m.materialLibraries[0].files, "a b.mtl");
  EXPECT_EQ(m.materialLibraries[0].line, 1);
  ASSERT_EQ(m.materialGroups.size(), 3u);
  EXPECT_EQ(m.materialGroups[0].name, "");
  EXPECT_EQ(m.materialGroups[0].firstTriangle, 0u);
  EXPECT_EQ(m.materialGroups[0].triangleCount, 1u);
  EXPECT_EQ(m.materialGroups[1].name, "Blue Sky");
  EXPECT_EQ(m.materialGroups[1].firstTriangle, 1u);
  EXPECT_EQ(m.materialGroups[1].triangleCount, 2u);
  EXPECT_EQ(m.materialGroups[1].line, 8);
  EXPECT_EQ(m.materialGroups[2].name, "red");
  EXPECT_EQ(m.materialGroups[2].firstTriangle, 3u);
  EXPECT_EQ(m.materialGroups[2].triangleCount, 1u);
  EXPECT_EQ(m.materialGroups[2].line, 10);

  const MeshData plain = parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "test");
  EXPECT_TRUE(plain.materialGroups.empty());
  EXPECT_TRUE(plain.materialLibraries.empty());
  test::expectObjError("mtllib\nv 0 0 0\n", 1, "mtllib needs a file name");
}

}  // namespace
}  // namespace camsim
