#include "integrator/geometry/motion.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "sensor/base/check.h"

namespace camsim {

RigidMotion::RigidMotion(std::vector<Keyframe> keys) : keys_(std::move(keys)) {
  CAMSIM_CHECK(!keys_.empty());
  for (size_t i = 1; i < keys_.size(); ++i) {
    CAMSIM_CHECK(keys_[i].time > keys_[i - 1].time);
    if (glm::dot(keys_[i].rotate, keys_[i - 1].rotate) < 0.0) keys_[i].rotate = -keys_[i].rotate;
  }
}

Keyframe RigidMotion::pose(double t) const {
  if (keys_.empty()) return {};
  if (t <= keys_.front().time) return keys_.front();
  if (t >= keys_.back().time) return keys_.back();
  const auto it = std::upper_bound(keys_.begin(), keys_.end(), t,
                                   [](double v, const Keyframe& k) { return v < k.time; });
  const Keyframe& b = *it;
  const Keyframe& a = *(it - 1);
  const double f = (t - a.time) / (b.time - a.time);
  Keyframe k;
  k.time = t;
  k.translate = glm::mix(a.translate, b.translate, f);
  k.rotate = glm::slerp(a.rotate, b.rotate, f);
  k.scale = a.scale + f * (b.scale - a.scale);
  return k;
}

glm::dmat4 RigidMotion::at(double t) const {
  const Keyframe k = pose(t);
  glm::dmat4 m = glm::mat4_cast(k.rotate) * k.scale;
  m[3] = glm::dvec4(k.translate, 1.0);
  return m;
}

glm::dvec3 RigidMotion::objectFromWorld(const glm::dvec3& p, double t) const {
  const Keyframe k = pose(t);
  return glm::inverse(k.rotate) * (p - k.translate) / k.scale;
}

bool RigidMotion::isStaticDuring(double t0, double t1) const {
  if (keys_.size() < 2) return true;
  const Keyframe a = pose(t0);
  for (const Keyframe& k : keys_) {
    if (k.time <= t0 || k.time >= t1) continue;
    if (k.translate != a.translate || k.rotate != a.rotate || k.scale != a.scale) return false;
  }
  const Keyframe b = pose(t1);
  return b.translate == a.translate && b.rotate == a.rotate && b.scale == a.scale;
}

double RigidMotion::rotationAngleDuring(double t0, double t1) const {
  // Sum of key-to-key angles within the window (slerp moves at constant angular speed).
  double total = 0.0;
  Keyframe prev = pose(t0);
  auto angle = [](const glm::dquat& a, const glm::dquat& b) {
    return 2.0 * std::acos(std::min(1.0, std::abs(glm::dot(a, b))));
  };
  for (const Keyframe& k : keys_) {
    if (k.time <= t0 || k.time >= t1) continue;
    total += angle(prev.rotate, k.rotate);
    prev = k;
  }
  return total + angle(prev.rotate, pose(t1).rotate);
}

}  // namespace camsim
