// Ray: origin (m), direction (not necessarily unit; t is in units of |d|), the parametric
// extent [0, tMax], and the time (s) at which it samples the scene.
#pragma once

#include <limits>

#include <glm/vec3.hpp>

namespace camsim {

struct Ray {
  glm::vec3 o{0.0f};
  glm::vec3 d{0.0f, 0.0f, 1.0f};
  float tMax = std::numeric_limits<float>::infinity();
  double time = 0.0;  // s, absolute (double: a 1 µs shutter at t = 1e6 s keeps its resolution)

  glm::vec3 at(float t) const { return o + t * d; }
};

}  // namespace camsim
