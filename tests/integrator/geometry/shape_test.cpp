// Tests for integrator/geometry/shape.cpp: InstanceMotion::fromPoses — a moving shape is traced as
// its pose at the reference step (the first of the largest scale) under X_k = M_k·M_ref⁻¹.
#include "integrator/geometry/shape.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

namespace camsim {
namespace {

glm::dmat4 pose(double scale, const glm::dvec3& translation, double degreesAboutZ) {
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), translation);
  m = glm::rotate(m, glm::radians(degreesAboutZ), glm::dvec3(0.0, 0.0, 1.0));
  return glm::scale(m, glm::dvec3(scale));
}

void expectNear(const glm::dmat4& a, const glm::dmat4& b, double tolerance) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], tolerance) << c << "," << r;
}

TEST(InstanceMotion, FewerThanTwoPosesAreStatic) {
  EXPECT_TRUE(InstanceMotion::fromPoses({}).empty());
  EXPECT_TRUE(InstanceMotion::fromPoses({pose(2.0, {1, 2, 3}, 30)}).empty());
}

TEST(InstanceMotion, StepsCarryTheReferencePoseToEachPose) {
  const std::vector<glm::dmat4> poses = {pose(1.0, {0, 0, 0}, 0), pose(3.0, {1, -4, 2}, 40),
                                         pose(2.0, {-2, 0, 5}, 90)};
  const InstanceMotion motion = InstanceMotion::fromPoses(poses);
  ASSERT_EQ(motion.steps.size(), 3u);
  EXPECT_EQ(motion.reference, 1);  // the largest scale
  for (size_t k = 0; k < poses.size(); ++k)
    expectNear(glm::dmat4(motion.steps[k]) * poses[1], poses[k], 1e-5);
  expectNear(glm::dmat4(motion.steps[1]), glm::dmat4(1.0), 1e-6);
  // The largest |translation component| of the steps X_k (not of the poses).
  float largest = 0.0f;
  for (const glm::mat4& x : motion.steps)
    for (int axis = 0; axis < 3; ++axis) largest = std::max(largest, std::abs(x[3][axis]));
  EXPECT_GT(largest, 0.0f);
  EXPECT_EQ(motion.translation, largest);
}

TEST(InstanceMotion, ARigidMotionKeepsItsFirstPoseAsReferenceDespiteRounding) {
  // Scales equal but for rounding, and one larger by less than 0.1 %: still the first.
  const InstanceMotion rigid = InstanceMotion::fromPoses(
      {pose(1.0, {0, 0, 0}, 0), pose(1.0 + 1e-12, {1, 0, 0}, 10), pose(1.0009, {2, 0, 0}, 20)});
  EXPECT_EQ(rigid.reference, 0);
  // Larger by more than 0.1 %: that one.
  EXPECT_EQ(InstanceMotion::fromPoses({pose(1.0, {}, 0), pose(1.0011, {}, 0)}).reference, 1);
}

}  // namespace
}  // namespace camsim
