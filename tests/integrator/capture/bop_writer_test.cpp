// Tests for integrator/capture/bop_writer.cpp and bop_models.cpp on a hand-built capture
// (the amodal AOV's channels as its contract names them: amodal_<n>.A, visible_<n>.A): the
// files of the layout, masks at coverage ≥ 0.5 and their counts and boxes, the depth PNG
// against the depth AOV within its step, the models' sizes in mm, and a two-image scene.
// The JSON is read back with yaml-cpp (JSON is YAML), not with camsim's writer.
#include "integrator/capture/bop_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "sensor/base/yaml_reader.h"
#include "sensor/io/png_io.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace bop_writer_test {

namespace fs = std::filesystem;
constexpr int kW = 8, kH = 6;

// Two labelled shapes: the unit cube placed at 0.4 scale (class 1) and a ball (class 2).
SceneDescription twoObjects() {
  return loadSceneFromText(
      "exports: [bop]\n"
      "camera: {position: [0, 0, -3], look_at: [0, 0, 0], resolution: [8, 6]}\n"
      "materials: {m: {type: diffuse}}\n"
      "shapes:\n"
      "  - type: mesh\n"
      "    class: 1\n"
      "    material: m\n"
      "    vertices: [[-0.5, -0.5, -0.5], [0.5, -0.5, -0.5], [0.5, 0.5, -0.5], [-0.5, 0.5, -0.5],\n"
      "               [-0.5, -0.5, 0.5], [0.5, -0.5, 0.5], [0.5, 0.5, 0.5], [-0.5, 0.5, 0.5]]\n"
      "    faces: [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],\n"
      "            [3, 6, 2], [3, 7, 6], [0, 4, 7], [0, 7, 3], [1, 2, 6], [1, 6, 5]]\n"
      "    instances: [{translate: [0.2, 0, 0], scale: 0.4}]\n"
      "  - {type: sphere, centre: [-0.3, 0, 0.5], radius: 0.25, class: 2, material: m}\n",
      "bop.yaml", ".");
}

// The capture: depth 2.5 + 0.1·x m with a miss (0) at (0, 0); object 1's amodal coverage 1
// over x 1…4, y 1…3, 0.5 at x = 5 (in) and 0.49 at x = 6 (out); visible where x ≥ 3; object
// 2's amodal coverage 0.75 over x 0…1, y 3…5, visible nowhere.
CaptureResult handBuilt() {
  CaptureResult r;
  r.description = twoObjects();
  r.aovs = Image(kW, kH, {"depth.Z", "amodal_1.A", "visible_1.A", "amodal_2.A", "visible_2.A"});
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      r.aovs.at(x, y, 0) = (x == 0 && y == 0) ? 0.0f : static_cast<float>(2.5 + 0.1 * x);
      const bool rows = y >= 1 && y <= 3;
      const float a1 = rows ? (x >= 1 && x <= 4 ? 1.0f
                               : x == 5         ? 0.5f
                               : x == 6         ? 0.49f
                                                : 0.0f)
                            : 0.0f;
      r.aovs.at(x, y, 1) = a1;
      r.aovs.at(x, y, 2) = x >= 3 ? a1 : 0.0f;
      r.aovs.at(x, y, 3) = (x <= 1 && y >= 3) ? 0.75f : 0.0f;
    }
  r.aovs.at(0, 3, 0) = 0.0f;  // a pixel of object 2's mask without depth
  return r;
}

void writePicture(const fs::path& dir, const std::string& name) {
  fs::create_directories(dir);
  writePng8(dir / (name + ".png"), kW, kH, std::vector<std::uint8_t>(kW * kH * 3, 128));
}

YamlMap json(const fs::path& file) {
  return YamlMap(parseYaml(test::readFile(file), file.string()));
}

std::vector<double> numbers(const YamlValue& v) {
  std::vector<double> out;
  for (const YamlValue& item : v.items()) out.push_back(item.number());
  return out;
}

