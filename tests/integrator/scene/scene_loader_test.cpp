// Tests for integrator/scene_loader.{h,cpp} (with yaml_reader and scene_spectra): every
// malformed scene is an InputError naming file, line, column and the dotted key; valid
// scenes (YAML and JSON, inline and file meshes, spectra from CSV/RGB/blackbody) load.
#include "integrator/scene/scene_loader.h"
#include "tests/support/temp_dir.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "sensor/base/input_error.h"
#include "sensor/base/luts_directory.h"
#include "sensor/io/exr_io.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/color_space.h"
#include "sensor/spectra/rgb_uplift.h"
#include "tests/integrator/scene/scene_loader_error_cases.h"
#include "tests/integrator/texture_test_support.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

using test::readFile;
using test::writeFile;

namespace fs = std::filesystem;

// A fresh directory under the system temp directory, removed with everything in it.
using test::TempDir;

using test::ErrorCase;
using test::kCamera;
using test::kErrorCases;
using test::kMaterials;
using test::kPrefix;
using test::kSphere;
using test::meshWith;
using test::sphereWith;
using test::withCameraLine;
using test::withShapes;

class SceneLoaderErrorTest : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(SceneLoaderErrorTest, ThrowsInputErrorWithLocation) {
  const ErrorCase& c = GetParam();
  TempDir dir;
  SCOPED_TRACE(c.text);
  try {
    loadSceneFromText(c.text, "test.yaml", dir.path());
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "test.yaml") << e.what();
    EXPECT_EQ(e.where().line, c.line) << e.what();
    EXPECT_EQ(e.where().column, c.column) << e.what();
    EXPECT_EQ(e.key(), c.key) << e.what();
    EXPECT_NE(e.message().find(c.message), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(SceneLoader, SceneLoaderErrorTest, ::testing::ValuesIn(kErrorCases),
                         [](const ::testing::TestParamInfo<ErrorCase>& param) {
                           return std::string(param.param.name);
                         });

// ---- file-based errors -----------------------------------------------------------------

TEST(SceneLoaderTest, FileErrorNamesTheFile) {
  TempDir dir;
  const fs::path file = dir.path() / "bad.yaml";
  writeFile(file, sphereWith("-2", ", material: m"));
  try {
    loadScene(file);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, file.string());
    EXPECT_EQ(e.where().line, 7);
    EXPECT_EQ(e.where().column, 47);
    EXPECT_EQ(e.key(), "shapes[0].radius");
  }
}

TEST(SceneLoaderTest, MissingSceneFile) {
  TempDir dir;
  EXPECT_THROW(loadScene(dir.path() / "nope.yaml"), InputError);
  EXPECT_THROW(loadScene(dir.path()), InputError);  // a directory
}

TEST(SceneLoaderTest, ErrorInsideMeshFileNamesTheMeshFile) {
  TempDir dir;
  writeFile(dir.path() / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  try {
    loadSceneFromText(withShapes("  - {type: mesh, material: m, file: tri.obj}\n"), "test.yaml",
                      dir.path());
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(fs::path(e.where().file), dir.path() / "tri.obj") << e.what();
    EXPECT_EQ(e.where().line, 4) << e.what();
  }
}

TEST(SceneLoaderTest, EmptyText) {
  TempDir dir;
  EXPECT_THROW(loadSceneFromText("", "test.yaml", dir.path()), InputError);
  EXPECT_THROW(loadSceneFromText("# only a comment\n", "test.yaml", dir.path()), InputError);
}

// ---- valid scenes ----------------------------------------------------------------------

// world_from_camera with columns right, up, forward (right = forward × up, determinant −1)
// is the pose look_at builds: the same camera from the origin towards +z.
TEST(SceneLoaderTest, WorldFromCameraMatchesLookAt) {
  const SceneDescription a = loadSceneFromText(
      "camera:\n  world_from_camera: [-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]\n" +
          kMaterials + "shapes:\n" + kSphere,
      "a.yaml", ".");
  const SceneDescription b = loadSceneFromText(
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1]}\n" + kMaterials + "shapes:\n" + kSphere,
      "b.yaml", ".");
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      EXPECT_EQ(a.camera.worldFromCamera[c][r], b.camera.worldFromCamera[c][r]) << c << r;
}

