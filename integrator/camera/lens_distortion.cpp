#include "integrator/camera/lens_distortion.h"

#include <cmath>

namespace camsim {

glm::dvec2 LensDistortion::distort(glm::dvec2 p) const {
  const double x = p.x, y = p.y, r2 = x * x + y * y;
  const double c = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {x * c + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
          y * c + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
}

bool LensDistortion::undistort(glm::dvec2 target, glm::dvec2& out) const {
  // Newton's method on F(p) = distort(p) − target with a numerical Jacobian.
  glm::dvec2 p = target;
  for (int iter = 0; iter < 50; ++iter) {
    const glm::dvec2 f = distort(p) - target;
    if (std::abs(f.x) < 1e-12 && std::abs(f.y) < 1e-12) break;
    constexpr double h = 1e-7;
    const glm::dvec2 dx =
        (distort(p + glm::dvec2(h, 0.0)) - distort(p - glm::dvec2(h, 0.0))) / (2.0 * h);
    const glm::dvec2 dy =
        (distort(p + glm::dvec2(0.0, h)) - distort(p - glm::dvec2(0.0, h))) / (2.0 * h);
    const double det = dx.x * dy.y - dy.x * dx.y;
    if (!(std::abs(det) > 1e-12)) return false;
    p -= glm::dvec2(dy.y * f.x - dy.x * f.y, -dx.y * f.x + dx.x * f.y) / det;
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
  }
  const glm::dvec2 residual = distort(p) - target;
  if (std::abs(residual.x) > 1e-7 || std::abs(residual.y) > 1e-7) return false;
  out = p;
  return true;
}

}  // namespace camsim
