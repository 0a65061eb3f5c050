// `camsim dataset` with the BOP and KITTI exports (integrator/capture/bop_writer.h,
// kitti_writer.h) on the real binary: a manifest selects them with `set: {exports: [bop,
// kitti]}`; each item writes its own BOP scene and KITTI image, numbered by the item's index,
// listed in item.json by their paths in the item folder, so that shards write the items of
// one run byte for byte and --resume skips them.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace dataset_exports_test {

namespace fs = std::filesystem;

const char* const kScene =
    "name: table\n"
    "render: {spp: 2, max_depth: 1}\n"
    "camera: {position: [0, 0, -2], look_at: [0, 0, 0], resolution: [24, 16]}\n"
    "materials: {m: {type: diffuse}}\n"
    "shapes:\n"
    "  - {type: rectangle, corner: [-2, -2, 1], edge_u: [4, 0, 0], edge_v: [0, 4, 0], "
    "material: m}\n"
    "  - type: mesh\n"
    "    class: 3\n"
    "    material: m\n"
    "    vertices: [[0, 0, 0], [0.3, 0, 0], [0, 0.3, 0]]\n"
    "    faces: [[0, 1, 2]]\n"
    "    instances: [{translate: [0, 0, 0]}, {translate: [-0.4, 0, 0.2]}]\n"
    "lights: [{type: point, position: [0, 1, -2], intensity: 20}]\n";

const char* const kManifest =
    "format: camsim-dataset/1\nscene: table.yaml\n"
    "set: {exports: [bop, kitti]}\n"
    "items:\n"
    "  - {camera.position: [0, 0, -2]}\n"
    "  - {camera.position: [0.3, 0.1, -2]}\n";

std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename() != "index.jsonl")
      files[fs::relative(e.path(), dir).string()] = test::readFile(e.path());
  return files;
}

TEST(DatasetExports, EachItemIsABopSceneAndAKittiImageOfItsIndexThatShardsAndResumeKeep) {
  test::TempDir dir;
  test::writeFile(dir.path() / "table.yaml", kScene);
  test::writeFile(dir.path() / "bop.yaml", kManifest);
  const std::string manifest = test::quote((dir.path() / "bop.yaml").string());
  const fs::path whole = dir.path() / "whole", parts = dir.path() / "parts";
  const auto r = test::runCamsim("dataset " + manifest + " -o " + whole.string(), dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* f :
       {"items/000000/bop/train_pbr/000000/scene_gt.json",
        "items/000000/bop/train_pbr/000000/rgb/000000.png",
        "items/000000/bop/train_pbr/000000/depth/000000.png",
        "items/000001/bop/train_pbr/000001/scene_camera.json",
        "items/000001/bop/models/obj_000003.ply", "items/000001/bop/models/models_info.json",
        "items/000000/kitti/image_2/000000.png", "items/000000/kitti/label_2/000000.txt",
        "items/000001/kitti/calib/000001.txt", "items/000001/kitti/label_2/000001.txt"})
    EXPECT_TRUE(fs::is_regular_file(whole / f)) << f;
  // item.json lists the BOP files by their path in the item folder.
  const std::string item = test::readFile(whole / "items/000001/item.json");
  EXPECT_NE(item.find("\"bop/train_pbr/000001/scene_gt.json\""), std::string::npos) << item;
  EXPECT_NE(item.find("\"kitti/label_2/000001.txt\""), std::string::npos) << item;
  // The two instances of class 3 are two KITTI labels of type Class3.
  const std::string labels = test::readFile(whole / "items/000001/kitti/label_2/000001.txt");
  EXPECT_EQ(labels.find("Class3 "), 0U) << labels;
  EXPECT_NE(labels.find("\nClass3 "), std::string::npos) << labels;
  // Two instances of one mesh, class 3: one model, two entries.
  const std::string gt = test::readFile(whole / "items/000000/bop/train_pbr/000000/scene_gt.json");
  int entries = 0;
  for (auto p = gt.find("\"obj_id\": 3"); p != std::string::npos;
       p = gt.find("\"obj_id\": 3", p + 1))
    ++entries;
  EXPECT_EQ(entries, 2) << gt;

  for (int k = 0; k < 2; ++k) {
    const auto s = test::runCamsim(
        "dataset " + manifest + " -o " + parts.string() + " --shard " + std::to_string(k) + "/2",
        dir.path());
    ASSERT_EQ(s.exitCode, 0) << s.err;
  }
  const auto a = tree(whole), b = tree(parts);
  EXPECT_EQ(a.size(), b.size());
  for (const auto& [name, content] : a) {
    ASSERT_TRUE(b.count(name)) << name;
    EXPECT_TRUE(b.at(name) == content) << name << " differs";
  }
  // --resume finds every item up to date (its BOP files included) and renders nothing.
  const auto again =
      test::runCamsim("dataset " + manifest + " -o " + whole.string() + " --resume", dir.path());
  ASSERT_EQ(again.exitCode, 0) << again.err;
  EXPECT_EQ(tree(whole), a);
  const std::string index = test::readFile(whole / "index.jsonl");
  EXPECT_EQ(index.find("\"item\": 0", index.find("\"item\": 0") + 1), std::string::npos) << index;
}