// A far look_at is a direction: 1e300 overflowed the length, and the zero direction was
// refused as "up is parallel to the viewing direction".
TEST(SceneLoaderTest, AFarLookAtIsItsDirection) {
  const SceneDescription near = loadSceneFromText(
      "camera: {position: [0, 0, 0], look_at: [1, 0, 1]}\n" + kMaterials + "shapes:\n" + kSphere,
      "near.yaml", ".");
  const SceneDescription far =
      loadSceneFromText("camera: {position: [0, 0, 0], look_at: [1e300, 0, 1e300]}\n" + kMaterials +
                            "shapes:\n" + kSphere,
                        "far.yaml", ".");
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      EXPECT_EQ(near.camera.worldFromCamera[c][r], far.camera.worldFromCamera[c][r]) << c << r;
}

TEST(SceneLoaderTest, CornellBoxLoads) {
  const fs::path file = fs::path(CAMSIM_SOURCE_DIR) / "scenes" / "cornell_box.yaml";
  const std::string text = readFile(file);
  ASSERT_FALSE(text.empty());
  const SceneDescription scene = loadSceneFromText(text, "cornell_box.yaml", file.parent_path());
  EXPECT_EQ(scene.name, "cornell_box");
  EXPECT_EQ(scene.shapes.size(), 8u);
  EXPECT_EQ(scene.materials.size(), 3u);
  EXPECT_EQ(scene.camera.resolution.x, 512);
  EXPECT_EQ(scene.render.spp, 64);
  const ShapeDescription& light = scene.shapes[0];
  EXPECT_EQ(light.label, "light");
  ASSERT_TRUE(light.emission.has_value());
  EXPECT_NEAR(luminance(light.emission->radiance), 10000.0, 10000.0 * 1e-3);
  int emitters = 0;
  for (const ShapeDescription& s : scene.shapes) emitters += s.emission ? 1 : 0;
  EXPECT_EQ(emitters, 1);

  const SceneDescription fromFile = loadScene(file);
  EXPECT_EQ(fromFile.shapes.size(), 8u);
  EXPECT_EQ(fromFile.sourceFile, file.string());
}

TEST(SceneLoaderTest, ValidJsonLoads) {
  TempDir dir;
  const std::string json =
      "{\"camera\": {\"position\": [0, 0, -1], \"look_at\": [0, 0, 0], \"resolution\": [64, 48]},\n"
      " \"render\": {\"spp\": 4, \"seed\": 7},\n"
      " \"materials\": {\"m\": {\"type\": \"diffuse\", \"reflectance\": 0.25}},\n"
      " \"shapes\": [{\"type\": \"sphere\", \"centre\": [0, 0, 2], \"radius\": 0.5, "
      "\"material\": \"m\"}]}\n";
  const SceneDescription scene = loadSceneFromText(json, "scene.json", dir.path());
  EXPECT_EQ(scene.name, "scene");
  EXPECT_EQ(scene.camera.resolution.x, 64);
  EXPECT_EQ(scene.camera.resolution.y, 48);
  EXPECT_EQ(scene.render.spp, 4);
  EXPECT_EQ(scene.render.seed, 7u);
  ASSERT_EQ(scene.shapes.size(), 1u);
  EXPECT_EQ(scene.shapes[0].kind, ShapeDescription::Kind::kSphere);
  EXPECT_FLOAT_EQ(scene.shapes[0].radius, 0.5f);
  // Render space: relative to the camera's position (0, 0, −1).
  EXPECT_EQ(scene.renderOrigin, glm::dvec3(0.0, 0.0, -1.0));
  EXPECT_FLOAT_EQ(scene.shapes[0].centre.z, 3.0f);
  EXPECT_FLOAT_EQ(scene.materials[0].reflectance.value(550.0f), 0.25f);
}

