// `camsim dataset` into a folder that already holds a dataset, and the errors of an item
// named by the manifest's lines (integrator/dataset/dataset_run.cpp, dataset_item.cpp).
// Found by probing, each exit 0 before:
//  - a second manifest run into the folder of a first: the first's items stayed beside the
//    second's and the index held two "item 0 done" lines — now exit 2, naming dataset.json's
//    manifest, the folder untouched; the same manifest (renamed, or edited and resumed) runs;
//  - a shorter version of the manifest over the folder of a longer one: the surplus items
//    stayed, looking like part of the dataset — now exit 2, naming the item's folder;
//  - an item named `item` or `params`: its render's NAME.json replaced the item's own
//    item.json or params.json — now exit 2 at the manifest line that names it;
//  - an error found while rendering (white balance of an unlit image) named a line of the
//    resolved scene in memory — now the manifest line that set the key.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>

#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;
using test::readFile;
using test::writeFile;

const char* kBase =
    "format: camsim-scene/1\nname: probe\nrender: {spp: 1}\n"
    "camera: {position: [0, 0, -3], look_at: [0, 0, 0], resolution: [8, 8]}\n"
    "sensor: {model: smartphone-1.4um, noise: none}\n"
    "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
    "shapes:\n"
    "  - {type: sphere, centre: [0, 0, 0], radius: 1, material: grey}\n"
    "  - {name: light, type: sphere, centre: [0, 1.5, -3], radius: 0.5, emission: {luminance: "
    "1000}}\n";

std::string manifest(int items) {
  std::string text = "format: camsim-dataset/1\nscene: base.yaml\nitems:\n";
  for (int i = 0; i < items; ++i) text += "  - {render.seed: " + std::to_string(i + 1) + "}\n";
  return text;
}

std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = readFile(e.path());
  return files;
}

class DatasetReuse : public testing::Test {
 protected:
  void SetUp() override { writeFile(dir_.path() / "base.yaml", kBase); }
  test::RunResult run(const std::string& manifestName, const std::string& args) {
    return test::runCamsim("dataset " + test::quote((dir_.path() / manifestName).string()) +
                               " -o " + test::quote(out_.string()) + " " + args,
                           dir_.path());
  }
  test::TempDir dir_;
  fs::path out_ = dir_.path() / "out";
};

