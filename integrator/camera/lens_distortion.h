// Brown–Conrady radial–tangential distortion in OpenCV's convention, so dataset users can
// reuse the intrinsics with cv::projectPoints / cv::undistortPoints.
//
// | parameter        | unit | default |
// |------------------|------|---------|
// | k1, k2, k3       | —    | 0       | radial coefficients |
// | p1, p2           | —    | 0       | tangential coefficients |
//
// In OpenCV's normalised camera coordinates (x right, y DOWN, z forward; x' = X/Z, y' = Y/Z):
//   r² = x'² + y'²,  c = 1 + k1 r² + k2 r⁴ + k3 r⁶
//   x'' = x' c + 2 p1 x'y' + p2 (r² + 2x'²)
//   y'' = y' c + p1 (r² + 2y'²) + 2 p2 x'y'
//   u = fx x'' + cx,  v = fy y'' + cy   with fx = f / pitch_x, fy = f / pitch_y,
//   cx = W/2 − ½, cy = H/2 − ½ (OpenCV puts pixel centres at integers).
// Rendering needs the inverse (pixel → ray): x' is found from x'' by fixed-point/Newton
// iteration to 1e-7.
#pragma once

#include <glm/vec2.hpp>

namespace camsim {

struct LensDistortion {
  double k1 = 0.0, k2 = 0.0, k3 = 0.0, p1 = 0.0, p2 = 0.0;

  bool isIdentity() const { return k1 == 0.0 && k2 == 0.0 && k3 == 0.0 && p1 == 0.0 && p2 == 0.0; }
  // Undistorted → distorted normalised coordinates (OpenCV's forward model).
  glm::dvec2 distort(glm::dvec2 p) const;
  // Distorted → undistorted; false if the iteration does not converge (outside the
  // model's invertible region).
  bool undistort(glm::dvec2 distorted, glm::dvec2& undistorted) const;
};

}  // namespace camsim
