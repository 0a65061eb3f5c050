#include "integrator/shape.h"

#include <algorithm>
#include <cmath>

#include "integrator/math.h"

namespace camsim {

InstanceMotion::InstanceMotion(int referenceStep, std::vector<glm::mat4> transforms)
    : reference(referenceStep), steps(std::move(transforms)) {
  for (const glm::mat4& m : steps)
    for (int axis = 0; axis < 3; ++axis) translation = std::max(translation, std::abs(m[3][axis]));
}

int InstanceMotion::largestStep(const std::vector<double>& sizes) {
  int ref = 0;
  for (int k = 1; k < static_cast<int>(sizes.size()); ++k)
    if (sizes[static_cast<size_t>(k)] > 1.001 * sizes[static_cast<size_t>(ref)]) ref = k;
  return ref;
}

float areaToSolidAnglePdf(float pdfArea, const glm::vec3& ref, const SurfaceInteraction& onShape) {
  const glm::vec3 d = onShape.p - ref;
  const float dist2 = lengthSquared(d);
  if (dist2 == 0.0f) return 0.0f;
  const float cosTheta = std::abs(glm::dot(onShape.n, d)) / std::sqrt(dist2);
  if (cosTheta == 0.0f) return 0.0f;
  return pdfArea * dist2 / cosTheta;
}

}  // namespace camsim
