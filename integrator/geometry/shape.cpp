#include "integrator/geometry/shape.h"

#include <algorithm>
#include <cmath>

#include "integrator/geometry/math.h"

namespace camsim {

InstanceMotion InstanceMotion::fromPoses(const std::vector<glm::dmat4>& poses) {
  InstanceMotion motion;
  if (poses.size() < 2) return motion;
  const auto scale = [](const glm::dmat4& m) { return glm::length(glm::dvec3(m[0])); };
  size_t ref = 0;
  for (size_t k = 1; k < poses.size(); ++k)
    if (scale(poses[k]) > 1.001 * scale(poses[ref])) ref = k;
  motion.reference = static_cast<int>(ref);
  const glm::dmat4 fromReference = glm::inverse(poses[ref]);
  for (const glm::dmat4& pose : poses) {
    motion.steps.emplace_back(pose * fromReference);
    for (int axis = 0; axis < 3; ++axis)
      motion.translation = std::max(motion.translation, std::abs(motion.steps.back()[3][axis]));
  }
  return motion;
}

}  // namespace camsim
