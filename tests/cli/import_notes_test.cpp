// Tests for the loader's import notes (SceneDescription::notes) at the command line
// (cli/render_command.cpp) and in the sidecar (integrator/capture/capture_sidecar.cpp): an
// OBJ with an .mtl whose statements camsim ignores prints each as "note: …" on stderr and
// lists it in the sidecar's "import_notes"; a scene without notes has "import_notes": [].
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;
using test::quote;
using test::readFile;
using test::writeFile;

const fs::path kObjMtlData = fs::path(CAMSIM_TEST_DATA_DIR) / "obj_mtl";

std::string sceneWith(const std::string& shape) {
  return "camera: {position: [6, 0.5, 8], look_at: [6, 0.5, 0], resolution: [8, 8]}\n"
         "render: {spp: 1}\n"
         "shapes:\n  - " +
         shape +
         "\n"
         "  - {type: sphere, centre: [6, 0, 12], radius: 1, emission: {luminance: 100}}\n";
}

TEST(ImportNotes, PrintedOnStderrAndListedInTheSidecar) {
  test::TempDir dir;
  writeFile(dir.path() / "notes.yaml",
            sceneWith("{type: mesh, file: " + (kObjMtlData / "quads.obj").string() + "}"));
  const fs::path out = dir.path() / "out";
  const test::RunResult r = test::runCamsim(
      "render " + quote((dir.path() / "notes.yaml").string()) + " -o " + quote(out.string()),
      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string note =
      (kObjMtlData / "quads.mtl").string() + " line 4: 'Ka' ignored: camsim has no ambient term.";
  EXPECT_NE(r.err.find("note: " + note + "\n"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'map_Bump' ignored"), std::string::npos) << r.err;
  const std::string json = readFile(out / "notes.json");
  EXPECT_NE(json.find("\"import_notes\": [\"" + note + "\", "), std::string::npos) << json;
}

TEST(ImportNotes, EmptyListWithoutNotes) {
  test::TempDir dir;
  writeFile(dir.path() / "plain.yaml",
            sceneWith("{type: sphere, centre: [6, 0.5, 0], radius: 1, material: grey}") +
                "materials: {grey: {type: diffuse}}\n");
  const fs::path out = dir.path() / "out";
  const test::RunResult r = test::runCamsim(
      "render " + quote((dir.path() / "plain.yaml").string()) + " -o " + quote(out.string()),
      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find("note: "), std::string::npos) << r.err;
  EXPECT_NE(readFile(out / "plain.json").find("\"import_notes\": []"), std::string::npos);
}

}  // namespace
}  // namespace camsim
