// A sequence's camera metadata checked with the real clients: OpenCV's projectPoints
// (Debian's python3-opencv) puts rendered points back on their pixels with the exported K,
// distortion and poses; COLMAP's own model_converter reads the exported text model.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "sensor/io/exr_io.h"
#include "tests/support/run_command.h"
#include "tests/support/scene_text.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

using test::onPath;

// A wall 3 m away, the camera moving 20 cm sideways and turning 3° over 3 frames with a 1°
// shutter (no blur), lens distortion k1 = −0.05, p1 = 0.001; ground truth: position.
const char* kExportScene =
    "name: walk\n"
    "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [64, 48], "
    "sensor_width_mm: 36, sensor_height_mm: 27, focal_length_mm: 35,\n"
    "         distortion: {k1: -0.05, p1: 0.001},\n"
    "         motion: [{time: 0, translate: [0, 0, 0]}, {time: 0.2, translate: [0.2, 0, 0], "
    "rotate: {axis: [0, 1, 0], angle_deg: 3}}]}\n"
    "render: {spp: 64, max_depth: 1, aovs: [position]}\n"
    "frames: {count: 3, rate_hz: 10, shutter_angle_deg: 1}\n"
    "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
    "shapes:\n"
    "  - {type: rectangle, corner: [-5, -5, 3], edge_u: [0, 10, 0], edge_v: [10, 0, 0], "
    "material: grey}\n"
    "lights:\n  - {type: point, position: [0, 0, 0], intensity: 10}\n";

TEST(DatasetExport, OpenCvProjectsRenderedPointsOntoTheirPixels) {
  ASSERT_TRUE(onPath("/usr/bin/python3"));
  ASSERT_EQ(std::system("/usr/bin/python3 -c 'import cv2' 2>/dev/null"), 0)
      << "python3-opencv is not installed (Debian package python3-opencv; scripts/setup.sh)";
  test::TempDir dir;
  test::writeFile(dir.path() / "walk.yaml", kExportScene);
  const test::RunResult r =
      test::runCamsim("render " + test::quote((dir.path() / "walk.yaml").string()) + " -o " +
                          test::quote((dir.path() / "out").string()),
                      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // Points: each fully covered pixel's mean hit point, which the pixel's samples spread
  // evenly around its centre (OpenCV: pixel centres at integer coordinates).
  std::ofstream points(dir.path() / "points.csv");
  int n = 0;
  for (int k = 0; k < 3; ++k) {
    const ExrFile exr = readExr(dir.path() / "out" / ("walk_000" + std::to_string(k) + ".exr"));
    const Image& im = exr.image;
    for (int y = 2; y < im.height; y += 5)
      for (int x = 2; x < im.width; x += 5) {
        ASSERT_EQ(im.at(x, y, im.channelIndex("coverage.A")), 1.0f);
        points << k << "," << x << "," << y << "," << test::num(im.at(x, y, im.channelIndex("P.X")))
               << "," << test::num(im.at(x, y, im.channelIndex("P.Y"))) << ","
               << test::num(im.at(x, y, im.channelIndex("P.Z"))) << "\n";
        ++n;
      }
  }
  points.close();
  EXPECT_GT(n, 100);
  const test::RunResult check = test::runCommand(
      "/usr/bin/python3 " +
          test::quote(std::string(CAMSIM_SOURCE_DIR) + "/tests/cli/check_opencv_projection.py") +
          " " + test::quote((dir.path() / "out" / "cameras.json").string()) + " " +
          test::quote((dir.path() / "points.csv").string()) + " 0.05",
      dir.path());
  std::printf("%s", check.out.c_str());
  EXPECT_EQ(check.exitCode, 0) << check.out << check.err;

  // COLMAP reads the text model (and writes it back as binary).
  ASSERT_TRUE(onPath("colmap"))
      << "colmap is not installed (Debian package colmap; scripts/setup.sh)";
  std::filesystem::create_directories(dir.path() / "bin");
  const test::RunResult colmap = test::runCommand(
      "QT_QPA_PLATFORM=offscreen colmap model_converter --input_path " +
          test::quote((dir.path() / "out" / "colmap").string()) + " --output_path " +
          test::quote((dir.path() / "bin").string()) + " --output_type BIN",
      dir.path());
  EXPECT_EQ(colmap.exitCode, 0) << colmap.out << colmap.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "bin" / "images.bin"));
  const std::string transforms = test::readFile(dir.path() / "out" / "transforms.json");
  for (const char* key : {"\"fl_x\"", "\"cx\"", "\"k1\"", "\"p2\"", "\"transform_matrix\"",
                          "\"file_path\": \"walk_0002.png\""})
    EXPECT_NE(transforms.find(key), std::string::npos) << key;
}

