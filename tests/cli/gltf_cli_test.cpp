// `camsim render` on scenes that include glTF files, as a user runs it: a malformed asset
// exits 2 with the file and the JSON path in the message and writes nothing; a good one
// prints the loader's notes ("note: …") and lists them in the sidecar's import_notes.
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
using test::runCamsim;

const fs::path kGltfData = fs::path(CAMSIM_TEST_DATA_DIR) / "gltf";

std::string sceneIncluding(const fs::path& gltf) {
  return "camera: {position: [0, 0, 5], look_at: [0, 0, 0], resolution: [16, 12]}\n"
         "render: {spp: 1}\ninclude:\n  - gltf: " +
         gltf.string() + "\n";
}

TEST(GltfCli, MalformedAssetsExitTwoNamingFileAndJsonPathAndWriteNothing) {
  const struct {
    fs::path file;
    const char* path;
  } cases[] = {
      {kGltfData / "BoundsChecking/integer-out-of-bounds.gltf", "bufferViews[0].byteLength"},
      {kGltfData / "BoundsChecking/invalid-buffer-index.gltf", "bufferViews[1].buffer"},
      {kGltfData / "BoundsChecking/invalid-buffer-view-index.gltf", "bufferViews[0].buffer"},
      {kGltfData / "BoundsChecking/invalid-primitive-indices.gltf", "bufferViews[0].buffer"},
  };
  for (const auto& c : cases) {
    test::TempDir dir;
    test::writeFile(dir.path() / "scene.yaml", sceneIncluding(c.file));
    const fs::path out = dir.path() / "out";
    const test::RunResult r = runCamsim(
        "render " + quote((dir.path() / "scene.yaml").string()) + " -o " + quote(out.string()),
        dir.path());
    EXPECT_EQ(r.exitCode, 2) << c.file << "\n" << r.err;
    EXPECT_NE(r.err.find(c.file.string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.path), std::string::npos) << r.err;
    EXPECT_TRUE(!fs::exists(out) || fs::is_empty(out)) << c.file;
  }
}

TEST(GltfCli, RenderingAGltfFileDirectlySaysHowToIncludeIt) {
  test::TempDir dir;
  const test::RunResult r = runCamsim("render " + quote((kGltfData / "box01.glb").string()) +
                                          " -o " + quote((dir.path() / "o").string()),
                                      dir.path());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("a glTF file is an asset, not a camsim scene"), std::string::npos) << r.err;
}

TEST(GltfCli, NotesArePrintedAndInTheSidecar) {
  test::TempDir dir;
  test::writeFile(dir.path() / "scene.yaml",
                  "camera:\n  gltf: {camera: 0}\n  resolution: [16, 12]\nrender: {spp: 1}\n"
                  "include:\n  - gltf: " +
                      (kGltfData / "khronos/Cameras.gltf").string() + "\n");
  const fs::path out = dir.path() / "out";
  const test::RunResult r = runCamsim(
      "render " + quote((dir.path() / "scene.yaml").string()) + " -o " + quote(out.string()),
      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("note: include[0] (Cameras.gltf): cameras[0]: aspectRatio"),
            std::string::npos)
      << r.err;
  const std::string sidecar = test::readFile(out / "scene.json");
  EXPECT_NE(sidecar.find("\"import_notes\""), std::string::npos);
  EXPECT_NE(sidecar.find("aspectRatio 1.000000 is not used"), std::string::npos) << sidecar;
}

}  // namespace
}  // namespace camsim
