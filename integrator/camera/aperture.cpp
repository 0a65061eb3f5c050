#include "integrator/camera/aperture.h"

#include <algorithm>
#include <cmath>

#include "integrator/geometry/math.h"
#include "sensor/base/check.h"

namespace camsim {

Aperture::Aperture(double diameter, int blades, double rotation)
    : blades_(blades), rotation_(rotation) {
  CAMSIM_CHECK(diameter > 0.0 && (blades == 0 || blades >= 3));
  const double circleArea = M_PI * 0.25 * diameter * diameter;
  area_ = circleArea;
  radius_ = blades == 0 ? 0.5 * diameter
                        : std::sqrt(2.0 * circleArea / (blades * std::sin(2.0 * M_PI / blades)));
}

glm::vec2 Aperture::sample(glm::vec2 u) const {
  if (blades_ == 0) return static_cast<float>(radius_) * sampleUniformDiskConcentric(u);
  // Pick one of the N equal triangles (centre, v_k, v_{k+1}), then a uniform point in it.
  const float scaled = u.x * static_cast<float>(blades_);
  const int k = std::min(static_cast<int>(scaled), blades_ - 1);
  const glm::vec2 b = sampleUniformTriangle({scaled - static_cast<float>(k), u.y});
  const double a0 = rotation_ + 2.0 * M_PI * k / blades_,
               a1 = rotation_ + 2.0 * M_PI * (k + 1) / blades_;
  const glm::vec2 v0(static_cast<float>(radius_ * std::cos(a0)),
                     static_cast<float>(radius_ * std::sin(a0)));
  const glm::vec2 v1(static_cast<float>(radius_ * std::cos(a1)),
                     static_cast<float>(radius_ * std::sin(a1)));
  return b.y * v0 + (1.0f - b.x - b.y) * v1;  // the centre has weight b.x
}

}  // namespace camsim