TEST(BopWriter, WritesEveryFileWithMasksCountsAndDepthInMm) {
  test::TempDir tmp;
  const CaptureResult r = handBuilt();
  writePicture(tmp.path(), r.description.name);
  std::vector<std::string> skipped;
  (void)writeBop(r, PoseModels(r.description), tmp.path(), 7, &skipped);
  EXPECT_TRUE(skipped.empty());
  const fs::path scene = tmp.path() / "bop" / "train_pbr" / "000007";
  for (const char* f :
       {"scene_camera.json", "scene_gt.json", "scene_gt_info.json", "rgb/000000.png",
        "depth/000000.png", "mask/000000_000000.png", "mask/000000_000001.png",
        "mask_visib/000000_000000.png", "mask_visib/000000_000001.png"})
    EXPECT_TRUE(fs::is_regular_file(scene / f)) << f;
  for (const char* f : {"obj_000001.ply", "obj_000002.ply", "models_info.json"})
    EXPECT_TRUE(fs::is_regular_file(tmp.path() / "bop" / "models" / f)) << f;

  // scene_camera: K of the 8 × 6 camera (cx, cy at the centre, pixel centres at integers);
  // the camera 3 m before the world origin: t_w2c = (0, 0, 3000) mm.
  YamlMap cam = YamlMap(json(scene / "scene_camera.json").require("0"));
  const std::vector<double> k = numbers(cam.require("cam_K"));
  ASSERT_EQ(k.size(), 9u);
  EXPECT_DOUBLE_EQ(k[2], 3.5);
  EXPECT_DOUBLE_EQ(k[5], 2.5);
  EXPECT_DOUBLE_EQ(k[8], 1.0);
  const std::vector<double> t = numbers(cam.require("cam_t_w2c"));
  EXPECT_NEAR(t[0], 0.0, 1e-6);
  EXPECT_NEAR(t[2], 3000.0, 1e-6);
  const double depthScale = cam.require("depth_scale").number();
  EXPECT_DOUBLE_EQ(depthScale, 0.1);  // 3.2 m = 32 000 steps of 0.1 mm

  // depth/: 16-bit, × depth_scale = the AOV in mm within half a step; 0 where nothing was hit.
  const PngImage depth = readPng(scene / "depth/000000.png");
  ASSERT_EQ(depth.bitDepth, 16);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      EXPECT_NEAR(depth.samples[static_cast<size_t>(y * kW + x)] * depthScale,
                  1000.0 * double(r.aovs.at(x, y, 0)), 0.5 * depthScale + 1e-3)
          << x << ", " << y;

  // scene_gt: the cube's pose (obj_id 1) puts its model origin at (0.2, 0, 0) m in the world,
  // 3 m ahead: t = (−200, 0, 3000) mm in OpenCV axes (the camera's right is world −x).
  const std::vector<YamlValue> gt = json(scene / "scene_gt.json").require("0").items();
  ASSERT_EQ(gt.size(), 2u);
  EXPECT_EQ(YamlMap(gt[0]).require("obj_id").integer(0, 100), 1);
  EXPECT_EQ(YamlMap(gt[1]).require("obj_id").integer(0, 100), 2);
  const std::vector<double> tm = numbers(YamlMap(gt[0]).require("cam_t_m2c"));
  EXPECT_NEAR(tm[0], -200.0, 1e-6);
  EXPECT_NEAR(tm[1], 0.0, 1e-6);
  EXPECT_NEAR(tm[2], 3000.0, 1e-6);
  EXPECT_EQ(numbers(YamlMap(gt[0]).require("cam_R_m2c")).size(), 9u);

  // scene_gt_info: object 1's amodal mask is x 1…5 (0.5 is in, 0.49 out), y 1…3: 15 px, box
  // [1, 1, 4, 2] (bop_toolkit: w = x_max − x_min); visible x 3…5: 9 px, fraction 0.6.
  const std::vector<YamlValue> info = json(scene / "scene_gt_info.json").require("0").items();
  ASSERT_EQ(info.size(), 2u);
  YamlMap one(info[0]), two(info[1]);
  EXPECT_EQ(numbers(one.require("bbox_obj")), (std::vector<double>{1, 1, 4, 2}));
  EXPECT_EQ(numbers(one.require("bbox_visib")), (std::vector<double>{3, 1, 2, 2}));
  EXPECT_EQ(one.require("px_count_all").integer(0, 100), 15);
  EXPECT_EQ(one.require("px_count_valid").integer(0, 100), 15);
  EXPECT_EQ(one.require("px_count_visib").integer(0, 100), 9);
  EXPECT_DOUBLE_EQ(one.require("visib_fract").number(), 0.6);
  // Object 2: 6 px, one without depth; not visible: its visible box is [−1, −1, −1, −1].
  EXPECT_EQ(two.require("px_count_all").integer(0, 100), 6);
  EXPECT_EQ(two.require("px_count_valid").integer(0, 100), 5);
  EXPECT_EQ(two.require("px_count_visib").integer(0, 100), 0);
  EXPECT_EQ(numbers(two.require("bbox_visib")), (std::vector<double>{-1, -1, -1, -1}));
  EXPECT_DOUBLE_EQ(two.require("visib_fract").number(), 0.0);

  // The mask PNGs: 8-bit 0/255 with the counts above.
  const PngImage mask = readPng(scene / "mask/000000_000000.png");
  ASSERT_EQ(mask.bitDepth, 8);
  int in = 0;
  for (std::uint16_t v : mask.samples) {
    EXPECT_TRUE(v == 0 || v == 255);
    in += v == 255;
  }
  EXPECT_EQ(in, 15);

  // models_info: the cube × 0.4 is 400 mm wide, its diameter 400·√3 mm; the ball's 500 mm.
  YamlMap models = json(tmp.path() / "bop/models/models_info.json");
  YamlMap cube(models.require("1")), ball(models.require("2"));
  EXPECT_NEAR(cube.require("size_x").number(), 400.0, 1e-6);
  EXPECT_NEAR(cube.require("min_y").number(), -200.0, 1e-6);
  EXPECT_NEAR(cube.require("diameter").number(), 400.0 * std::sqrt(3.0), 1e-6);
  EXPECT_NEAR(ball.require("diameter").number(), 500.0, 1e-6);
  const std::string ply = test::readFile(tmp.path() / "bop/models/obj_000001.ply");
  EXPECT_NE(ply.find("element vertex 8\n"), std::string::npos);
  EXPECT_NE(ply.find("element face 12\n"), std::string::npos);
  EXPECT_NE(ply.find("\n-200 -200 -200 "), std::string::npos) << ply.substr(0, 400);
}

