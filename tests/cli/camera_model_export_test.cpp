// Every camera model's export checked with the real library (issue 36): a room rendered
// through the model with the position AOV, and each fully covered pixel's mean hit point
// projected with the model and intrinsics cameras.json exports — by cv2.projectPoints
// (opencv: rational, thin prism, tilt), cv2.fisheye.projectPoints (kannala_brandt),
// cv2.omnidir.projectPoints (unified) and the published closed forms for the others
// (tests/cli/check_camera_models.py) — lands on the pixel's centre within 0.01 px over the
// whole valid image, the fisheyes out to 100° from the axis (a 200° field, walls behind the
// camera). The mean of a pixel's samples on a plane is the plane point of the pixel centre
// up to the mapping's curvature across the pixel (second order), so only pixels whose mean
// lies on a wall (not across an edge of the room) and whose neighbours are all covered
// (not across the image circle's rim) are used.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include "sensor/io/exr_io.h"
#include "tests/support/run_command.h"
#include "tests/support/scene_text.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

using test::onPath;

struct ModelCase {
  const char* name;
  const char* resolution;
  const char* projection;  // the camera.projection block
  const char* colmap;      // COLMAP's model, or "" where it has none (colmap/ left out)
  const char* nerfstudio;  // transforms.json's camera_model, or "" (left out)
};

// fx 24-60 px per radian puts 100° about 54 px from the centre of a 128 × 128 image.
const ModelCase kCases[] = {
    {"opencv", "[128, 96]",
     "{model: opencv, k1: -0.08, k2: 0.01, p1: 0.001, p2: -0.0005, k3: 0.002, k4: 0.05, k5: 0.01, "
     "k6: 0.002, s1: 0.002, s2: -0.001, s3: 0.001, s4: 0.0005, tau_x: 0.01, tau_y: -0.008}",
     "", ""},
    {"kannala_brandt", "[128, 128]",
     "{model: kannala_brandt, k1: 0.02, k2: -0.003, k3: 0.0005, k4: -0.00005, "
     "max_field_angle_deg: 100, fx: 32, fy: 33, cx: 63.5, cy: 63.5}",
     "OPENCV_FISHEYE", "OPENCV_FISHEYE"},
    {"equidistant", "[128, 128]",
     "{model: equidistant, max_field_angle_deg: 100, fx: 32, fy: 32, cx: 63.5, cy: 63.5}",
     "OPENCV_FISHEYE", "OPENCV_FISHEYE"},
    {"equisolid", "[128, 128]",
     "{model: equisolid, max_field_angle_deg: 100, fx: 36, fy: 36, cx: 63.5, cy: 63.5}", "", ""},
    {"stereographic", "[128, 128]",
     "{model: stereographic, max_field_angle_deg: 100, fx: 24, fy: 24, cx: 63.5, cy: 63.5}", "",
     ""},
    {"orthographic", "[128, 128]",
     "{model: orthographic, max_field_angle_deg: 75, fx: 60, fy: 60, cx: 63.5, cy: 63.5}", "", ""},
    {"ftheta", "[128, 128]",
     "{model: ftheta, k1: 0.01, k2: -0.02, k3: 0.003, k4: -0.0005, max_field_angle_deg: 100, "
     "fx: 32, fy: 32, cx: 63.5, cy: 63.5}",
     "", ""},
    {"unified", "[128, 128]",
     "{model: unified, xi: 0.8, k1: -0.05, k2: 0.01, p1: 0.001, p2: -0.001, "
     "max_field_angle_deg: 100, fx: 36, fy: 36, cx: 63.5, cy: 63.5}",
     "", ""},
    {"double_sphere", "[128, 128]",
     "{model: double_sphere, xi: -0.2, alpha: 0.6, max_field_angle_deg: 100, fx: 26, fy: 26, "
     "cx: 63.5, cy: 63.5}",
     "", ""},
    {"equirectangular", "[128, 64]", "{model: equirectangular}", "", "EQUIRECTANGULAR"},
};

// A closed room around the camera (x −2 … 2.3, y −1.5 … 1.4, z −1.7 … 2.5 m): every
// direction hits a wall, those behind the camera too.
const double kRoom[2][3] = {{-2.0, -1.5, -1.7}, {2.3, 1.4, 2.5}};

std::string roomScene(const ModelCase& c) {
  std::string s =
      std::string("name: room\n") +
      "camera: {position: [0, 0, 0], look_at: [0.1, 0.05, 1], resolution: " + c.resolution +
      ", sensor_width_mm: 36, sensor_height_mm: 27, focal_length_mm: 20,\n"
      "         projection: " +
      c.projection +
      "}\n"
      "render: {spp: 64, max_depth: 1, aovs: [position]}\n"
      "frames: {count: 1, rate_hz: 10, shutter_angle_deg: 1}\n"
      "materials: {grey: {type: diffuse, reflectance: 0.5}}\nshapes:\n";
  const auto v = [](double x, double y, double z) {
    return "[" + test::num(x) + ", " + test::num(y) + ", " + test::num(z) + "]";
  };
  const double(&a)[3] = kRoom[0];
  const double(&b)[3] = kRoom[1];
  const std::string walls[6][3] = {
      {v(a[0], a[1], b[2]), v(b[0] - a[0], 0, 0), v(0, b[1] - a[1], 0)},
      {v(a[0], a[1], a[2]), v(0, b[1] - a[1], 0), v(b[0] - a[0], 0, 0)},
      {v(a[0], a[1], a[2]), v(0, 0, b[2] - a[2]), v(0, b[1] - a[1], 0)},
      {v(b[0], a[1], a[2]), v(0, b[1] - a[1], 0), v(0, 0, b[2] - a[2])},
      {v(a[0], a[1], a[2]), v(b[0] - a[0], 0, 0), v(0, 0, b[2] - a[2])},
      {v(a[0], b[1], a[2]), v(0, 0, b[2] - a[2]), v(b[0] - a[0], 0, 0)}};
  for (const auto& w : walls)
    s += "  - {type: rectangle, corner: " + w[0] + ", edge_u: " + w[1] + ", edge_v: " + w[2] +
         ", material: grey}\n";
  return s + "lights:\n  - {type: point, position: [0, 0, 0], intensity: 10}\n";
}

