// PoseProjector (integrator/camera/pose_projector.h) against its scalar reference,
// PhysicalCamera::projectFrom: motion vectors of the same bits for points around a turning,
// moving camera, with and without lens distortion; points behind the lens at any pose and
// lanes past the count left out.
#include "integrator/camera/pose_projector.h"

#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

namespace camsim {
namespace {

std::array<glm::dmat4, 3> turningPoses() {
  std::array<glm::dmat4, 3> m;
  for (int j = 0; j < 3; ++j) {
    glm::dmat4 r =
        glm::rotate(glm::dmat4(1.0), 0.05 * (j - 1), glm::normalize(glm::dvec3(0.2, 1.0, 0.1)));
    r[3] = glm::dvec4(0.3 * j - 0.2, 1.1 + 0.01 * j, -2.0 + 0.07 * j, 1.0);
    m[static_cast<std::size_t>(j)] = r;
  }
  return m;
}

PhysicalCamera cameraWith(double k1) {
  PhysicalCameraParams c;
  c.resolution = {360, 240};
  c.focalLength = 0.035;
  c.projection.k1 = k1;
  c.projection.p2 = k1 * 0.1;
  return PhysicalCamera(c);
}

void expectSameAsProjectFrom(const PhysicalCamera& camera) {
  const std::array<glm::dmat4, 3> poses = turningPoses();
  const PoseProjector projector(camera, poses);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int projected = 0, behind = 0;
  for (int n = 0; n < 500; ++n) {
    // Four points (lanes), each a little apart at the three poses (a moving hit).
    PosePoints p;
    for (int lane = 0; lane < 4; ++lane) {
      const glm::dvec3 base(3.0 * u(rng), 3.0 * u(rng), 4.0 * u(rng));
      for (std::size_t j = 0; j < 3; ++j) {
        p.x[j][lane] = base.x + 0.02 * u(rng);
        p.y[j][lane] = base.y + 0.02 * u(rng);
        p.z[j][lane] = base.z + 0.02 * u(rng);
      }
    }
    const int lanes = 1 + n % 4;
    MotionVectorSums sums{};
    Long4 front;
    projector.addMotionVectors(p, lanes, sums, front);
    for (int lane = 0; lane < 4; ++lane) {
      bool all = lane < lanes;
      std::array<glm::dvec2, 3> r;
      for (std::size_t j = 0; j < 3 && all; ++j) {
        const std::optional<glm::dvec2> q =
            camera.projectFrom(poses[j], glm::dvec3(p.x[j][lane], p.y[j][lane], p.z[j][lane]));
        all = q.has_value();
        if (all) r[j] = *q;
      }
      EXPECT_EQ(front[lane] != 0, all) << "point " << n << " lane " << lane;
      EXPECT_EQ(sums.count[lane], all ? 1.0 : 0.0) << "point " << n << " lane " << lane;
      if (all) {
        EXPECT_EQ(sums.fwx[lane], r[2].x - r[1].x) << "point " << n << " lane " << lane;
        EXPECT_EQ(sums.fwy[lane], r[2].y - r[1].y) << "point " << n << " lane " << lane;
        EXPECT_EQ(sums.bwx[lane], r[0].x - r[1].x) << "point " << n << " lane " << lane;
        EXPECT_EQ(sums.bwy[lane], r[0].y - r[1].y) << "point " << n << " lane " << lane;
        ++projected;
      } else {
        EXPECT_EQ(sums.fwx[lane], 0.0);
        EXPECT_EQ(sums.bwy[lane], 0.0);
        ++behind;
      }
    }
  }
  // Both branches were exercised.
  EXPECT_GT(projected, 200);
  EXPECT_GT(behind, 200);
}

TEST(PoseProjector, SameBitsAsProjectFromAtEachPose) {
  expectSameAsProjectFrom(cameraWith(0.0));
}

TEST(PoseProjector, DistortedCameraSameAsProjectFrom) {
  expectSameAsProjectFrom(cameraWith(-0.12));
}

}  // namespace
}  // namespace camsim
