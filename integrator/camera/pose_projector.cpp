#include "integrator/camera/pose_projector.h"

namespace camsim {
namespace {

// Lanes 0–2 from the three poses, lane 3 a copy of lane 1 (a valid pose, so it never
// divides by zero). (Written through a reference: a Double4 by value changes the x86-64 ABI
// without AVX.)
void setLanes(Double4& out, const std::array<glm::dmat4, 3>& m, int column, int row) {
  out = Double4{m[0][column][row], m[1][column][row], m[2][column][row], m[1][column][row]};
}

}  // namespace

PoseProjector::PoseProjector(const PhysicalCamera& camera,
                             const std::array<glm::dmat4, 3>& worldFromCamera)
    : camera_(&camera), poses_(worldFromCamera),
      distorted_(!camera.params().distortion.isIdentity()) {
  for (int i = 0; i < 3; ++i) {
    setLanes(o_[i], worldFromCamera, 3, i);
    setLanes(x_[i], worldFromCamera, 0, i);
    setLanes(y_[i], worldFromCamera, 1, i);
    setLanes(z_[i], worldFromCamera, 2, i);
  }
  const glm::dvec4& k = camera.intrinsics();
  fx_ = Double4{k.x, k.x, k.x, k.x};
  fy_ = Double4{k.y, k.y, k.y, k.y};
  cx_ = Double4{k.z, k.z, k.z, k.z};
  cy_ = Double4{k.w, k.w, k.w, k.w};
}

bool PoseProjector::project(const std::array<glm::dvec3, 3>& p,
                            std::array<glm::dvec2, 3>& out) const {
  if (distorted_) {  // the scalar reference: OpenCV's distortion per point
    std::array<glm::dvec2, 3> q;
    for (std::size_t j = 0; j < 3; ++j) {
      const std::optional<glm::dvec2> r = camera_->projectFrom(poses_[j], p[j]);
      if (!r) return false;
      q[j] = *r;
    }
    out = q;
    return true;
  }
  // v = p − o per lane; c = (v·x, −(v·y), v·z) with glm::dot's order (x, then y, then z).
  const Double4 vx = Double4{p[0].x, p[1].x, p[2].x, p[1].x} - o_[0];
  const Double4 vy = Double4{p[0].y, p[1].y, p[2].y, p[1].y} - o_[1];
  const Double4 vz = Double4{p[0].z, p[1].z, p[2].z, p[1].z} - o_[2];
  const Double4 cx = vx * x_[0] + vy * x_[1] + vz * x_[2];
  const Double4 cy = -(vx * y_[0] + vy * y_[1] + vz * y_[2]);
  const Double4 cz = vx * z_[0] + vy * z_[1] + vz * z_[2];
  if (!(cz[0] > 0.0 && cz[1] > 0.0 && cz[2] > 0.0)) return false;
  const Double4 u = fx_ * (cx / cz) + cx_;
  const Double4 v = fy_ * (cy / cz) + cy_;
  for (std::size_t j = 0; j < 3; ++j) out[j] = glm::dvec2(u[j], v[j]);
  return true;
}

}  // namespace camsim