// Whether p lies on one of the room's walls (the mean of samples across an edge does not).
bool onAWall(const double p[3]) {
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
      if (std::abs(p[axis] - kRoom[side][axis]) < 2e-6) return true;
  return false;
}

class CameraModelExport : public testing::TestWithParam<ModelCase> {};

TEST_P(CameraModelExport, RealLibraryProjectsRenderedPointsOntoTheirPixelCentres) {
  ASSERT_EQ(std::system("/usr/bin/python3 -c 'import cv2' 2>/dev/null"), 0)
      << "python3-opencv is not installed (Debian package python3-opencv; scripts/setup.sh)";
  const ModelCase& c = GetParam();
  test::TempDir dir;
  test::writeFile(dir.path() / "room.yaml", roomScene(c));
  const test::RunResult r =
      test::runCamsim("render " + test::quote((dir.path() / "room.yaml").string()) + " -o " +
                          test::quote((dir.path() / "out").string()),
                      dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Image im = readExr(dir.path() / "out" / "room_0000.exr").image;
  const int cov = im.channelIndex("coverage.A"), px = im.channelIndex("P.X");
  ASSERT_GE(px, 0);
  const auto covered = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < im.width && y < im.height && im.at(x, y, cov) == 1.0f;
  };
  std::ofstream points(dir.path() / "points.csv");
  int n = 0, unimaged = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      bool inside = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) inside = inside && covered(x + dx, y + dy);
      // The equirectangular image wraps: its left and right columns are neighbours.
      if (std::string(c.name) == "equirectangular")
        inside = covered(x, y) && y > 0 && y + 1 < im.height;
      if (!covered(x, y)) ++unimaged;
      const double p[3] = {im.at(x, y, px), im.at(x, y, px + 1), im.at(x, y, px + 2)};
      if (!inside || !onAWall(p)) continue;
      points << "0," << x << "," << y << "," << test::num(p[0]) << "," << test::num(p[1]) << ","
             << test::num(p[2]) << "\n";
      ++n;
    }
  points.close();
  std::printf("%s: %d of %d pixels on a wall (%d unimaged)\n", c.name, n, im.width * im.height,
              unimaged);
  EXPECT_GT(n, im.width * im.height / 3);
  const test::RunResult check = test::runCommand(
      "/usr/bin/python3 " +
          test::quote(std::string(CAMSIM_SOURCE_DIR) + "/tests/cli/check_camera_models.py") + " " +
          test::quote((dir.path() / "out" / "cameras.json").string()) + " " +
          test::quote((dir.path() / "points.csv").string()) + " 0.01",
      dir.path());
  std::printf("%s", check.out.c_str());
  EXPECT_EQ(check.exitCode, 0) << check.out << check.err;
  const std::string cameras = test::readFile(dir.path() / "out" / "cameras.json");
  EXPECT_NE(cameras.find("\"model\": \"" + std::string(c.name) + "\""), std::string::npos);

  // The tools' model names; an export the tool cannot express is left out and named.
  const std::string log = r.out + r.err;
  const std::filesystem::path colmap = dir.path() / "out" / "colmap" / "cameras.txt";
  if (*c.colmap) {
    EXPECT_NE(test::readFile(colmap).find(std::string(" ") + c.colmap + " "), std::string::npos);
  } else {
    EXPECT_FALSE(std::filesystem::exists(colmap));
    EXPECT_NE(log.find("colmap/ not written: COLMAP has no"), std::string::npos) << log;
    EXPECT_NE(cameras.find("\"not_written\""), std::string::npos);
  }
  const std::filesystem::path transforms = dir.path() / "out" / "transforms.json";
  if (*c.nerfstudio) {
    const std::string t = test::readFile(transforms);
    EXPECT_NE(t.find(std::string("\"camera_model\": \"") + c.nerfstudio + "\""), std::string::npos);
    // camera_angle_x: the field across the width through the model; the equidistant
    // fisheye's image circle (100°) ends inside the width (±64 px = ±2 rad at 32 px/rad),
    // the panorama spans 2π.
    const std::size_t at = t.find("\"camera_angle_x\": ");
    ASSERT_NE(at, std::string::npos);
    const double angle = std::stod(t.substr(at + 18));
    const std::string name = c.name;
    if (name == "equidistant") {
      EXPECT_NEAR(angle, 2.0 * 100.0 * std::numbers::pi / 180.0, 1e-9);
    }
    if (name == "equirectangular") {
      EXPECT_NEAR(angle, 2.0 * std::numbers::pi, 1e-12);
    }
  } else {
    EXPECT_FALSE(std::filesystem::exists(transforms));
    EXPECT_NE(log.find("transforms.json not written: nerfstudio"), std::string::npos) << log;
  }
}

INSTANTIATE_TEST_SUITE_P(EveryModel, CameraModelExport, testing::ValuesIn(kCases),
                         [](const testing::TestParamInfo<ModelCase>& param) {
                           return std::string(param.param.name);
                         });

}  // namespace
}  // namespace camsim
