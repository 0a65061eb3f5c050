// cameraExport (integrator/capture/camera_export.h): nerfstudio's camera_angle_x is the
// horizontal field across the image width through the model, also when the principal point
// lies off the image (found by probing: the two edges' unsigned angles were added, so cx =
// −20 px gave 87.9° for a 45.3° field). Closed forms for the pinhole: atan((x − cx)/fx).
#include "integrator/capture/camera_export.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "integrator/camera/physical_camera.h"
#include "integrator/capture/dataset_writer.h"
#include "integrator/scene/scene_loader.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

double cameraAngleX(const std::string& projection) {
  const SceneDescription d = loadSceneFromText(
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [96, 64], projection: " +
          projection +
          "}\nshapes: [{type: sphere, centre: [0, 0, 3], radius: 1, emission: {luminance: 1}}]\n",
      "export.yaml", ".");
  return cameraExport(PhysicalCamera(d.camera)).cameraAngleX;
}

TEST(CameraExport, CameraAngleXIsTheFieldAcrossTheWidth) {
  // Pixel centres at integers: the width spans x from −0.5 to 95.5.
  const auto pinhole = [](double cx) {
    return std::atan((95.5 - cx) / 50.0) - std::atan((-0.5 - cx) / 50.0);
  };
  for (const double cx : {47.5, -20.0, 120.0, 10.0}) {
    const std::string block =
        "{model: opencv, fx: 50, fy: 50, cx: " + std::to_string(cx) + ", cy: 31.5}";
    EXPECT_NEAR(cameraAngleX(block), pinhole(cx), 1e-9) << block;
  }
  // The equidistant fisheye: θ = r / f, so the field is the width over fx wherever cx is.
  EXPECT_NEAR(cameraAngleX("{model: equidistant, fx: 50, fy: 50, cx: -20, cy: 31.5}"), 96.0 / 50.0,
              1e-9);
}

// A traced lens images through its prescription, whose distortion no tool's model holds
// (found by probing: the 10 mm fisheye was written to colmap/ and transforms.json as an
// undistorted pinhole, its points 14 px off on average, 90 px at the edge).
TEST(CameraExport, ATracedLensIsNoToolsModel) {
  const SceneDescription d = loadSceneFromText(
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [96, 64], "
      "sensor_width_mm: 36, sensor_height_mm: 24, lens: {file: dgauss.50mm.dat}}\n"
      "shapes: [{type: sphere, centre: [0, 0, 3], radius: 1, emission: {luminance: 1}}]\n",
      "lens.yaml", CAMSIM_SOURCE_DIR);
  const PhysicalCamera camera(d.camera);
  ASSERT_NE(camera.lensCamera(), nullptr);
  const CameraExport e = cameraExport(camera);
  EXPECT_TRUE(e.tracedLens);
  EXPECT_TRUE(e.colmapModel.empty());
  EXPECT_TRUE(e.nerfstudioModel.empty());
  EXPECT_NE(e.colmapLacks.find("traced lens"), std::string::npos) << e.colmapLacks;
  EXPECT_NE(cameraModelText(e).find("traced_lens"), std::string::npos);

  DatasetFrame frame;
  frame.image = "lens_0000.png";
  frame.camera = d.camera;
  const test::TempDir dir;
  std::vector<std::string> skipped;
  (void)writeDatasetMetadata({frame}, dir.path(), &skipped);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "colmap"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "transforms.json"));
  EXPECT_EQ(skipped.size(), 2U);
  const std::string cameras = test::readFile(dir.path() / "cameras.json");
  EXPECT_NE(cameras.find("\"traced_lens\": true"), std::string::npos) << cameras;
  EXPECT_NE(cameras.find("\"not_written\""), std::string::npos) << cameras;
}

}  // namespace
}  // namespace camsim