// BOP's one-model-per-obj_id rule is checked by --check as by the run, and named at the
// manifest's line (found by probing: --check said "all valid" for a manifest the run then
// refused, and the run named line 9 of the edited scene text, which no file has).
TEST(DatasetExports, BopModelClashIsFoundByCheckAndNamedAtTheManifestLine) {
  const test::TempDir dir;
  test::writeFile(dir.path() / "table.yaml", kScene);
  test::writeFile(dir.path() / "clash.yaml",
                  "format: camsim-dataset/1\nscene: table.yaml\n"
                  "set: {exports: [bop]}\n"
                  "items:\n"
                  "  - {\"shapes[0].class\": 3}\n");
  for (const std::string& run :
       {std::string(" --check"), " -o " + test::quote((dir.path() / "out").string())}) {
    const test::RunResult r = test::runCamsim(
        "dataset " + test::quote((dir.path() / "clash.yaml").string()) + run, dir.path());
    EXPECT_EQ(r.exitCode, 2) << run << "\n" << r.err;
    EXPECT_NE(r.err.find("clash.yaml:3:16: key 'set.exports': item 0"), std::string::npos)
        << run << "\n"
        << r.err;
    EXPECT_NE(r.err.find("have class 3 (BOP's obj_id) but different models"), std::string::npos)
        << r.err;
    EXPECT_EQ(r.out.find("all valid"), std::string::npos) << r.out;
  }
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

// The items of a dataset are one BOP dataset (their train_pbr/ scenes gather under one
// models/), so an obj_id has one model in all of them: the first item's that has it (found
// by probing: a grid over a labelled mesh's scale wrote obj_000002.ply 159 mm across in item
// 0 and 238 mm in item 1, and exited 0). Refused by --check and the run alike, at the
// item's manifest line, before anything is written; a class's pose may vary.
TEST(DatasetExports, AnObjIdHasOneModelInAllItems) {
  const test::TempDir dir;
  test::writeFile(dir.path() / "table.yaml", kScene);
  const std::string head = "format: camsim-dataset/1\nscene: table.yaml\nset: {exports: [bop]}\n";
  struct Case {
    const char* items;
    const char* error;  // "": valid
  };
  const Case cases[] = {
      // Posed elsewhere (instances), a class added in later items with one model: valid.
      {"items:\n"
       "  - {camera.position: [0, 0, -2]}\n"
       "  - {\"shapes[1].instances\": [{translate: [0.1, 0, 0]}]}\n"
       "  - {\"shapes[0].class\": 4}\n"
       "  - {\"shapes[0].class\": 4, camera.position: [0.1, 0, -2]}\n",
       ""},
      // Each item's class 3 within the tolerance (4.2e-5 m) of item 0's, 6e-5 m from each
      // other: valid; class 4, which item 0 lacks, compares only its own models (found in
      // review: items 1 and 2 were compared on class 3 too, and refused).
      {"items:\n"
       "  - {camera.position: [0, 0, -2]}\n"
       "  - {\"shapes[0].class\": 4, \"shapes[1].vertices\": [[0, 0, 0], [0.30003, 0, 0], "
       "[0, 0.3, 0]]}\n"
       "  - {\"shapes[0].class\": 4, \"shapes[1].vertices\": [[0, 0, 0], [0.29997, 0, 0], "
       "[0, 0.3, 0]]}\n",
       ""},
      // Class 3's triangle larger in item 1.
      {"items:\n"
       "  - {camera.position: [0, 0, -2]}\n"
       "  - {\"shapes[1].vertices\": [[0, 0, 0], [0.4, 0, 0], [0, 0.3, 0]]}\n",
       "items.yaml:6:5: item 1 (the base scene with this item's values): bop: shape 'shapes[1][0]' "
       "has class 3 (BOP's obj_id) but a different model than shape 'shapes[1][0]' of item 0"},
      // Class 4, which item 0 lacks: item 2's rectangle against item 1's, from a grid.
      {"items:\n"
       "  - {camera.position: [0, 0, -2]}\n"
       "  - {\"shapes[0].class\": 4}\n"
       "  - {\"shapes[0].class\": 4, \"shapes[0].edge_u\": [3, 0, 0]}\n",
       "items.yaml:7:5: item 2 (the base scene with this item's values): bop: shape 'shapes[0]' "
       "has class 4 (BOP's obj_id) but a different model than shape 'shapes[0]' of item 1"},
  };
  for (const Case& c : cases) {
    test::writeFile(dir.path() / "items.yaml", head + c.items);
    for (const std::string& run :
         {std::string(" --check"), " -o " + test::quote((dir.path() / "out").string())}) {
      const test::RunResult r = test::runCamsim(
          "dataset " + test::quote((dir.path() / "items.yaml").string()) + run + " --threads 1",
          dir.path());
      if (!*c.error) {
        EXPECT_EQ(r.exitCode, 0) << c.items << run << "\n" << r.err;
        continue;
      }
      EXPECT_EQ(r.exitCode, 2) << c.items << run << "\n" << r.err;
      EXPECT_NE(r.err.find(c.error), std::string::npos) << run << "\n" << r.err;
      EXPECT_FALSE(fs::exists(dir.path() / "out")) << c.items;
    }
    fs::remove_all(dir.path() / "out");
  }
}

// Each item's estimated memory is held to the limit by --check and by the run (found by
// probing: a 32768 × 8192 item passed --check, then failed with std::bad_alloc, exit 1):
// a 256 × 256 item needs more than 1 MB (its film alone is 1.5 MB).
TEST(DatasetExports, AnItemBeyondTheMemoryLimitIsRefusedBeforeAnything) {
  const test::TempDir dir;
  test::writeFile(dir.path() / "table.yaml", kScene);
  test::writeFile(dir.path() / "big.yaml",
                  "format: camsim-dataset/1\nscene: table.yaml\n"
                  "items:\n"
                  "  - {camera.resolution: [24, 16]}\n"
                  "  - {camera.resolution: [256, 256]}\n");
  for (const std::string& run :
       {std::string(" --check"), " -o " + test::quote((dir.path() / "out").string())}) {
    const test::RunResult r =
        test::runCamsim("dataset " + test::quote((dir.path() / "big.yaml").string()) + run +
                            " --threads 1 --max-memory-gb 0.001",
                        dir.path());
    EXPECT_EQ(r.exitCode, 2) << run << "\n" << r.err;
    EXPECT_NE(r.err.find("big.yaml:5:5: item 1 (the base scene with this item's values): this "
                         "render needs an estimated"),
              std::string::npos)
        << run << "\n"
        << r.err;
    EXPECT_NE(r.err.find("set by --max-memory-gb"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

}  // namespace dataset_exports_test
}  // namespace camsim
