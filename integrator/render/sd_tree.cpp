#include "integrator/render/sd_tree.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/common.hpp>

#include "integrator/geometry/math.h"  // kPi

namespace camsim {
namespace {

constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

int quadrantOf(glm::vec2 p) {
  return (p.x >= 0.5f ? 1 : 0) + (p.y >= 0.5f ? 2 : 0);
}

// p in the quadrant q of the node's cell → p in the quadrant's own unit square.
glm::vec2 intoQuadrant(glm::vec2 p, int q) {
  return glm::vec2(2.0f * p.x - static_cast<float>(q & 1), 2.0f * p.y - static_cast<float>(q >> 1));
}

// atan2(y, x) in [0, 2π): atan on [0, 1] as an odd polynomial of degree 15 (coefficients
// fitted to atan by reweighted least squares on Chebyshev nodes; max error 1.4·10⁻⁷ rad
// evaluated in float, the size of atan2f's own rounding near π), then the octant. A guided
// bounce evaluates the map two or three times: atan2f was 9 % of a guided small_light
// render's profile (perf, 2026-12-06).
float azimuth(float y, float x) {
  const float ax = std::abs(x), ay = std::abs(y);
  const float hi = std::max(ax, ay);
  if (!(hi > 0.0f)) return 0.0f;
  const float a = std::min(ax, ay) / hi, a2 = a * a;
  float r = -0.00405456132f;
  for (const float c : {0.0218629406f, -0.0559123099f, 0.0964219693f, -0.139086299f, 0.199465659f,
                        -0.333298608f, 0.999999336f})
    r = r * a2 + c;
  r *= a;
  if (ay > ax) r = 0.5f * kPi - r;
  if (x < 0.0f) r = kPi - r;
  if (y < 0.0f) r = 2.0f * kPi - r;
  return r;
}

}  // namespace

glm::vec2 directionToSquare(const glm::vec3& w) {
  const float u = std::clamp((w.z + 1.0f) * 0.5f, 0.0f, 1.0f);
  const float phi = azimuth(w.y, w.x);
  const float v = std::clamp(phi / (2.0f * kPi), 0.0f, 1.0f);
  return {u, v};
}

glm::vec3 squareToDirection(glm::vec2 p) {
  const float cosTheta = 2.0f * p.x - 1.0f;
  const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
  const float phi = 2.0f * kPi * p.y;
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

DirectionalQuadtree::DirectionalQuadtree() : nodes_(1) {}

void DirectionalQuadtree::record(glm::vec2 p, float weight) {
  p = glm::clamp(p, glm::vec2(0.0f), glm::vec2(kOneMinusEpsilon));
  std::uint32_t node = 0;
  for (;;) {
    const int q = quadrantOf(p);
    Node& n = nodes_[node];
    n.sum[q] += weight;
    if (n.child[q] == 0) return;
    node = n.child[q];
    p = intoQuadrant(p, q);
  }
}

glm::vec2 DirectionalQuadtree::sample(glm::vec2 u, float* density) const {
  glm::vec2 origin(0.0f);
  float size = 1.0f, d = 1.0f;
  std::uint32_t node = 0;
  for (;;) {
    const Node& n = nodes_[node];
    const float total = n.sum[0] + n.sum[1] + n.sum[2] + n.sum[3];
    if (!(total > 0.0f)) break;  // no energy below: uniform in this cell
    // The column (x half) ∝ its energy, then the row within it: P(q) = E_q / E_node.
    const float left = n.sum[0] + n.sum[2];
    const float pLeft = left / total;
    int qx;
    if (u.x < pLeft) {
      qx = 0;
      u.x /= pLeft;
    } else {
      qx = 1;
      u.x = (u.x - pLeft) / (1.0f - pLeft);
    }
    const float column = n.sum[qx] + n.sum[qx + 2];
    const float pLow = column > 0.0f ? n.sum[qx] / column : 0.5f;
    int qy;
    if (u.y < pLow) {
      qy = 0;
      u.y /= pLow;
    } else {
      qy = 1;
      u.y = (u.y - pLow) / (1.0f - pLow);
    }
    u = glm::clamp(u, glm::vec2(0.0f), glm::vec2(kOneMinusEpsilon));
    size *= 0.5f;
    origin += glm::vec2(static_cast<float>(qx), static_cast<float>(qy)) * size;
    const int q = qx + 2 * qy;
    d *= 4.0f * n.sum[q] / total;
    if (n.child[q] == 0) break;
    node = n.child[q];
  }
  if (density) *density = d;
  return glm::clamp(origin + u * size, glm::vec2(0.0f), glm::vec2(kOneMinusEpsilon));
}

float DirectionalQuadtree::pdf(glm::vec2 p) const {
  p = glm::clamp(p, glm::vec2(0.0f), glm::vec2(kOneMinusEpsilon));
  float density = 1.0f;
  std::uint32_t node = 0;
  for (;;) {
    const Node& n = nodes_[node];
    const float total = n.sum[0] + n.sum[1] + n.sum[2] + n.sum[3];
    if (!(total > 0.0f)) return density;
    const int q = quadrantOf(p);
    density *= 4.0f * n.sum[q] / total;
    if (n.child[q] == 0 || density == 0.0f) return density;
    node = n.child[q];
    p = intoQuadrant(p, q);
  }
}

void DirectionalQuadtree::refineInto(DirectionalQuadtree& out, std::uint32_t outNode, int oldNode,
                                     const float energy[4], float threshold, int depth) const {
  for (int q = 0; q < 4; ++q) {
    if (depth + 1 >= kMaxQuadDepth || !(energy[q] > threshold)) continue;
    const int oldChild = oldNode >= 0 && nodes_[static_cast<std::size_t>(oldNode)].child[q] != 0
                             ? static_cast<int>(nodes_[static_cast<std::size_t>(oldNode)].child[q])
                             : -1;
    float childEnergy[4];
    for (int c = 0; c < 4; ++c)  // an old leaf cell: its energy assumed uniform over it
      childEnergy[c] =
          oldChild >= 0 ? nodes_[static_cast<std::size_t>(oldChild)].sum[c] : energy[q] / 4.0f;
    const auto child = static_cast<std::uint32_t>(out.nodes_.size());
    out.nodes_.emplace_back();
    out.nodes_[outNode].child[q] = child;
    refineInto(out, child, oldChild, childEnergy, threshold, depth + 1);
  }
}

DirectionalQuadtree DirectionalQuadtree::refined() const {
  DirectionalQuadtree out;
  const float e = total();
  if (e > 0.0f) refineInto(out, 0, 0, nodes_[0].sum, kEnergyFraction * e, 0);
  return out;
}

SDTree::SDTree(glm::vec3 lo, glm::vec3 hi) : lo_(lo), size_(hi - lo), nodes_(1), leaves_(1) {
  const float longest = std::max({size_.x, size_.y, size_.z, 1e-6f});
  size_ = glm::max(size_, glm::vec3(1e-6f * longest));
  nodes_[0].leaf = 0;
}

int SDTree::leafAt(const glm::vec3& p) const {
  glm::vec3 lo = lo_, size = size_;
  std::uint32_t node = 0;
  for (;;) {
    const Node& n = nodes_[node];
    if (n.child[0] == 0) return n.leaf;
    size[n.axis] *= 0.5f;
    const float mid = lo[n.axis] + size[n.axis];
    if (p[n.axis] < mid) {
      node = n.child[0];
    } else {
      node = n.child[1];
      lo[n.axis] = mid;
    }
  }
}

void SDTree::record(const glm::vec3& p, glm::vec2 square, float weight, const glm::vec3& source,
                    float sourceWeight) {
  GuideLeaf& l = leaves_[static_cast<std::size_t>(leafAt(p))];
  ++l.records;
  if (!(weight > 0.0f && std::isfinite(weight))) return;
  l.building.record(square, weight);
  l.moments.add(source, sourceWeight);
}

// Splits a leaf (of extent `size`) in two across its longest side, each child keeping half
// the records (assumed uniform in the cell, as Müller et al.), until a child holds at most
// `threshold`.
void SDTree::split(std::uint32_t node, int depth, glm::vec3 size, std::uint64_t records,
                   double threshold) {
  if (depth >= kMaxSpatialDepth || static_cast<double>(records) <= threshold) return;
  const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
  size[axis] *= 0.5f;
  const int leaf = nodes_[node].leaf;
  const auto c0 = static_cast<std::uint32_t>(nodes_.size());
  nodes_.resize(nodes_.size() + 2);
  const int newLeaf = static_cast<int>(leaves_.size());
  GuideLeaf copy = leaves_[static_cast<std::size_t>(leaf)];  // both halves sample it
  leaves_.push_back(std::move(copy));
  Node& n = nodes_[node];
  n.child[0] = c0;
  n.child[1] = c0 + 1;
  n.axis = static_cast<std::uint8_t>(axis);
  n.leaf = -1;
  nodes_[c0].leaf = leaf;
  nodes_[c0 + 1].leaf = newLeaf;
  split(c0, depth + 1, size, records / 2, threshold);
  split(c0 + 1, depth + 1, size, records / 2, threshold);
}

void SDTree::refine(int iteration, double spatialC) {
  const double threshold = spatialC * std::sqrt(std::ldexp(1.0, iteration));
  // The leaves as they are now, with their depths and extents (split appends nodes).
  struct Pending {
    std::uint32_t node;
    int depth;
    glm::vec3 size;
  };
  std::vector<Pending> stack{{0, 0, size_}}, leavesNow;
  while (!stack.empty()) {
    const Pending p = stack.back();
    stack.pop_back();
    const Node& n = nodes_[p.node];
    if (n.child[0] == 0) {
      leavesNow.push_back(p);
    } else {
      glm::vec3 half = p.size;
      half[n.axis] *= 0.5f;
      stack.push_back({n.child[1], p.depth + 1, half});
      stack.push_back({n.child[0], p.depth + 1, half});
    }
  }
  for (const Pending& p : leavesNow)
    split(p.node, p.depth, p.size, leaves_[static_cast<std::size_t>(nodes_[p.node].leaf)].records,
          threshold);
  for (GuideLeaf& l : leaves_) {
    DirectionalQuadtree next = l.building.refined();
    l.sampling = std::move(l.building);
    l.building = std::move(next);
    l.lobe = SourceLobe::fit(l.moments);
    l.moments = SourceMoments();
    l.records = 0;
  }
}

void SDTree::freeze() {
  for (GuideLeaf& l : leaves_) {
    l.building = DirectionalQuadtree();
    l.moments = SourceMoments();
    l.records = 0;
  }
}

std::size_t SDTree::bytes() const {
  std::size_t b = nodes_.capacity() * sizeof(Node) + leaves_.capacity() * sizeof(GuideLeaf);
  for (const GuideLeaf& l : leaves_) b += l.sampling.bytes() + l.building.bytes();
  return b;
}

}  // namespace camsim
