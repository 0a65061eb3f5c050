// The projection models against the real OpenCV (Debian's python3-opencv 4.6, in double):
// cv2.projectPoints (rational + tangential + thin prism + tilt), cv2.fisheye.projectPoints
// (Kannala–Brandt, and the equidistant model as Kannala–Brandt with k = 0) and
// cv2.omnidir.projectPoints (Mei's unified model), through
// tests/integrator/camera/projection_opencv_check.py; and checkProjection's range checks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "integrator/camera/projection.h"
#include "sensor/base/input_error.h"
#include "tests/integrator/camera/projection_cases.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

std::string csvRow(const char* name, const Projection& p, glm::dvec3 d, glm::dvec2 px) {
  std::string row = name;
  for (double v : {p.fx, p.fy, p.cx, p.cy, p.k1,   p.k2,   p.k3, p.k4, p.k5, p.k6, p.p1, p.p2,
                   p.s1, p.s2, p.s3, p.s4, p.tauX, p.tauY, p.xi, d.x,  d.y,  d.z,  px.x, px.y}) {
    char buf[32];
    std::snprintf(buf, sizeof buf, ",%.17g", v);
    row += buf;
  }
  return row + "\n";
}

TEST(ProjectionOpenCv, RealOpenCvProjectsTheSamePixels) {
  ASSERT_EQ(std::system("/usr/bin/python3 -c 'import cv2' 2>/dev/null"), 0)
      << "python3-opencv is not installed (Debian package python3-opencv; scripts/setup.sh)";
  std::string csv;
  int rows = 0;
  for (const test::ProjectionCase& c : test::projectionCases()) {
    const ProjectionModel m = c.p.model;
    const int n = m == ProjectionModel::kOpenCv ? 40000 : 4000;  // the pinhole sees 1/20
    const bool omni = m == ProjectionModel::kUnified;
    if (m != ProjectionModel::kOpenCv && m != ProjectionModel::kKannalaBrandt &&
        m != ProjectionModel::kEquidistant && !omni)
      continue;
    for (int i = 0; i < n; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / n, s = std::sqrt(1.0 - z * z);
      const double phi = i * std::numbers::pi * (3.0 - std::sqrt(5.0));
      const glm::dvec3 d = 4.0 * glm::dvec3(s * std::cos(phi), s * std::sin(phi), z);
      // OpenCV's pinhole and fisheye take θ = atan(|X/Z, Y/Z|): only points in front.
      if (!omni && z <= 1e-3) continue;
      const std::optional<glm::dvec2> px = project(c.p, d);
      // Pixels on the image (far outside it the opencv rows would compare round-off of
      // pixel coordinates in the thousands).
      if (!px || px->x < -0.5 || px->y < -0.5 || px->x > c.size.x - 0.5 || px->y > c.size.y - 0.5)
        continue;
      csv += csvRow(c.name, c.p, d, *px);
      ++rows;
    }
  }
  ASSERT_GT(rows, 5000);
  test::TempDir dir;
  test::writeFile(dir.path() / "projections.csv", csv);
  const test::RunResult check =
      test::runCommand("/usr/bin/python3 " +
                           test::quote(std::string(CAMSIM_SOURCE_DIR) +
                                       "/tests/integrator/camera/projection_opencv_check.py") +
                           " " + test::quote((dir.path() / "projections.csv").string()) + " 1e-6",
                       dir.path());
  std::printf("%s", check.out.c_str());
  EXPECT_EQ(check.exitCode, 0) << check.out << check.err;
}

// The message and key of checkProjection's InputError for p, or "" when it passes.
std::string checkFailure(const Projection& p) {
  try {
    checkProjection(p, {}, "camera.projection");
  } catch (const InputError& e) {
    return e.key() + ": " + e.message();
  }
  return "";
}

TEST(ProjectionCheck, TypicalCamerasPassAndBadCoefficientsAreNamed) {
  for (const test::ProjectionCase& c : test::projectionCases()) {
    EXPECT_EQ(checkFailure(c.p), "") << c.name;
    // None of the typical lenses folds inside the field its tests cover.
    EXPECT_GE(limitedToFold(c.p).maxFieldAngle, c.testedFieldAngle) << c.name;
  }
  Projection p;
  p.fx = 0.0;
  EXPECT_EQ(checkFailure(p), "camera.projection.fx: value 0 px must be positive and finite");
  p = Projection{};
  p.k3 = NAN;
  EXPECT_EQ(checkFailure(p), "camera.projection.k3: must be a finite number");
  p = Projection{};
  p.maxFieldAngle = 4.0;
  EXPECT_NE(checkFailure(p).find("camera.projection.max_field_angle: value 4 rad is out of "
                                 "range (0, 3.14159265"),
            std::string::npos);
  p = Projection{};
  p.model = ProjectionModel::kDoubleSphere;
  p.alpha = 1.2;
  EXPECT_EQ(checkFailure(p), "camera.projection.alpha: value 1.2 is out of range [0, 1]");
  p.alpha = 0.5;
  p.xi = -1.5;
  EXPECT_EQ(checkFailure(p),
            "camera.projection.xi: value -1.5 is out of range (-1, 1] (ξ = −1 is singular: the "
            "axis maps to a circle)");
  p.xi = -1.0;  // singular (found by probing: a black frame or a ring, exit 0)
  EXPECT_NE(checkFailure(p), "");
  p.xi = -0.999;
  EXPECT_EQ(checkFailure(p), "");
  p.xi = -1.5;
  p.model = ProjectionModel::kUnified;
  EXPECT_EQ(checkFailure(p), "camera.projection.xi: value -1.5 must be ≥ 0");
  // A Kannala–Brandt polynomial that turns back inside the field: ρ'(θ) = 1 − 0.6 θ² is 0 at
  // θ = √(1/0.6) = 73.9685°.
  p = Projection{};
  p.model = ProjectionModel::kKannalaBrandt;
  p.k1 = -0.2;
  p.maxFieldAngle = 1.6;
  const std::string msg = checkFailure(p);
  EXPECT_NE(msg.find("camera.projection.k1: k1 … k4 make the radius ρ(θ) stop increasing at "
                     "field angle 73.9685°"),
            std::string::npos)
      << msg;
  p.maxFieldAngle = 1.25;  // 71.6°: fine
  EXPECT_EQ(checkFailure(p), "");
}

}  // namespace
}  // namespace camsim
