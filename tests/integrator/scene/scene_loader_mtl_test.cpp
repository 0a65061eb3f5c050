// Tests for integrator/scene/scene_loader_mtl.cpp: an OBJ mesh shape without `material:`
// takes its .mtl materials (tests/data/obj_mtl: one quad per mapping of docs/scene-format.md
// "Materials of OBJ files") — Kd → the uplifted reflectance, Ks/Ns → plastic, Ni with d < 1
// or illum 4 → dielectric, map_Kd → the image texture with its -s/-o — and is split into one
// shape per material; the ignored statements become notes naming the .mtl, line and key; a
// given `material:` overrides the file's (no .mtl read); the errors name the .obj or .mtl
// line (missing .mtl, unknown usemtl, missing map_Kd, name clash, triangles without material).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "integrator/scene/scene_loader.h"
#include "integrator/textures/image_texture.h"
#include "sensor/base/input_error.h"
#include "sensor/spectra/color_space.h"
#include "sensor/spectra/rgb_uplift.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;
using test::TempDir;
using test::writeFile;
using Type = MaterialDescription::Type;

const fs::path kData = fs::path(CAMSIM_TEST_DATA_DIR) / "obj_mtl";

// Line 4 is the shape; `materials` (line 2) may hold the scene's own.
std::string mtlScene(const std::string& shape, const std::string& materials = "{}") {
  return "camera: {position: [0, 0, 5], look_at: [0, 0, 0]}\n"  // 1
         "materials: " +
         materials +
         "\n"  // 2
         "shapes:\n  - " +
         shape + "\n";  // 4
}

SceneDescription loadMtl(const std::string& text, const fs::path& dir = kData) {
  return loadSceneFromText(text, "mtl.yaml", dir);
}

const MaterialDescription& material(const SceneDescription& d, const std::string& name) {
  const auto it = std::find_if(d.materials.begin(), d.materials.end(),
                               [&](const MaterialDescription& m) { return m.name == name; });
  if (it == d.materials.end()) throw std::runtime_error("no material " + name);
  return *it;
}

