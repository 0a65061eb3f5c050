// The SD-tree of practical path guiding (Müller, Gross, Novák 2017): a binary spatial tree
// over the scene's bounding box, each cell split in half across its longest side (the
// paper: a cube, axes in turn — the same cells for a cube, but a room is no cube), each
// leaf holding a directional quadtree that approximates the incident radiance there,
// normalised into a sampling density.
//
// | parameter        | value         | meaning                                                |
// |------------------|---------------|--------------------------------------------------------|
// | kSpatialC        | 4000 records  | a leaf splits above kSpatialC·√(2^k) records in        |
// |                  |               | training iteration k (paper: 12000 at 720p; camsim's   |
// |                  |               | bench images are ~25× smaller. small_light 240×160, 64 |
// |                  |               | spp: 1000 gave 5 % lower MRAE per spp, 25 % more time) |
// | kEnergyFraction  | ρ = 0.01      | a directional cell with > ρ of its leaf's energy is    |
// |                  |               | subdivided, smaller subtrees merged                    |
// | kMaxQuadDepth    | 20 levels     | finest directional cell: 2⁻²⁰ of the square's side     |
// | kMaxSpatialDepth | 48 levels     | finest spatial cell: 2⁻¹⁶ of the box's sides           |
//
// Directions use the area-preserving cylindrical map of the sphere onto the unit square:
//   u = (ω_z + 1)/2, v = φ/(2π), φ = atan2(ω_y, ω_x) ∈ [0, 2π) (a polynomial atan2, within
//   1.4·10⁻⁷ rad: the cells' edges move by less than float's rounding of φ)
// (world axes), whose Jacobian is constant: p_Ω(ω) = p_square(u, v) / (4π) sr⁻¹.
//
// A quadtree node holds, per quadrant, the energy (sum of record weights) of its subtree.
// Sampling descends choosing a quadrant ∝ its energy, then is uniform inside the leaf cell,
// so p_square = Π over the levels of 4·E_quadrant/E_node: a piecewise-constant density that
// integrates to 1 over the square. A node without energy samples uniformly below it.
//
// Everything here is serial and deterministic: records are inserted in a fixed order by
// the trainer (integrator/render/path_guide.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/render/source_lobe.h"

namespace camsim {

inline constexpr double kSpatialC = 4000.0;
inline constexpr float kEnergyFraction = 0.01f;
inline constexpr int kMaxQuadDepth = 20;
inline constexpr int kMaxSpatialDepth = 48;

// The cylindrical map (above): unit direction ↔ point of [0, 1]².
glm::vec2 directionToSquare(const glm::vec3& w);
glm::vec3 squareToDirection(glm::vec2 p);

class DirectionalQuadtree {
 public:
  DirectionalQuadtree();  // one node, four empty cells

  // Adds `weight` (≥ 0) to the finest cell containing p ∈ [0, 1]² and to its ancestors.
  void record(glm::vec2 p, float weight);
  float total() const {  // the energy of all records
    const Node& r = nodes_[0];
    return r.sum[0] + r.sum[1] + r.sum[2] + r.sum[3];
  }
  // A point of [0, 1]² drawn with density pdf(); u uniform in [0, 1)². With `density`, also
  // pdf() of the point (the product met on the way down: no second descent).
  glm::vec2 sample(glm::vec2 u, float* density = nullptr) const;
  float pdf(glm::vec2 p) const;  // density on the unit square (integrates to 1)
  // The structure for the next iteration: cells with more than kEnergyFraction of this
  // tree's energy are subdivided (until kMaxQuadDepth), smaller subtrees merged; no energy.
  DirectionalQuadtree refined() const;
  std::size_t nodeCount() const { return nodes_.size(); }
  std::size_t bytes() const { return nodes_.capacity() * sizeof(Node); }

 private:
  struct Node {
    float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};  // energy per quadrant (index x + 2y)
    std::uint32_t child[4] = {0, 0, 0, 0};    // 0: the quadrant is a leaf cell
  };
  void refineInto(DirectionalQuadtree& out, std::uint32_t outNode, int oldNode,
                  const float energy[4], float threshold, int depth) const;

  std::vector<Node> nodes_;
};

// One spatial leaf: the density and source lobe sampled this iteration, and the ones being
// recorded.
struct GuideLeaf {
  DirectionalQuadtree sampling, building;
  SourceLobe lobe;
  SourceMoments moments;
  std::uint64_t records = 0;  // records into `building` this iteration
};

class SDTree {
 public:
  // The root cell: the box lo … hi (the scene's bounds; each side at least 10⁻⁶ of the
  // longest).
  SDTree(glm::vec3 lo, glm::vec3 hi);

  // The leaf whose cell contains p (points outside the box go to its nearest cell).
  int leafAt(const glm::vec3& p) const;
  const GuideLeaf& leaf(int index) const { return leaves_[static_cast<std::size_t>(index)]; }
  std::size_t leafCount() const { return leaves_.size(); }

  // One record: incident-radiance weight at p from direction w (unit, world), and the
  // source lobe's weight of `source`, the point the light left (source_lobe.h).
  void record(const glm::vec3& p, glm::vec2 square, float weight, const glm::vec3& source,
              float sourceWeight);
  // After training iteration k (0-based): splits leaves with more records than
  // spatialC·√(2^k) (the children copy the parent's recorded tree), then makes each
  // leaf's recorded tree its sampling density and a refined, empty one its next record
  // (and the recorded moments its source lobe).
  void refine(int iteration, double spatialC = kSpatialC);
  // Drops the recording trees (after the last iteration: only sampling is left).
  void freeze();
  std::size_t bytes() const;

 private:
  struct Node {
    std::uint32_t child[2] = {0, 0};  // 0: a leaf
    std::int32_t leaf = -1;           // its index in leaves_ (leaves only)
    std::uint8_t axis = 0;            // split axis: the cell's longest
  };
  void split(std::uint32_t node, int depth, glm::vec3 size, std::uint64_t records,
             double threshold);

  glm::vec3 lo_, size_;
  std::vector<Node> nodes_;
  std::vector<GuideLeaf> leaves_;
};

}  // namespace camsim
