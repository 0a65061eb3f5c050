// RigidMotion: keyframed rigid transforms (translation, rotation, uniform scale) of an
// object or the camera over time.
//
// | keyframe field | unit | meaning |
// |----------------|------|---------|
// | time           | s    | when the pose holds |
// | translate      | m    | translation |
// | rotate         | deg  | axis–angle rotation about the object's origin (axis need not be unit) |
// | scale          | —    | uniform scale about the object's origin |
//
//   M(t) = T(lerp(t_a, t_b)) · R(slerp(q_a, q_b)) · S(lerp(s_a, s_b)) between the keys around t;
//   before the first key / after the last, the end pose holds.
// Consecutive rotations are interpolated along the shorter arc: keys must be < 180° apart.
#pragma once

#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace camsim {

struct Keyframe {
  double time = 0.0;
  glm::dvec3 translate{0.0};
  glm::dquat rotate{1.0, 0.0, 0.0, 0.0};
  double scale = 1.0;
};

class RigidMotion {
 public:
  RigidMotion() = default;                           // identity, static
  explicit RigidMotion(std::vector<Keyframe> keys);  // sorted by time, ≥ 1 key

  bool empty() const { return keys_.empty(); }
  // True if the pose does not change within [t0, t1].
  bool isStaticDuring(double t0, double t1) const;
  glm::dmat4 at(double t) const;  // object → world at time t
  // The world point p at time t in object space, M(t)⁻¹ p, from the pose without forming
  // and inverting the matrix: R⁻¹ (p − T) / s.
  glm::dvec3 objectFromWorld(const glm::dvec3& p, double t) const;
  // Largest rotation angle (radians) between poses over [t0, t1] (for choosing time steps).
  double rotationAngleDuring(double t0, double t1) const;
  const std::vector<Keyframe>& keys() const { return keys_; }

 private:
  Keyframe pose(double t) const;
  std::vector<Keyframe> keys_;
};

}  // namespace camsim