TEST(SceneLoaderTest, ObjMeshWithScaleAndTranslate) {
  TempDir dir;
  writeFile(dir.path() / "meshes" / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const SceneDescription scene = loadSceneFromText(
      withShapes("  - type: mesh\n    material: m\n    file: meshes/tri.obj\n    scale: 2\n"
                 "    translate: [1, 2, 3]\n"),
      "test.yaml", dir.path());
  ASSERT_EQ(scene.shapes.size(), 1u);
  const MeshData& mesh = scene.shapes[0].mesh;
  EXPECT_EQ(scene.shapes[0].kind, ShapeDescription::Kind::kMesh);
  ASSERT_EQ(mesh.positions.size(), 3u);
  // Render space: world positions minus the camera's position.
  auto world = [&](double x, double y, double z) {
    return glm::vec3(glm::dvec3(x, y, z) - scene.renderOrigin);
  };
  EXPECT_EQ(mesh.positions[0], world(1, 2, 3));
  EXPECT_EQ(mesh.positions[1], world(3, 2, 3));
  EXPECT_EQ(mesh.positions[2], world(1, 4, 3));
  EXPECT_EQ(mesh.indices, (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(SceneLoaderTest, CsvReflectanceFoundThroughSpectraPath) {
  TempDir dir;
  writeFile(dir.path() / "tables" / "paint.csv",
            "wavelength,gloss,matte\n400,0.2,0.1\n700,0.8,0.4\n");
  const std::string text = "spectra_path: [tables]\n" + kCamera +
                           "materials:\n  m: {type: diffuse, reflectance: {csv: paint.csv, column: "
                           "matte}}\nshapes:\n" +
                           kSphere;
  const SceneDescription scene = loadSceneFromText(text, "test.yaml", dir.path());
  const Spectrum& r = scene.materials[0].reflectance.value;
  EXPECT_NEAR(r(400.0f), 0.1, 1e-6);
  EXPECT_NEAR(r(550.0f), 0.25, 1e-6);
  EXPECT_NEAR(r(700.0f), 0.4, 1e-6);
  EXPECT_NEAR(r(380.0f), 0.1, 1e-6);  // reflectance holds its end values
  EXPECT_NEAR(r(800.0f), 0.4, 1e-6);

  // Without spectra_path the table is not found, and the error names the csv key.
  try {
    loadSceneFromText(text.substr(text.find('\n') + 1), "test.yaml", dir.path());
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "materials.m.reflectance.csv") << e.what();
    EXPECT_EQ(e.where().line, 5) << e.what();
  }
}

// inputFiles: every file the loader read, in the order first read, each once — the bench's
// reference cache keys on it (integrator/measure/bench_reference.h), so a file missing here would let a
// stale reference survive a change to it.
TEST(SceneLoaderTest, RecordsEveryFileItReads) {
  TempDir dir;
  writeFile(dir.path() / "tables" / "paint.csv", "wavelength,r\n400,0.2\n700,0.8\n");
  writeFile(dir.path() / "tri.obj", "v 0 0 1\nv 1 0 1\nv 0 1 1\nf 1 2 3\n");
  fs::create_symlink("paint.csv", dir.path() / "tables" / "alias.csv");
  test::writeTestPng(dir.path() / "albedo.png", 2, 2, 3, 8, std::vector<std::uint16_t>(12, 100));
  Image env(4, 2, {"R", "G", "B"});
  env.pixels.assign(env.pixels.size(), 1.0f);
  writeExr(dir.path() / "sky.exr", env, {}, std::nullopt);
  const std::string text =
      "spectra_path: [tables]\n" + kCamera +
      "sensor: {model: fullframe-d850}\n"
      "materials:\n"
      "  a: {type: diffuse, reflectance: {csv: paint.csv}}\n"
      "  b: {type: diffuse, reflectance: {csv: ./paint.csv}}\n"  // the same file again
      "  e: {type: diffuse, reflectance: {csv: alias.csv}}\n"    // and through a link
      "  c: {type: conductor, metal: Au}\n"
      "  d: {type: diffuse, reflectance: {texture: albedo.png}}\n"
      "shapes:\n" +
      "  - {type: mesh, file: tri.obj, material: a}\n"
      "lights:\n  - {type: environment, file: sky.exr, scale: 1}\n";
  const SceneDescription scene = loadSceneFromText(text, "test.yaml", dir.path());
  const fs::path luts = lutsDirectory();  // as the loader finds it (honours $CAMSIM_LUTS)
  const std::vector<fs::path> expected = {luts / "sensors" / "fullframe-d850.yaml",
                                          luts / "spectra" / "cameras" / "nikon_d850.csv",
                                          dir.path() / "tables" / "paint.csv",
                                          luts / "spectra" / "metals" / "Au.csv",
                                          dir.path() / "albedo.png",
                                          dir.path() / "tri.obj",
                                          dir.path() / "sky.exr"};
  ASSERT_EQ(scene.inputFiles.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i)
    EXPECT_TRUE(fs::equivalent(scene.inputFiles[i], expected[i]))
        << i << ": " << scene.inputFiles[i] << " vs " << expected[i];
}

TEST(SceneLoaderTest, RgbReflectance) {
  TempDir dir;
  const SceneDescription scene = loadSceneFromText(
      kCamera + "materials:\n  m: {type: diffuse, reflectance: {rgb: [0.6, 0.3, 0.1]}}\nshapes:\n" +
          kSphere,
      "test.yaml", dir.path());
  const Spectrum expected = rgbToReflectance({0.6, 0.3, 0.1}, RgbColorSpace::linearRec709());
  const Spectrum& r = scene.materials[0].reflectance.value;
  for (int i = 0; i < kSpectrumSamples; ++i) {
    EXPECT_FLOAT_EQ(r.sample(i), expected.sample(i)) << i;
    EXPECT_GE(r.sample(i), 0.0f);
    EXPECT_LE(r.sample(i), 1.0f);
  }
  EXPECT_GT(r(650.0f), r(450.0f));  // reddish
}

TEST(SceneLoaderTest, BlackbodyEmissionWithUnitScale) {
  TempDir dir;
  const SceneDescription scene = loadSceneFromText(
      sphereWith("1", ", emission: {spectrum: {blackbody: 3000}, scale: 1, two_sided: true}"),
      "test.yaml", dir.path());
  ASSERT_TRUE(scene.shapes[0].emission.has_value());
  EXPECT_TRUE(scene.shapes[0].emission->twoSided);
  EXPECT_EQ(scene.shapes[0].material, -1);  // an emitter without material is black
  const Spectrum expected = Spectrum::blackbody(3000.0);
  for (int i = 0; i < kSpectrumSamples; ++i)
    EXPECT_FLOAT_EQ(scene.shapes[0].emission->radiance.sample(i), expected.sample(i)) << i;
}

TEST(SceneLoaderTest, LuminanceSetsAbsoluteScale) {
  TempDir dir;
  const SceneDescription scene =
      loadSceneFromText(sphereWith("1", ", emission: {spectrum: {illuminant: A}, luminance: 250}"),
                        "test.yaml", dir.path());
  EXPECT_NEAR(luminance(scene.shapes[0].emission->radiance), 250.0, 250.0 * 1e-3);
}

}  // namespace
}  // namespace camsim

namespace camsim {
namespace {

// yaml-cpp 0.7's LoadAll loops forever on these (fuzz finding, jbeder/yaml-cpp#1319): the
// loader must reject them at once as syntax errors at 1:1.
TEST(SceneLoaderYamlCpp, InputsThatMadeLoadAllLoopAreSyntaxErrors) {
  for (const char* text : {",", "[]\"\",", ",,,"}) {
    try {
      loadSceneFromText(text, "loop.yaml", ".");
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().line, 1) << text;
      EXPECT_NE(std::string(e.what()).find("YAML syntax error"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace camsim
