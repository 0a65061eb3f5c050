// glTF node animation as camsim keyframed rigid motion (RigidMotion: T(t) · R(t) · S(t),
// translation and uniform scale interpolated linearly, rotation by slerp).
//
// The include's animations (all of them by default) play together from t = 0; where two
// animate the same property of a node, the first in the file wins (noted). A mesh moves
// with the chain of animated nodes above it (itself included): its render-space pose is
//   M(t) = B₀ · L₁(t) · B₁ · L₂(t) · … · L_k(t)
// with L_i(t) = T·R·S of animated node i at t and B_i the static transforms between them
// (B₀ = render ← the first animated node's parent: placement and rest poses), and must be a
// similarity (rotation, translation, uniform positive scale) at every time.
//
// | glTF sampler  | camsim keyframes                                                   |
// |---------------|--------------------------------------------------------------------|
// | LINEAR        | one per key: exact (slerp of glTF's rotation keys, shorter arc)     |
// | STEP          | one per key, and a copy of each value 1 µs before the next key      |
// | CUBICSPLINE   | the Hermite spline sampled at 16 steps per key interval (rotations |
// |               | normalised), linear in between: an approximation, noted             |
// Channels of the chain's nodes are sampled at the union of their times, which keeps LINEAR
// channels of one node exact. A chain of several animated nodes is also sampled between
// those times wherever M(t) departs from camsim's interpolation of the samples around it by
// more than kChainTolerance within 1 m of the node (checked at ¼, ½, ¾ of each interval,
// halving it up to kChainHalvings times): e.g. a rotating parent swings its child's origin
// on an arc, which a linear interpolation of translations cuts short; a translating parent
// of a rotating child needs no extra samples (exact). Times are glTF's seconds on camsim's clock (a frame
// sequence's frame k starts at (first + k)/rate). Before the first key and after the last
// the end values hold (glTF 2.0 §3.11).
#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "integrator/scene/gltf_convert.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace {

constexpr double kStepGap = 1e-6;         // s: a STEP key's jump
constexpr int kCubicSteps = 16;           // samples per CUBICSPLINE key interval
constexpr double kChainTolerance = 1e-6;  // m, within 1 m of the animated node
constexpr int kChainHalvings = 8;         // ≤ 256 samples per key interval

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

// The channels that play on each node: the first (in file order) of the include's
// animations to target each (node, property).
std::vector<std::vector<const GltfChannel*>> playingChannels(const GltfInclude& inc,
                                                             std::vector<std::string>* notes) {
  std::vector<std::vector<const GltfChannel*>> out(inc.doc.nodes.size());
  for (int a : inc.animations)
    for (const GltfChannel& c : inc.doc.animations[static_cast<size_t>(a)].channels) {
      std::vector<const GltfChannel*>& mine = out[static_cast<size_t>(c.node)];
      const auto same = std::find_if(mine.begin(), mine.end(),
                                     [&](const GltfChannel* o) { return o->target == c.target; });
      if (same == mine.end()) {
        mine.push_back(&c);
      } else if (notes) {
        notes->push_back(c.path + ": not played: " + (*same)->path +
                         " animates the same property of " +
                         inc.doc.nodes[static_cast<size_t>(c.node)].path +
                         " (choose one animation with `animation:`)");
      }
    }
  return out;
}

struct ChainNode {
  const GltfNode* node;
  std::vector<const GltfChannel*> channels;
  bool scaled = false;    // a scale channel
  bool residual = false;  // its constant non-uniform scale stays with what is below it
};

// L(t) of a chain node: T·R·S at t (S = 1 where its scale is a residual).
glm::dmat4 localAt(const ChainNode& c, double t, const std::string& file) {
  const GltfNode& node = *c.node;
  glm::dvec3 T = node.translation, S = c.residual ? glm::dvec3(1.0) : node.scale;
  glm::dquat R = node.rotation;
  for (const GltfChannel* ch : c.channels) {
    const glm::dvec4 v = valueAt(*ch, t);
    if (ch->target == GltfChannel::Path::kTranslation)
      T = glm::dvec3(v);
    else if (ch->target == GltfChannel::Path::kScale)
      S = glm::dvec3(v);
    else
      R = glm::normalize(glm::dquat(v.w, v.x, v.y, v.z));
  }
  if (c.scaled &&
      (!(S.x > 0.0) || std::abs(S.x - S.y) > 1e-6 * S.x || std::abs(S.y - S.z) > 1e-6 * S.x))
    throw InputError({file, 0, 0}, node.path + ".scale",
                     "an animated scale must be uniform and positive (at t = " + std::to_string(t) +
                         " s it is (" + std::to_string(S.x) + ", " + std::to_string(S.y) + ", " +
                         std::to_string(S.z) + "))");
  return glm::translate(glm::dmat4(1.0), T) * glm::mat4_cast(R) * glm::scale(glm::dmat4(1.0), S);
}

