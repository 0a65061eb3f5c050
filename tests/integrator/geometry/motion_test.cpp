// RigidMotion: keyframes hold exactly, translation interpolates linearly, rotation by
// slerp (constant angular speed), end poses hold outside the keys.
#include <gtest/gtest.h>

#include <cmath>

#include "integrator/geometry/motion.h"

namespace camsim {
namespace {

TEST(RigidMotion, InterpolatesTranslationLinearlyAndRotationBySlerp) {
  Keyframe a, b;
  a.time = 0.0;
  b.time = 2.0;
  b.translate = {2.0, 0.0, -4.0};
  b.rotate = glm::angleAxis(glm::radians(90.0), glm::dvec3(0.0, 0.0, 1.0));
  b.scale = 3.0;
  const RigidMotion m({a, b});
  const glm::dvec4 x(1.0, 0.0, 0.0, 1.0);
  // t = 0.5: 22.5° about z, scale 1.5, translation (0.5, 0, −1).
  const glm::dvec4 p = m.at(0.5) * x;
  const double angle = glm::radians(22.5);
  EXPECT_NEAR(p.x, 0.5 + 1.5 * std::cos(angle), 1e-12);
  EXPECT_NEAR(p.y, 1.5 * std::sin(angle), 1e-12);
  EXPECT_NEAR(p.z, -1.0, 1e-12);
  EXPECT_NEAR((m.at(-1.0) * x).x, 1.0, 1e-12);  // before the first key: first pose
  EXPECT_NEAR((m.at(5.0) * x).y, 3.0, 1e-12);   // after the last: last pose (90°, scale 3)
  EXPECT_FALSE(m.isStaticDuring(0.0, 1.0));
  EXPECT_TRUE(m.isStaticDuring(2.5, 3.0));
  EXPECT_NEAR(m.rotationAngleDuring(0.0, 2.0), M_PI / 2.0, 1e-9);
  EXPECT_NEAR(m.rotationAngleDuring(0.0, 1.0), M_PI / 4.0, 1e-9);
}

}  // namespace
}  // namespace camsim
