// PoseProjector (integrator/camera/pose_projector.h) against its scalar reference,
// PhysicalCamera::projectFrom: the same bits for points around a turning, moving camera,
// with and without lens distortion, and the same answer (none) for points behind the lens.
#include "integrator/camera/pose_projector.h"

#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

namespace camsim {
namespace {

std::array<glm::dmat4, 3> turningPoses() {
  std::array<glm::dmat4, 3> m;
  for (int j = 0; j < 3; ++j) {
    glm::dmat4 r = glm::rotate(glm::dmat4(1.0), 0.05 * (j - 1), glm::normalize(glm::dvec3(0.2, 1.0, 0.1)));
    r[3] = glm::dvec4(0.3 * j - 0.2, 1.1 + 0.01 * j, -2.0 + 0.07 * j, 1.0);
    m[static_cast<std::size_t>(j)] = r;
  }
  return m;
}

PhysicalCamera cameraWith(double k1) {
  PhysicalCameraParams c;
  c.resolution = {360, 240};
  c.focalLength = 0.035;
  c.distortion.k1 = k1;
  c.distortion.p2 = k1 * 0.1;
  return PhysicalCamera(c);
}

void expectSameAsProjectFrom(const PhysicalCamera& camera) {
  const std::array<glm::dmat4, 3> poses = turningPoses();
  const PoseProjector projector(camera, poses);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int projected = 0, behind = 0;
  for (int n = 0; n < 2000; ++n) {
    const glm::dvec3 base(3.0 * u(rng), 3.0 * u(rng), 4.0 * u(rng));
    std::array<glm::dvec3, 3> p;
    for (std::size_t j = 0; j < 3; ++j) p[j] = base + 0.02 * glm::dvec3(u(rng), u(rng), u(rng));
    std::array<glm::dvec2, 3> q{};
    const bool ok = projector.project(p, q);
    bool all = true;
    for (std::size_t j = 0; j < 3; ++j) {
      const std::optional<glm::dvec2> r = camera.projectFrom(poses[j], p[j]);
      if (!r) {
        all = false;
        continue;
      }
      if (ok) {
        EXPECT_EQ(q[j].x, r->x) << "point " << n << " pose " << j;
        EXPECT_EQ(q[j].y, r->y) << "point " << n << " pose " << j;
      }
    }
    EXPECT_EQ(ok, all) << "point " << n;
    (ok ? projected : behind) += 1;
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