// M(t) as a keyframe; InputError naming the deepest node if M is not a similarity.
Keyframe poseAt(const std::vector<GltfChainLink>& chain, const std::vector<ChainNode>& nodes,
                double t, const std::string& file) {
  glm::dmat4 m(1.0);
  for (size_t i = 0; i < chain.size(); ++i) m = m * chain[i].before * localAt(nodes[i], t, file);
  const glm::dvec3 c0(m[0]), c1(m[1]), c2(m[2]);
  const double s = glm::length(c0);
  const double tol = 1e-6 * s;
  if (!(s > 0.0) || !std::isfinite(s) || std::abs(glm::length(c1) - s) > tol ||
      std::abs(glm::length(c2) - s) > tol || std::abs(glm::dot(c0, c1)) > tol * s ||
      std::abs(glm::dot(c1, c2)) > tol * s || std::abs(glm::dot(c0, c2)) > tol * s ||
      glm::dot(glm::cross(c0, c1), c2) < 0.0)
    throw InputError({file, 0, 0}, nodes.back().node->path,
                     "an animated node's parents (and the include's placement) must be "
                     "rotations, translations and uniform positive scales at every time: "
                     "camsim's motion is rigid (at t = " +
                         std::to_string(t) + " s they are not)");
  Keyframe k;
  k.time = t;
  k.translate = glm::dvec3(m[3]);
  k.rotate = glm::normalize(glm::quat_cast(glm::dmat3(c0 / s, c1 / s, c2 / s)));
  k.scale = s;
  return k;
}

// Largest distance, within 1 m of the node's origin, between pose `truth` and camsim's
// interpolation at the same time.
double poseError(const Keyframe& truth, const glm::dmat4& interpolated) {
  const glm::dmat4 m = RigidMotion({truth}).at(truth.time);
  double error = glm::length(glm::dvec3(m[3] - interpolated[3]));
  for (int axis = 0; axis < 3; ++axis) {
    const glm::dvec4 d = (m[axis] - interpolated[axis]) / truth.scale + (m[3] - interpolated[3]);
    error = std::max(error, glm::length(glm::dvec3(d)));
  }
  return error;
}

// Samples of (a, b) (exclusive) where the chain's pose needs them (see above), in order.
void refine(const std::vector<GltfChainLink>& chain, const std::vector<ChainNode>& nodes,
            const Keyframe& a, const Keyframe& b, int depth, const std::string& file,
            std::vector<Keyframe>& out) {
  const RigidMotion between({a, b});
  bool fine = true;
  for (double f : {0.25, 0.5, 0.75}) {
    const double t = a.time + f * (b.time - a.time);
    fine = fine && poseError(poseAt(chain, nodes, t, file), between.at(t)) <= kChainTolerance;
  }
  const double mid = 0.5 * (a.time + b.time);
  if (fine || depth >= kChainHalvings || !(mid > a.time && mid < b.time)) return;
  const Keyframe m = poseAt(chain, nodes, mid, file);
  refine(chain, nodes, a, m, depth + 1, file, out);
  out.push_back(m);
  refine(chain, nodes, m, b, depth + 1, file, out);
}

}  // namespace

std::vector<bool> gltfAnimatedNodes(const GltfInclude& inc) {
  std::vector<bool> animated(inc.doc.nodes.size(), false);
  for (int a : inc.animations)
    for (const GltfChannel& c : inc.doc.animations[static_cast<size_t>(a)].channels)
      animated[static_cast<size_t>(c.node)] = true;
  return animated;
}

std::vector<std::string> gltfAnimationNotes(const GltfInclude& inc) {
  std::vector<std::string> notes;
  playingChannels(inc, &notes);
  return notes;
}

RigidMotion gltfChainMotion(const GltfInclude& inc, const std::vector<GltfChainLink>& chain,
                            glm::dmat4& residual) {
  const std::string file = inc.doc.file.string();
  const std::vector<std::vector<const GltfChannel*>> playing = playingChannels(inc, nullptr);
  std::vector<ChainNode> nodes;
  std::set<double> times;
  for (const GltfChainLink& link : chain) {
    ChainNode c{&inc.doc.nodes[static_cast<size_t>(link.node)],
                playing[static_cast<size_t>(link.node)], false, false};
    if (c.node->hasMatrix)
      throw InputError({file, 0, 0}, c.node->path + ".matrix",
                       "an animated node must use translation/rotation/scale");
    for (const GltfChannel* ch : c.channels) {
      c.scaled = c.scaled || ch->target == GltfChannel::Path::kScale;
      for (size_t k = 0; k < ch->times.size(); ++k) {
        times.insert(ch->times[k]);
        if (k + 1 == ch->times.size()) continue;
        const double t0 = ch->times[k], t1 = ch->times[k + 1];
        if (ch->interpolation == GltfChannel::Interpolation::kStep)
          times.insert(t1 - std::min(kStepGap, 0.5 * (t1 - t0)));
        if (ch->interpolation == GltfChannel::Interpolation::kCubicSpline)
          for (int j = 1; j < kCubicSteps; ++j) times.insert(t0 + (t1 - t0) * j / kCubicSteps);
      }
    }
    // A constant non-uniform scale of the node stays with the geometry below it.
    const glm::dvec3& rest = c.node->scale;
    const bool uniformRest = std::abs(rest.x - rest.y) <= 1e-9 * std::abs(rest.x) &&
                             std::abs(rest.y - rest.z) <= 1e-9 * std::abs(rest.x);
    c.residual = !c.scaled && !uniformRest;
    nodes.push_back(std::move(c));
  }
  residual = nodes.back().residual ? glm::scale(glm::dmat4(1.0), nodes.back().node->scale)
                                   : glm::dmat4(1.0);
  std::vector<Keyframe> keys;
  for (double t : times) {
    const Keyframe k = poseAt(chain, nodes, t, file);
    if (chain.size() > 1 && !keys.empty()) {
      const Keyframe previous = keys.back();
      refine(chain, nodes, previous, k, 0, file, keys);
    }
    keys.push_back(k);
  }
  return RigidMotion(std::move(keys));
}

}  // namespace camsim
