// PoseProjector: PhysicalCamera::projectFrom at three poses at once, for the motion field
// (integrator/render/aov_film.h), which images every camera sample's hit at the previous,
// this and the next frame's reference time. The three poses are the lanes of one Double4
// (lane 3 repeats lane 1), so the three projections are one pass of vector arithmetic; the
// operations per lane are projectFrom's, in its order, so the result is the same bits as
// three projectFrom calls (tests/integrator/camera/pose_projector_test.cpp). projectFrom
// stays the scalar reference, and is what a distorted camera uses here.
//
//   c = R (p − o)        the point in OpenCV camera axes (x right, y down, z forward)
//   u = f_x c_x / c_z + c_x',  v = f_y c_y / c_z + c_y'   (pixels; none if c_z ≤ 0)
#pragma once

#include <array>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/camera/physical_camera.h"
#include "sensor/base/simd.h"

namespace camsim {

class PoseProjector {
 public:
  // The camera's projection (intrinsics, distortion) at the poses worldFromCamera[j].
  PoseProjector(const PhysicalCamera& camera, const std::array<glm::dmat4, 3>& worldFromCamera);

  // Where p[j] (render space, m) images at pose j, as projectFrom(worldFromCamera[j], p[j]);
  // false (out unchanged) if any of the three is on or behind the lens plane.
  bool project(const std::array<glm::dvec3, 3>& p, std::array<glm::dvec2, 3>& out) const;

 private:
  const PhysicalCamera* camera_;
  std::array<glm::dmat4, 3> poses_;
  bool distorted_;
  // Per lane (pose): the centre o, and the rows of R: the camera's x axis, y axis (negated
  // after the dot product, as cameraCvFromWorld does) and z axis, in world coordinates.
  Double4 o_[3], x_[3], y_[3], z_[3];
  Double4 fx_, fy_, cx_, cy_;
};

}  // namespace camsim