// COCO annotations from the dominant instance ids: a ball (class "ball") rolling past a box
// (class 4) in front of an unlabelled wall, 2 frames; the masks, areas and boxes of
// annotations.json are checked against the EXRs' instance.id by tests/cli/check_coco.py.
TEST(DatasetExport, CocoMasksAndBoxesMatchTheInstanceIds) {
  ASSERT_EQ(std::system("/usr/bin/python3 -c 'import numpy' 2>/dev/null"), 0)
      << "python3-numpy is not installed (scripts/setup.sh)";
  test::TempDir dir;
  test::writeFile(
      dir.path() / "coco.yaml",
      "name: coco\n"
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [64, 48], "
      "sensor_width_mm: 36, sensor_height_mm: 27, focal_length_mm: 35}\n"
      "render: {spp: 16, max_depth: 1, aovs: [instance_id, class_id]}\n"
      "frames: {count: 2, rate_hz: 10, shutter_angle_deg: 10}\n"
      "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
      "shapes:\n"
      "  - {name: wall, type: rectangle, corner: [-5, -5, 3], edge_u: [0, 10, 0], edge_v: "
      "[10, 0, 0], material: grey}\n"
      "  - {name: crate, class: 4, type: mesh, vertices: [[-0.5, -0.3, 2], [-0.1, -0.3, 2], "
      "[-0.1, 0.2, 2], [-0.5, 0.2, 2]], faces: [[0, 1, 2, 3]], material: grey}\n"
      "  - {name: ball, class: ball, type: sphere, centre: [0.2, 0, 2.5], radius: 0.25, "
      "material: grey, motion: [{time: 0, translate: [0, 0, 0]}, {time: 0.2, translate: "
      "[-0.6, 0, 0]}]}\n"
      "lights:\n  - {type: point, position: [0, 0, 0], intensity: 10}\n");
  const test::RunResult r =
      test::runCamsim("render " + test::quote((dir.path() / "coco.yaml").string()) + " -o " +
                          test::quote((dir.path() / "out").string()),
                      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ofstream ids(dir.path() / "ids.txt");
  for (int k = 0; k < 2; ++k) {
    const Image im = readExr(dir.path() / "out" / ("coco_000" + std::to_string(k) + ".exr")).image;
    const int c = im.channelIndex("instance.id");
    ASSERT_GE(c, 0);
    for (int y = 0; y < im.height; ++y) {
      ids << k << " " << y;
      for (int x = 0; x < im.width; ++x) ids << " " << im.at(x, y, c);
      ids << "\n";
    }
  }
  ids.close();
  const test::RunResult check = test::runCommand(
      "/usr/bin/python3 " +
          test::quote(std::string(CAMSIM_SOURCE_DIR) + "/tests/cli/check_coco.py") + " " +
          test::quote((dir.path() / "out" / "annotations.json").string()) + " " +
          test::quote((dir.path() / "ids.txt").string()),
      dir.path());
  std::printf("%s", check.out.c_str());
  EXPECT_EQ(check.exitCode, 0) << check.out << check.err;
  const std::string coco = test::readFile(dir.path() / "out" / "annotations.json");
  EXPECT_NE(coco.find("\"name\": \"ball\""), std::string::npos);
  EXPECT_NE(coco.find("\"instance_name\": \"crate\""), std::string::npos);
  EXPECT_EQ(coco.find("\"instance_name\": \"wall\""), std::string::npos);  // unlabelled
}

}  // namespace
}  // namespace camsim
