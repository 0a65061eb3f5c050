// PoseProjector: PhysicalCamera::projectFrom at three poses for four points at once, for the
// motion field (integrator/render/aov_film.h), which images every camera sample's hit at the
// previous, this and the next frame's reference time and sums the differences. The four
// points are the lanes of Double4s, so twelve projections are one pass of vector arithmetic
// (whole AVX registers on CPUs that have AVX2, two SSE2 halves otherwise); each lane does
// projectFrom's operations in its order, so each image is the same bits as a projectFrom
// call (tests/integrator/camera/pose_projector_test.cpp). projectFrom stays the scalar
// reference, and is what any camera but the ideal pinhole uses here.
//
//   c = R (p − o)        the point in OpenCV camera axes (x right, y down, z forward)
//   u = f_x c_x / c_z + c_x',  v = f_y c_y / c_z + c_y'   (pixels; none if c_z ≤ 0)
#pragma once

#include <array>

#include <glm/mat4x4.hpp>

#include "integrator/camera/physical_camera.h"
#include "sensor/base/simd.h"

namespace camsim {

// Four points (lanes), each at the three poses (render space, m).
struct PosePoints {
  std::array<Double4, 3> x, y, z;  // [pose]
};

// Motion vectors summed per lane: of the points in front of the lens at all three poses,
// the count and Σ (image at pose 2 − at pose 1), Σ (image at pose 0 − at pose 1) (pixels).
struct MotionVectorSums {
  Double4 count, fwx, fwy, bwx, bwy;
};

class PoseProjector {
 public:
  // The camera model (intrinsics, projection) at the poses worldFromCamera[j].
  PoseProjector(const PhysicalCamera& camera, const std::array<glm::dmat4, 3>& worldFromCamera);

  // Adds the motion vectors of the first `lanes` points to `sums` (lane by lane); `front`:
  // which lanes were in front of the lens at all three poses (−1) or not (0; not added).
  // Each image is projectFrom's, bit for bit.
  void addMotionVectors(const PosePoints& p, int lanes, MotionVectorSums& sums, Long4& front) const;

  // Each pose's centre o and the rows of R (the camera's x, y and z axes in world
  // coordinates; the y row's dot product is negated, as cameraCvFromWorld does), and the
  // intrinsics: the kernel's constants.
  struct Pose {
    double o[3], x[3], y[3], z[3];
  };

 private:
  const PhysicalCamera* camera_;
  std::array<glm::dmat4, 3> poses_;
  std::array<Pose, 3> pose_;
  double k_[4];  // f_x, f_y, c_x', c_y' (PhysicalCamera::intrinsics)
  bool avx2_;    // simd::cpuHasAvx2()
};

}  // namespace camsim
