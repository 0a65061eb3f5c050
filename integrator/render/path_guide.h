// Practical path guiding (Müller, Gross, Novák 2017; issue 38): the path tracer samples a
// bounce's direction at a non-specular vertex from the one-sample mixture
//
//   p(ω) = α·p_bsdf(ω) + (1 − α − γ)·p_guide(x, ω) + γ·p_lobe(x, ω)
//   α = kBsdfFraction = 0.5, γ = kLobeFraction = 0.25 where the leaf has a source lobe
//   and x is far enough from its cloud (κ ≥ 4, source_lobe.h), else 0
//
// where p_guide is the SD-tree's learnt density of the incident radiance at x
// (integrator/render/sd_tree.h) and p_lobe the vMF lobe towards the leaf's learnt light
// sources (source_lobe.h); next-event estimation's MIS weighs against the same mixture
// pdf. Where the guide has no density (no records there), p = p_bsdf.
//
// Training (PathGuide::train): iterations k = 0, 1, … of 2^k samples per pixel, while their
// total stays within a quarter of the render's spp (256 spp: 1+2+…+32 = 63 spp); the last
// iteration's records make the guide. Iteration k samples with the guide of iteration k − 1
// (k = 0: the BSDF alone) and records, at every non-specular vertex of every path, the
// spectral average (over the path's wavelengths) of the radiance the rest of the path
// brought in along the sampled direction, divided by the mixture pdf it was sampled with,
// and the point that radiance left (the ray's hit: the source lobe's moments).
// Training uses its own sample streams (the render seed hashed with "guide"), none of the
// final render's, and its samples are not in the image.
//
// Russian roulette (path_tracer.cpp) then takes its survival rate from the throughput with
// the BSDF's sampling weight f·cos/p_bsdf at guided bounces instead of f·cos/p: a direction
// the guide favours has a large p, and roulette on the true throughput killed most of the
// paths guiding found (small_light: no gain at all without this).
// Unbiasedness: the final render uses the FROZEN guide, so p is a fixed density, positive
// wherever p_bsdf is (α > 0): plain importance sampling.
// Determinism: tiles are traced in parallel in batches; each tile keeps its records, and
// they are inserted in tile order after each batch (float sums in a fixed order): the same
// scene and seed give the same guide, and image, for any thread count.
// Memory: the SD-tree (bytes()), plus during training one batch's records (40 bytes each;
// batches of 32 tiles × 32 spp: ≈ 42 MB at 4 vertices per path, whatever the spp).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/render/sd_tree.h"
#include "integrator/render/source_lobe.h"
#include "sensor/spectra/sampled_spectrum.h"

namespace camsim {

class Scene;

// One training record: a vertex, the square point of its sampled direction, the weight
// L/p it adds to the cell there, the point the light left and its source-lobe weight
// L_d²/p (source_lobe.h; 0: none).
struct GuideRecord {
  glm::vec3 p{0.0f};
  glm::vec2 square{0.0f};
  float weight = 0.0f;
  glm::vec3 source{0.0f};
  float sourceWeight = 0.0f;
};

// What a training path keeps of its vertices until it ends (path_tracer.cpp).
struct GuideRecorder {
  struct Vertex {
    glm::vec3 p;
    glm::vec2 square;
    float pdf;                 // sr⁻¹, of the direction sampled there
    SampledSpectrum beta;      // path throughput after the vertex's scattering
    SampledSpectrum L{0.0f};   // radiance arrived since, divided by beta
    SampledSpectrum Ld{0.0f};  // of which emitted or lit directly at the next vertex
    bool direct = true;        // Ld still open: no specular vertex after this one yet
    glm::vec3 next{0.0f};      // where the sampled ray hit (hasNext)
    bool hasNext = false;
  };
  std::vector<Vertex> path;  // cleared per path
  std::vector<GuideRecord>* out = nullptr;
};

struct GuideStats {
  double trainSeconds = 0.0;
  int iterations = 0;
  int trainSpp = 0;  // samples per pixel traced in training (all iterations)
  std::uint64_t records = 0;
  std::size_t leaves = 0;
  std::size_t bytes = 0;  // the SD-tree as the final render uses it
};

// What the guide holds at one point: the leaf's density (null: none) and its source lobe
// there (kappa 0: none).
struct GuideQuery {
  const DirectionalQuadtree* density = nullptr;
  VmfLobe lobe;
};

class PathGuide {
 public:
  static constexpr float kBsdfFraction = 0.5f;   // α of the mixture above
  static constexpr float kLobeFraction = 0.25f;  // γ, where there is a lobe

  // Trains on `scene` with the render's spp, seed and threads (0: all); options as render().
  // cancel (may be null): when it turns true, training stops within one chunk of one tile
  // (kChunkSpp samples of its pixels) and the guide is returned as it is.
  static PathGuide train(const Scene& scene, int spp, std::uint64_t seed, int threads,
                         const std::atomic<bool>* cancel = nullptr);
  // An estimate of the records training holds at once (bytes) for a render of this size,
  // spp and max_depth: a batch of tiles × one chunk of samples × min(max_depth, 8) vertices
  // a path (the Cornell box averages 3.8; a path records at most max_depth, and a tile's
  // vector may hold up to twice its records' room). The SD-tree itself is small (tens of kB).
  static std::uint64_t trainingBytes(glm::ivec2 resolution, int spp, int maxDepth);
  // A guide from a tree (tests).
  explicit PathGuide(SDTree tree) : tree_(std::move(tree)) {}

  // The guide at x; density null where it has none (sample with the BSDF alone).
  GuideQuery at(const glm::vec3& x) const {
    const GuideLeaf& l = tree_.leaf(tree_.leafAt(x));
    if (!(l.sampling.total() > 0.0f)) return {};
    return {&l.sampling, l.lobe.at(x)};
  }
  static float pdf(const DirectionalQuadtree& d, const glm::vec3& w);  // sr⁻¹, w unit
  // A unit direction and its pdf (sr⁻¹).
  static glm::vec3 sample(const DirectionalQuadtree& d, glm::vec2 u, float* pdf);
  const SDTree& tree() const { return tree_; }
  const GuideStats& stats() const { return stats_; }

 private:
  SDTree tree_;
  GuideStats stats_;
};

}  // namespace camsim
