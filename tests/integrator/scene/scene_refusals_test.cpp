// Scenes refused by the key that is wrong, found by probing the command line (each named
// something else before): a mesh file's translate past ±1e15 m ("mesh has zero area"), a
// sensor's own data refused after rendering (the scene's sensor block).
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "integrator/capture/capture.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "tests/integrator/scene/scene_limits_support.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

using test::errorOf;
using test::kBall;
using test::kHeader;
using test::kLimitsCamera;
using test::kMaterial;
using test::kSun;

// A mesh file's translate past ±1e15 m is named by its key (the collapsed float positions
// were refused as "mesh has zero area", naming the file).
TEST(SceneRefusals, AMeshFilesTranslateIsRangeChecked) {
  const test::TempDir dir;
  test::writeFile(dir.path() / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  try {
    (void)loadSceneFromText(kHeader + kLimitsCamera + kSun + kMaterial + "shapes:\n" + kBall +
                                "  - {type: mesh, file: tri.obj, translate: [1e20, 0, 0], "
                                "material: m}\n",
                            "far.yaml", dir.path());
    ADD_FAILURE() << "loaded";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "shapes[1].translate") << e.what();
    EXPECT_NE(e.message().find("within ±1e15 m"), std::string::npos) << e.what();
  }
}

// A sensor whose CFA no demosaicking reads (a 3×3 tile) is refused after rendering, naming
// the sensor's file and its key, and the scene line that named it (it named the scene's
// sensor.model alone, or with a --sensor override the scene file).
TEST(SceneRefusals, ASensorsOwnDataErrorNamesItsFile) {
  const test::TempDir dir;
  test::writeFile(dir.path() / "cfa3.yaml",
                  "pixel_pitch_um: 5\ncfa: {tile: [[0, 1, 2], [1, 2, 0], [2, 0, 1]], channels: "
                  "[R, G, B]}\nqe: {curves: cameras/sony_ilce_7m3.csv, peak_qe: 0.6}\n");
  const InputError e = errorOf([&] {
    capture(loadSceneFromText(kHeader + kLimitsCamera + kSun + "sensor: {model: cfa3.yaml}\n" +
                                  kMaterial + "shapes:\n" + kBall,
                              "cfa3_scene.yaml", dir.path()));
  });
  EXPECT_EQ(e.where().file, (dir.path() / "cfa3.yaml").string()) << e.what();
  EXPECT_EQ(e.key(), "cfa") << e.what();
  EXPECT_NE(std::string(e.what()).find("demosaicking needs a Bayer layout"), std::string::npos)
      << e.what();
  EXPECT_NE(std::string(e.what()).find("in the file named by cfa3_scene.yaml:"), std::string::npos)
      << e.what();
}

// Spectral tables are held to an inline value's range: an emission shape of 1e40 overflowed
// the float spectrum and the light distribution was NaN (a failed check, exit 134); an index
// of refraction of 1e300 from a table was taken where `ior: 1e300` is refused.
TEST(SceneRefusals, SpectralTablesAreHeldToTheInlineRange) {
  const test::TempDir dir;
  test::writeFile(dir.path() / "hot.csv", "nm,e\n400,1e40\n700,1e40\n");
  test::writeFile(dir.path() / "dense.csv", "nm,n\n400,1e300\n700,1.5\n");
  const struct {
    std::string materials, shapes, key, says;
  } cases[] = {
      {kMaterial,
       "  - {type: sphere, centre: [0, 2, 0], radius: 0.5, emission: {spectrum: {csv: hot.csv, "
       "column: e}, luminance: 1000}}\n",
       "shapes[1].emission.spectrum.csv", "above 1e+30"},
      {"materials: {m: {type: diffuse}, glass: {type: dielectric, ior: {csv: dense.csv}}}\n",
       "  - {type: sphere, centre: [0, 2, 0], radius: 0.5, material: glass}\n",
       "materials.glass.ior.csv", "above 1000"},
  };
  for (const auto& c : cases) {
    const InputError e = errorOf([&] {
      loadSceneFromText(
          kHeader + kLimitsCamera + kSun + c.materials + "shapes:\n" + kBall + c.shapes,
          "tables.yaml", dir.path());
    });
    EXPECT_EQ(e.key(), c.key) << e.what();
    EXPECT_NE(e.message().find(c.says), std::string::npos) << e.what();
  }
}

// A traced lens no ray from the film gets through (an aspheric a16 of 1e10 bends every ray
// out) rendered black at 0 rays/s, exit 0, its sidecar claiming f/4.8: refused when the
// scene is built, naming the scene file; without the term the lens builds.
TEST(SceneRefusals, ALensThatPassesNoLightIsRefused) {
  const test::TempDir dir;
  // A front element of a clear aperture far below anything the exit-pupil search resolves
  // (its windows stop at a millionth of the rear element's). An aspheric a16 = 1e10 once
  // served, but the search now finds the light its central 0.3 mm passes.
  const std::string lens =
      "# radius thickness N aperture\n50 5 1.5 {aperture}\n-50 1 1 20\n0 4 0 10\n";
  const auto scene = [&](const std::string& aperture) {
    std::string text = lens;
    text.replace(text.find("{aperture}"), 10, aperture);
    test::writeFile(dir.path() / "lens.dat", text);
    return loadSceneFromText(
        "camera: {position: [0, 0, 0], look_at: [0, 0, 1], sensor_width_mm: 36, "
        "sensor_height_mm: 24, resolution: [12, 8], lens: {file: lens.dat}}\n" +
            kMaterial + "shapes:\n" + kBall,
        "lens_scene.yaml", dir.path());
  };
  const InputError e = errorOf([&] { const Scene built(scene("1e-12")); });
  EXPECT_EQ(e.where().file, "lens_scene.yaml") << e.what();
  EXPECT_EQ(e.key(), "camera.lens") << e.what();
  EXPECT_NE(e.message().find("no ray from the film gets through"), std::string::npos) << e.what();
  EXPECT_NO_THROW(const Scene built(scene("20")));
}

}  // namespace
}  // namespace camsim