TEST_F(DatasetReuse, AnotherManifestsFolderIsRefusedAndLeftAsItWas) {
  writeFile(dir_.path() / "a.yaml", manifest(3));
  ASSERT_EQ(run("a.yaml", "").exitCode, 0);
  const auto before = tree(out_);
  writeFile(dir_.path() / "b.yaml", manifest(1) + "set: {render.spp: 2}\n");
  const auto r = run("b.yaml", "");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find((out_ / "dataset.json").string() + ":"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("key 'manifest'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("another manifest ('a.yaml')"), std::string::npos) << r.err;
  EXPECT_EQ(tree(out_), before);
  // The same manifest edited (one item more) resumes: only the new item renders.
  writeFile(dir_.path() / "a.yaml", manifest(4));
  const auto grown = run("a.yaml", "--resume");
  EXPECT_EQ(grown.exitCode, 0) << grown.err;
  EXPECT_NE((grown.out + grown.err).find("1 rendered, 3 up to date"), std::string::npos)
      << grown.out << grown.err;
  // The same manifest under another name is the same dataset: up to date.
  writeFile(dir_.path() / "renamed.yaml", manifest(4));
  const auto renamed = run("renamed.yaml", "--resume");
  EXPECT_EQ(renamed.exitCode, 0) << renamed.err;
  EXPECT_NE((renamed.out + renamed.err).find("0 rendered, 4 up to date"), std::string::npos)
      << renamed.out << renamed.err;
}

TEST_F(DatasetReuse, ItemsPastAShorterManifestsCountAreRefused) {
  writeFile(dir_.path() / "a.yaml", manifest(3));
  ASSERT_EQ(run("a.yaml", "").exitCode, 0);
  const auto before = tree(out_);
  // One item: the smallest surplus folder named (the iteration order is the filesystem's),
  // and how many more there are.
  writeFile(dir_.path() / "a.yaml", manifest(1));
  const auto r = run("a.yaml", "--resume");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find((out_ / "items" / "000001").string() + ": "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("an item this manifest does not have (it has 1 item), left by an earlier "
                       "run with 1 more"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(tree(out_), before);
  fs::remove_all(out_ / "items" / "000001");
  fs::remove_all(out_ / "items" / "000002");
  EXPECT_EQ(run("a.yaml", "--resume").exitCode, 0);
}

TEST_F(DatasetReuse, AnItemNamedAfterTheItemsOwnFilesIsRefusedAtItsLine) {
  for (const char* name : {"item", "params"}) {
    SCOPED_TRACE(name);
    writeFile(dir_.path() / "n.yaml", manifest(1) + "  - {name: " + name + "}\n");
    const auto r = run("n.yaml", "");
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("n.yaml:5:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("key 'items[1].name'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(std::string("taken by the item's own ") + name + ".json"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(out_));
  }
  // A name from the base scene is refused at its line there; from the base scene's file
  // name, at the manifest's scene: line.
  std::string named = kBase;
  named.replace(named.find("name: probe"), 11, "name: item");
  writeFile(dir_.path() / "named.yaml", named);
  writeFile(dir_.path() / "n.yaml",
            "format: camsim-dataset/1\nscene: named.yaml\nitems:\n  - {render.seed: 1}\n");
  auto r = run("n.yaml", "");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("named.yaml:2:7: key 'name'"), std::string::npos) << r.err;
  std::string unnamed = kBase;
  unnamed.erase(unnamed.find("name: probe\n"), 12);
  writeFile(dir_.path() / "params.yaml", unnamed);
  writeFile(dir_.path() / "n.yaml",
            "format: camsim-dataset/1\nscene: params.yaml\nitems:\n  - {render.seed: 1}\n");
  r = run("n.yaml", "");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("n.yaml:2:8: key 'scene': the base scene's file name"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out_));
}

// A dataset.json that another program wrote: not a camsim dataset folder (it said
// "key 'manifest': required key is missing").
TEST_F(DatasetReuse, AForeignDatasetJsonIsNotACamsimFolder) {
  fs::create_directories(out_);
  writeFile(out_ / "dataset.json", "{\"name\": \"someone else's\"}\n");
  writeFile(dir_.path() / "a.yaml", manifest(1));
  const auto r = run("a.yaml", "");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("not a camsim dataset folder"), std::string::npos) << r.err;
}

TEST_F(DatasetReuse, AnErrorFoundWhileRenderingNamesTheManifestLine) {
  writeFile(dir_.path() / "wb.yaml",
            "format: camsim-dataset/1\nscene: base.yaml\nset:\n  isp.white_balance: grey_world\n"
            "items:\n  - {render.seed: 1}\n  - {'shapes[light].emission.luminance': 0}\n");
  const auto r = run("wb.yaml", "--threads 1");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("wb.yaml:4:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("key 'set.isp.white_balance': item 1:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cannot white-balance"), std::string::npos) << r.err;
  // An error of a file of its own (a sensor whose CFA no demosaicking reads) keeps that
  // file's place, prefixed with the item (the review found it moved to the item's entry).
  writeFile(dir_.path() / "cfa3.yaml",
            "pixel_pitch_um: 5\ncfa: {tile: [[0, 1, 2], [1, 2, 0], [2, 0, 1]], channels: [R, G, "
            "B]}\nqe: {curves: cameras/sony_ilce_7m3.csv, peak_qe: 0.6}\n");
  writeFile(dir_.path() / "s.yaml",
            "format: camsim-dataset/1\nscene: base.yaml\nitems:\n  - {sensor.model: cfa3.yaml}\n");
  fs::remove_all(out_);
  const auto s = run("s.yaml", "--threads 1");
  EXPECT_EQ(s.exitCode, 2) << s.err;
  EXPECT_NE(s.err.find("cfa3.yaml: key 'cfa': item 0: demosaicking needs a Bayer layout"),
            std::string::npos)
      << s.err;
}

}  // namespace
}  // namespace camsim
