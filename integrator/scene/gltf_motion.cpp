// glTF node animation as camsim keyframed rigid motion (RigidMotion: T(t) · R(t) · S(t),
// translation and uniform scale interpolated linearly, rotation by slerp).
//
// | glTF sampler  | camsim keyframes                                                   |
// |---------------|--------------------------------------------------------------------|
// | LINEAR        | one per key: exact (slerp of glTF's rotation keys, shorter arc)     |
// | STEP          | one per key, and a copy of each value 1 µs before the next key      |
// | CUBICSPLINE   | the Hermite spline sampled at 16 steps per key interval (rotations |
// |               | normalised), linear in between: an approximation, noted             |
// Channels of one node with different key times are sampled at the union of their times,
// which keeps LINEAR channels exact. Times are glTF's seconds on camsim's clock (a frame
// sequence's frame k starts at (first + k)/rate). Before the first key and after the last
// the end values hold (glTF 2.0 §3.11).
#include <algorithm>
#include <cmath>
#include <set>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "integrator/scene/gltf_convert.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace {

constexpr double kStepGap = 1e-6;  // s: a STEP key's jump
constexpr int kCubicSteps = 16;    // samples per CUBICSPLINE key interval

glm::dvec4 valueAt(const GltfChannel& c, double t) {
  const bool cubic = c.interpolation == GltfChannel::Interpolation::kCubicSpline;
  auto value = [&](size_t k) { return c.values[cubic ? 3 * k + 1 : k]; };
  const size_t n = c.times.size();
  if (t <= c.times.front() || n == 1) return value(0);
  if (t >= c.times.back()) return value(n - 1);
  const size_t k =
      static_cast<size_t>(std::upper_bound(c.times.begin(), c.times.end(), t) - c.times.begin()) -
      1;
  const double dt = c.times[k + 1] - c.times[k];
  const double s = (t - c.times[k]) / dt;
  const bool rotation = c.target == GltfChannel::Path::kRotation;
  switch (c.interpolation) {
    case GltfChannel::Interpolation::kStep:
      return value(k);
    case GltfChannel::Interpolation::kLinear: {
      if (!rotation) return value(k) + s * (value(k + 1) - value(k));
      const glm::dvec4 a = value(k), b = value(k + 1);
      glm::dquat qa(a.w, a.x, a.y, a.z), qb(b.w, b.x, b.y, b.z);
      if (glm::dot(qa, qb) < 0.0) qb = -qb;  // the shorter arc
      const glm::dquat q = glm::slerp(qa, qb, s);
      return {q.x, q.y, q.z, q.w};
    }
    case GltfChannel::Interpolation::kCubicSpline: {
      const double s2 = s * s, s3 = s2 * s;
      const glm::dvec4 p = (2 * s3 - 3 * s2 + 1) * c.values[3 * k + 1] +
                           (s3 - 2 * s2 + s) * dt * c.values[3 * k + 2] +
                           (-2 * s3 + 3 * s2) * c.values[3 * (k + 1) + 1] +
                           (s3 - s2) * dt * c.values[3 * (k + 1)];
      return rotation ? p / glm::length(p) : p;
    }
  }
  return value(k);
}

}  // namespace

std::vector<bool> gltfAnimatedNodes(const GltfInclude& inc) {
  std::vector<bool> animated(inc.doc.nodes.size(), false);
  if (inc.animation < 0) return animated;
  for (const GltfChannel& c : inc.doc.animations[static_cast<size_t>(inc.animation)].channels)
    animated[static_cast<size_t>(c.node)] = true;
  return animated;
}