// A capture without the amodal channels: no masks nor scene_gt_info.json, and a line says why.
TEST(BopWriter, WithoutTheAmodalAovTheMasksAreLeftOut) {
  test::TempDir tmp;
  CaptureResult r = handBuilt();
  Image depthOnly(kW, kH, {"depth.Z"});
  r.aovs = depthOnly;
  writePicture(tmp.path(), r.description.name);
  std::vector<std::string> skipped;
  (void)writeBop(r, PoseModels(r.description), tmp.path(), 0, &skipped);
  ASSERT_EQ(skipped.size(), 1u);
  EXPECT_NE(skipped[0].find("amodal_1.A"), std::string::npos) << skipped[0];
  const fs::path scene = tmp.path() / "bop/train_pbr/000000";
  EXPECT_TRUE(fs::is_regular_file(scene / "scene_gt.json"));
  EXPECT_FALSE(fs::exists(scene / "scene_gt_info.json"));
  EXPECT_FALSE(fs::exists(scene / "mask"));
}

// A sequence of two frames is one scene of two images (ids 0 and 1).
TEST(BopWriter, TwoFramesAreTwoImagesOfOneScene) {
  test::TempDir tmp;
  CaptureResult r = handBuilt();
  const PoseModels models(r.description);
  BopWriter writer(tmp.path(), 3, models);
  for (int k = 0; k < 2; ++k) {
    r.description.name = "bop_000" + std::to_string(k);
    writePicture(tmp.path(), r.description.name);
    (void)writer.addFrame(r, k);
  }
  (void)writer.finish();
  const fs::path scene = tmp.path() / "bop/train_pbr/000003";
  for (const char* f : {"scene_camera.json", "scene_gt.json", "scene_gt_info.json"}) {
    YamlMap j = json(scene / f);
    EXPECT_EQ(j.keys(), (std::vector<std::string>{"0", "1"})) << f;
  }
  EXPECT_TRUE(fs::is_regular_file(scene / "rgb/000001.png"));
  EXPECT_TRUE(fs::is_regular_file(scene / "mask_visib/000001_000001.png"));
}

TEST(BopWriter, DepthScaleHoldsTheLargestDepthIn16Bits) {
  EXPECT_DOUBLE_EQ(bopDepthScale(6553.0), 0.1);
  EXPECT_DOUBLE_EQ(bopDepthScale(6554.0), 1.0);
  EXPECT_DOUBLE_EQ(bopDepthScale(70000.0), 10.0);
  EXPECT_DOUBLE_EQ(bopDepthScale(0.0), 0.1);
}

