// Test helper: the exact mean pinhole measurement weight of a pixel,
//   W̄ = A_pixel · T_eff · A_ap / z_i² · mean over the photosite of cos⁴θ,
// integrated numerically (n×n midpoint rule), to turn radiance expectations into the
// film's energy units.
#pragma once

#include "integrator/camera/physical_camera.h"

namespace camsim {

inline double meanPinholeWeight(const PhysicalCamera& camera, int px, int py, int n = 64) {
  const PhysicalCameraParams& p = camera.params();
  const double zi = camera.imageDistance();
  double sum = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = ((px + (i + 0.5) / n) / p.resolution.x - 0.5) * p.sensorSize.x;
      const double y = ((py + (j + 0.5) / n) / p.resolution.y - 0.5) * p.sensorSize.y;
      const double d2 = x * x + y * y + zi * zi;
      sum += zi * zi * zi * zi / (d2 * d2);
    }
  return camera.pixelArea() * p.shutter.effectiveTime() * camera.apertureArea() / (zi * zi) * sum /
         (n * n);
}

}  // namespace camsim
