// cameraExport (integrator/capture/camera_export.h): nerfstudio's camera_angle_x is the
// horizontal field across the image width through the model, also when the principal point
// lies off the image (found by probing: the two edges' unsigned angles were added, so cx =
// −20 px gave 87.9° for a 45.3° field). Closed forms for the pinhole: atan((x − cx)/fx).
#include "integrator/capture/camera_export.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "integrator/camera/physical_camera.h"
#include "integrator/scene/scene_loader.h"

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

}  // namespace
}  // namespace camsim