// Two shapes of one class (obj_id) with different meshes cannot share a model: InputError
// at the scene's `exports`, naming both; the same mesh file at two places can.
TEST(BopWriter, OneObjIdNeedsOneModel) {
  SceneDescription d = twoObjects();
  d.shapes[1].classNumber = 1u;
  d.shapes[1].className = "1";
  try {
    checkPoseExports(d);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("bop.yaml:1"), std::string::npos) << m;
    EXPECT_NE(m.find("different models"), std::string::npos) << m;
  }
  SceneDescription twice = twoObjects();
  twice.shapes[1] = twice.shapes[0];
  twice.shapes[1].placement[3] = glm::dvec4(1.0, 2.0, 3.0, 1.0);
  EXPECT_NO_THROW(checkPoseExports(twice));
  EXPECT_EQ(PoseModels(twice).bop().size(), 1u);
}

// The run's model table: BOP's poses take each shape's obj_id model (the first shape's),
// KITTI's each shape's own box; both the boxes objectModel gives, an unlabelled shape none.
TEST(BopWriter, PoseModelsMapEveryShapeToItsObjIdsModelAndItsOwnBox) {
  SceneDescription d = twoObjects();
  d.shapes.push_back(d.shapes[0]);  // a second copy of the class-1 cube, placed elsewhere
  d.shapes[2].placement[3] = glm::dvec4(1.0, 2.0, 3.0, 1.0);
  d.shapes.push_back(d.shapes[1]);  // and an unlabelled ball
  d.shapes[3].classNumber.reset();
  d.shapes[3].className.clear();
  PoseModels models(d);
  ASSERT_EQ(models.bop().size(), 2u);
  EXPECT_EQ(models.bop()[0].objId, 1u);
  EXPECT_EQ(models.bop()[0].shape, 0u);
  EXPECT_EQ(models.bop()[1].objId, 2u);
  ASSERT_EQ(models.bopOfShape().size(), 4u);
  ASSERT_EQ(models.ownOfShape().size(), 4u);
  EXPECT_EQ(models.bopOfShape()[0], &models.bop()[0].model);
  EXPECT_EQ(models.bopOfShape()[1], &models.bop()[1].model);
  EXPECT_EQ(models.bopOfShape()[2], &models.bop()[0].model);
  EXPECT_EQ(models.bopOfShape()[3], nullptr);
  EXPECT_EQ(models.ownOfShape()[3], nullptr);
  for (std::size_t s = 0; s < 3; ++s) {
    const ObjectModel own = objectModel(d, s);
    ASSERT_NE(models.ownOfShape()[s], nullptr) << s;
    EXPECT_TRUE(models.ownOfShape()[s]->boxMin == own.boxMin) << s;
    EXPECT_TRUE(models.ownOfShape()[s]->boxMax == own.boxMax) << s;
    EXPECT_TRUE(models.ownOfShape()[s]->vertices.empty()) << s;  // the box alone
  }
  // Moved, the table still points into itself.
  const PoseModels moved(std::move(models));
  EXPECT_EQ(moved.bopOfShape()[2], &moved.bop()[0].model);
}

// `exports: [bop]` adds the AOVs its files are made of: depth, and amodal when a shape is
// labelled (a scene without one loads, with depth alone: no objects, no masks).
TEST(BopWriter, TheExportAddsTheDepthAndAmodalAovs) {
  const auto has = [](const SceneDescription& d, Aov a) {
    return std::find(d.render.aovs.begin(), d.render.aovs.end(), a) != d.render.aovs.end();
  };
  const SceneDescription d = twoObjects();
  ASSERT_EQ(d.exports.size(), 1u);
  EXPECT_TRUE(has(d, Aov::kDepth));
  EXPECT_TRUE(has(d, Aov::kAmodal));
  const SceneDescription none = loadSceneFromText(
      "exports: [bop]\n"
      "camera: {position: [0, 0, -3], look_at: [0, 0, 0], resolution: [8, 6]}\n"
      "materials: {m: {type: diffuse}}\n"
      "shapes: [{type: sphere, centre: [0, 0, 0], radius: 0.5, material: m}]\n",
      "unlabelled.yaml", ".");
  EXPECT_TRUE(has(none, Aov::kDepth));
  EXPECT_FALSE(has(none, Aov::kAmodal));
}

}  // namespace bop_writer_test
}  // namespace camsim