bool hasNote(const SceneDescription& d, const std::string& text) {
  return std::any_of(d.notes.begin(), d.notes.end(),
                     [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

TEST(SceneLoaderMtlTest, MapsTheDocumentedFields) {
  const SceneDescription d = loadMtl(mtlScene("{type: mesh, file: quads.obj, name: quads}"));
  ASSERT_EQ(d.materials.size(), 5u);  // in first-use order; `unused` is not imported
  const std::vector<std::string> names = {"quads.obj:red", "quads.obj:shiny", "quads.obj:glass",
                                          "quads.obj:textured", "quads.obj:water"};
  for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(d.materials[i].name, names[i]);

  // Kd 0.8 0.1 0.1 → the same uplift as {rgb: [0.8, 0.1, 0.1]}, whose colour is Kd.
  const MaterialDescription& red = material(d, "quads.obj:red");
  EXPECT_EQ(red.type, Type::kDiffuse);  // illum 1, Ks 0
  EXPECT_EQ(red.reflectance.kind, TextureDescription::Kind::kConstant);
  const Spectrum expected = rgbToReflectance({0.8, 0.1, 0.1}, RgbColorSpace::linearRec709());
  for (int i = 0; i < 471; i += 10) EXPECT_EQ(red.reflectance.value.sample(i), expected.sample(i));
  const glm::dvec3 rgb = reflectanceToRgb(red.reflectance.value, RgbColorSpace::linearRec709());
  EXPECT_NEAR(rgb.r, 0.8, 1e-3);
  EXPECT_NEAR(rgb.g, 0.1, 1e-3);
  EXPECT_NEAR(rgb.b, 0.1, 1e-3);

  // Ks 0.2, Ns 98 → plastic ks = 0.2, Beckmann α = √(2/100).
  const MaterialDescription& shiny = material(d, "quads.obj:shiny");
  EXPECT_EQ(shiny.type, Type::kPlastic);
  EXPECT_FLOAT_EQ(shiny.specularWeight, 0.2f);
  EXPECT_NEAR(shiny.roughness.value.sample(200), std::sqrt(0.02), 1e-7);
  EXPECT_EQ(shiny.distribution, MicrofacetDistribution::kBeckmann);
  EXPECT_NEAR(reflectanceToRgb(shiny.reflectance.value, RgbColorSpace::linearRec709()).g, 0.5,
              1e-3);

  // Ni 1.33 with d 0.4, and Ni 1.33 with illum 4 → dielectric η = 1.33.
  for (const char* glass : {"quads.obj:glass", "quads.obj:water"}) {
    const MaterialDescription& g = material(d, glass);
    EXPECT_EQ(g.type, Type::kDielectric) << glass;
    EXPECT_FLOAT_EQ(g.eta.sample(0), 1.33f) << glass;
    EXPECT_FLOAT_EQ(g.eta.sample(470), 1.33f) << glass;
  }

  // map_Kd -s 2 3 -o 0.5 0.25 checker.png → that image, relative to the .mtl.
  const TextureDescription& tex = material(d, "quads.obj:textured").reflectance;
  EXPECT_EQ(tex.kind, TextureDescription::Kind::kImage);
  EXPECT_EQ(tex.file, kData / "checker.png");
  EXPECT_EQ(tex.encoding, TextureEncoding::kSrgb);
  EXPECT_EQ(tex.uvScale, glm::vec2(2, 3));
  EXPECT_EQ(tex.uvOffset, glm::vec2(0.5f, 0.25f));
  ASSERT_TRUE(tex.image);
  EXPECT_EQ(tex.image->width, 2);

  const std::vector<fs::path> files = {kData / "quads.obj", kData / "quads.mtl",
                                       kData / "checker.png"};
  EXPECT_EQ(d.inputFiles, files);
}

TEST(SceneLoaderMtlTest, SplitsTheMeshIntoOneShapePerMaterial) {
  const SceneDescription d =
      loadMtl(mtlScene("{type: mesh, file: quads.obj, name: quads, class: 3}"));
  ASSERT_EQ(d.shapes.size(), 5u);
  const std::vector<std::string> labels = {"quads/red", "quads/shiny", "quads/glass",
                                           "quads/textured", "quads/water"};
  for (std::size_t i = 0; i < d.shapes.size(); ++i) {
    const ShapeDescription& s = d.shapes[i];
    EXPECT_EQ(s.label, labels[i]);
    EXPECT_EQ(s.material, static_cast<int>(i));
    EXPECT_EQ(s.className, "3");
    const std::size_t quads = i == 0 ? 2 : 1;  // red: the first and the last quad
    EXPECT_EQ(s.mesh.indices.size(), 6 * quads) << s.label;
    EXPECT_EQ(s.mesh.positions.size(), 4 * quads) << s.label;  // only the vertices it uses
    EXPECT_EQ(s.mesh.uvs.size(), s.mesh.positions.size());
    EXPECT_TRUE(s.mesh.materialGroups.empty());
  }
  // The last quad (x from 10 to 11) is red's second.
  EXPECT_EQ(d.shapes[0].mesh.positions[4].x, 10.0f);
}

TEST(SceneLoaderMtlTest, IgnoredStatementsBecomeNotesNamingFileLineAndKey) {
  const SceneDescription d = loadMtl(mtlScene("{type: mesh, file: quads.obj}"));
  const std::string mtl = (kData / "quads.mtl").string();
  for (const std::string& n : d.notes) EXPECT_EQ(n.rfind(mtl + " line ", 0), 0u) << n;
  EXPECT_TRUE(hasNote(d, mtl + " line 4: 'Ka' ignored: camsim has no ambient term."));
  EXPECT_TRUE(hasNote(d, " line 7: 'Ns' ignored"));   // red is diffuse
  EXPECT_TRUE(hasNote(d, " line 14: 'Ni' ignored"));  // shiny is opaque
  EXPECT_TRUE(hasNote(d, " line 18: 'Kd' ignored"));  // glass is clear
  EXPECT_TRUE(hasNote(d, " line 20: 'd' approximated"));
  EXPECT_TRUE(hasNote(d, " line 25: 'map_Kd -bm' ignored"));
  EXPECT_TRUE(hasNote(d, " line 26: 'map_Bump' ignored: camsim has no bump maps."));
  EXPECT_FALSE(hasNote(d, "'Pr'"));  // the unused material is not mapped
  EXPECT_EQ(d.notes.size(), 7u);
}

TEST(SceneLoaderMtlTest, AGivenMaterialOverridesTheFileAndNeedsNoMtl) {
  TempDir dir;
  writeFile(dir.path() / "a.obj",
            "mtllib missing.mtl\nusemtl nowhere\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const SceneDescription d = loadMtl(
      mtlScene("{type: mesh, file: a.obj, material: grey}", "{grey: {type: diffuse}}"), dir.path());
  ASSERT_EQ(d.shapes.size(), 1u);
  EXPECT_EQ(d.shapes[0].material, 0);
  EXPECT_EQ(d.materials.size(), 1u);
  EXPECT_TRUE(d.notes.empty());
  EXPECT_EQ(d.inputFiles, std::vector<fs::path>{dir.path() / "a.obj"});
}

TEST(SceneLoaderMtlTest, TwoShapesOfOneFileShareItsMaterials) {
  const SceneDescription d = loadMtl(
      "camera: {position: [0, 0, 5], look_at: [0, 0, 0]}\nshapes:\n"
      "  - {type: mesh, file: quads.obj}\n  - {type: mesh, file: quads.obj, translate: [0, 2, "
      "0]}\n");
  EXPECT_EQ(d.materials.size(), 5u);
  ASSERT_EQ(d.shapes.size(), 10u);
  EXPECT_EQ(d.shapes[5].material, d.shapes[0].material);
  EXPECT_EQ(d.notes.size(), 7u);  // not repeated
}

// mtllib names one file (its name may hold spaces) or several; the first defining a name wins.
TEST(SceneLoaderMtlTest, ReadsEveryLibraryOfEveryMtllibLine) {
  TempDir dir;
  writeFile(dir.path() / "a.mtl", "newmtl x\nKd 0.6 0.2 0.2\n");
  writeFile(dir.path() / "b.mtl", "newmtl x\nKd 0.2 0.6 0.2\nnewmtl y\nKd 0.2 0.2 0.6\n");
  writeFile(dir.path() / "my lib.mtl", "newmtl z\nKd 0.5\n");
  writeFile(dir.path() / "m.obj",
            "mtllib a.mtl b.mtl\nmtllib my lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
            "usemtl x\nf 1 2 3\nusemtl y\nf 1 3 2\nusemtl z\nf 2 1 3\n");
  const SceneDescription d = loadMtl(mtlScene("{type: mesh, file: m.obj}"), dir.path());
  ASSERT_EQ(d.materials.size(), 3u);
  const auto rgb = [&](int i) {
    return reflectanceToRgb(d.materials[i].reflectance.value, RgbColorSpace::linearRec709());
  };
  EXPECT_NEAR(rgb(0).r, 0.6, 1e-3);  // x from a.mtl
  EXPECT_NEAR(rgb(1).b, 0.6, 1e-3);  // y from b.mtl
  EXPECT_NEAR(rgb(2).g, 0.5, 1e-3);
  EXPECT_EQ(d.inputFiles.size(), 4u);
}

void expectLoadError(const fs::path& dir, const std::string& text, const fs::path& file, int line,
                     const std::string& what) {
  try {
    loadMtl(text, dir);
    ADD_FAILURE() << "no InputError; expected " << what;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, file.string()) << e.what();
    EXPECT_EQ(e.where().line, line) << e.what();
    EXPECT_NE(e.message().find(what), std::string::npos) << e.what();
  }
}

TEST(SceneLoaderMtlTest, ErrorsNameTheObjOrMtlLine) {
  TempDir dir;
  const fs::path obj = dir.path() / "m.obj", mtl = dir.path() / "m.mtl";
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string shape = mtlScene("{type: mesh, file: m.obj}");

  writeFile(obj, "# a\nmtllib gone.mtl\nusemtl x\n" + tri);
  expectLoadError(dir.path(), shape, obj, 2, "material library 'gone.mtl' not found");

  writeFile(mtl, "newmtl x\nKd 0.5 0.5 0.5\n");
  writeFile(obj, "mtllib m.mtl\nusemtl y\n" + tri);
  expectLoadError(dir.path(), shape, obj, 2, "usemtl 'y': no such material");
  writeFile(obj, "usemtl x\n" + tri);
  expectLoadError(dir.path(), shape, obj, 1, "the file has no mtllib");

  writeFile(mtl, "newmtl x\nKd 0.5 0.5 0.5\n\nmap_Kd nothere.png\n");
  writeFile(obj, "mtllib m.mtl\nusemtl x\n" + tri);
  expectLoadError(dir.path(), shape, mtl, 4, "map_Kd: texture file 'nothere.png' not found");
  writeFile(mtl, "newmtl x\nKd 0.5 0.5 0.5 0.5\n");
  expectLoadError(dir.path(), shape, mtl, 2, "more are given");

  writeFile(mtl, "newmtl x\nKd 0.5 0.5 0.5\n");
  writeFile(obj, "mtllib m.mtl\n" + tri + "usemtl x\nf 1 3 2\n");
  expectLoadError(dir.path(), shape, obj, 6, "1 triangles have no material");

  writeFile(obj, "mtllib m.mtl\nusemtl x\n" + tri);
  expectLoadError(dir.path(), mtlScene("{type: mesh, file: m.obj}", "{'m.obj:x': {type: diffuse}}"),
                  "mtl.yaml", 4, "has the name of a material of the scene");
  // The emitter may leave triangles without a material: they are black.
  writeFile(obj, "mtllib m.mtl\n" + tri + "usemtl x\nf 1 3 2\n");
  const SceneDescription d = loadMtl(
      mtlScene("{type: mesh, file: m.obj, emission: {luminance: 1, two_sided: true}}"), dir.path());
  ASSERT_EQ(d.shapes.size(), 2u);
  EXPECT_EQ(d.shapes[0].material, -1);
  EXPECT_EQ(d.shapes[1].material, 0);
  EXPECT_TRUE(d.shapes[0].emission && d.shapes[1].emission);
}

}  // namespace
}  // namespace camsim