RigidMotion gltfNodeMotion(const GltfInclude& inc, int nodeIndex,
                           const glm::dmat4& renderFromParent, glm::dmat4& residual) {
  const GltfNode& node = inc.doc.nodes[static_cast<size_t>(nodeIndex)];
  const std::string file = inc.doc.file.string();
  auto fail = [&](const std::string& key, const std::string& m) {
    throw InputError({file, 0, 0}, key, m);
  };
  if (node.hasMatrix)
    fail(node.path + ".matrix", "an animated node must use translation/rotation/scale");
  std::vector<const GltfChannel*> channels;
  for (const GltfChannel& c : inc.doc.animations[static_cast<size_t>(inc.animation)].channels)
    if (c.node == nodeIndex) channels.push_back(&c);
  std::set<double> times;
  bool scaled = false;
  for (const GltfChannel* c : channels) {
    scaled = scaled || c->target == GltfChannel::Path::kScale;
    for (size_t k = 0; k < c->times.size(); ++k) {
      times.insert(c->times[k]);
      if (k + 1 == c->times.size()) continue;
      if (c->interpolation == GltfChannel::Interpolation::kStep)
        times.insert(c->times[k + 1] - std::min(kStepGap, 0.5 * (c->times[k + 1] - c->times[k])));
      if (c->interpolation == GltfChannel::Interpolation::kCubicSpline)
        for (int j = 1; j < kCubicSteps; ++j)
          times.insert(c->times[k] + (c->times[k + 1] - c->times[k]) * j / kCubicSteps);
    }
  }
  // The parent's similarity: scale s, rotation qP, translation.
  const glm::dvec3 c0(renderFromParent[0]), c1(renderFromParent[1]), c2(renderFromParent[2]);
  const double s = glm::length(c0);
  const double tol = 1e-6 * s;
  if (!(s > 0.0) || std::abs(glm::length(c1) - s) > tol || std::abs(glm::length(c2) - s) > tol ||
      std::abs(glm::dot(c0, c1)) > tol * s || std::abs(glm::dot(c1, c2)) > tol * s ||
      std::abs(glm::dot(c0, c2)) > tol * s || glm::dot(glm::cross(c0, c1), c2) < 0.0)
    fail(node.path,
         "an animated node's parents (and the include's placement) must be rotations, "
         "translations and uniform positive scales: camsim's motion is rigid");
  const glm::dquat qP = glm::quat_cast(glm::dmat3(c0 / s, c1 / s, c2 / s));
  // A constant non-uniform scale of the node stays with the geometry.
  residual = glm::dmat4(1.0);
  const glm::dvec3& rest = node.scale;
  const bool uniformRest = std::abs(rest.x - rest.y) <= 1e-9 * std::abs(rest.x) &&
                           std::abs(rest.y - rest.z) <= 1e-9 * std::abs(rest.x);
  if (!scaled && !uniformRest) residual = glm::scale(glm::dmat4(1.0), rest);
  std::vector<Keyframe> keys;
  for (double t : times) {
    glm::dvec3 T = node.translation, S = (scaled || uniformRest) ? rest : glm::dvec3(1.0);
    glm::dquat R = node.rotation;
    for (const GltfChannel* c : channels) {
      const glm::dvec4 v = valueAt(*c, t);
      if (c->target == GltfChannel::Path::kTranslation)
        T = glm::dvec3(v);
      else if (c->target == GltfChannel::Path::kScale)
        S = glm::dvec3(v);
      else
        R = glm::normalize(glm::dquat(v.w, v.x, v.y, v.z));
    }
    if (!(S.x > 0.0) || std::abs(S.x - S.y) > 1e-6 * S.x || std::abs(S.y - S.z) > 1e-6 * S.x)
      fail(node.path + ".scale", "an animated scale must be uniform and positive (at t = " +
                                     std::to_string(t) + " s it is (" + std::to_string(S.x) + ", " +
                                     std::to_string(S.y) + ", " + std::to_string(S.z) + "))");
    Keyframe k;
    k.time = t;
    k.translate = glm::dvec3(renderFromParent * glm::dvec4(T, 1.0));
    k.rotate = qP * R;
    k.scale = s * S.x;
    keys.push_back(k);
  }
  return RigidMotion(std::move(keys));
}

}  // namespace camsim
