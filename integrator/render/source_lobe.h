// The guide's source lobe (issue 38, part 4): where a spatial leaf's incident light comes
// FROM, as a point cloud, so that the direction towards it can be recomputed at each point
// of the leaf (parallax; the idea of Ruppert, Herholz, Lensch 2020, in its simplest form).
//
// A leaf's directional quadtree (sd_tree.h) is one density for its whole cell: for light
// from a small, near source — the inside of small_light's lamp shade, seen through an
// opening of 0.005 sr from 2 m — the direction changes by more across a 0.7 m cell than
// the source subtends, so the quadtree blurs it over 0.1–0.3 sr. The lobe keeps instead
// the moments of the records' source points q (the recorded path's next vertex), each
// weighted by w = L_d²/p, L_d the radiance that left q directly (emitted there, or light
// sampled there: not what arrived after further bounces, nor past a specular vertex after
// q), p the pdf of the recorded direction. w estimates ∫ L_d² dω — the second moment, which a bright, small source
// dominates (small_light: the shade's inside, L ≈ 10³ cd/m² over 0.005 sr, against the
// ceiling's pool, 33 cd/m² over 0.3 sr; weighted by L/p, the radiance, the cloud was the
// whole room, σ ≈ 1.5 m):
//
//   c = Σ w q / Σ w            (m, the source's centroid)
//   σ² = Σ w |q|² / Σ w − |c|²  (m², its spread: the sum over the three axes)
//
// and at a point x of the leaf samples a von Mises–Fisher lobe about μ = (c − x)/d,
// d = |c − x|, of concentration κ = kSharpness · d²/σ²:
//
//   p(ω) = κ / (2π (1 − e^(−2κ))) · e^(κ (μ·ω − 1))   sr⁻¹
//
// | parameter      | value | meaning                                                     |
// |----------------|-------|-------------------------------------------------------------|
// | kSharpness     | 3     | κ = 3d²/σ²: the lobe's angular variance 1/κ per axis is the |
// |                |       | cloud's, σ²/3 per axis over d² (small_light, 128 px, MRAE   |
// |                |       | @ 128 spp: 0.3 → 0.46, 1 → 0.37, 3 → 0.32, 10 → 0.39)       |
// | kMinKappa      | 4     | below it (x inside or near the cloud) the lobe is not used  |
// | kMaxKappa      | 10⁵   | caps κ (1/√κ: 3 mrad per axis)                              |
// | kMinSpread     | 1e-6  | σ² floor, m²                                                 |
//
// The lobe is one more technique of the path tracer's one-sample mixture (path_guide.h);
// it is a fixed function of x once training ends, so the estimator stays unbiased.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace camsim {

// The moments being recorded (training), double sums in record order (deterministic).
struct SourceMoments {
  double w = 0.0;
  double q[3] = {0.0, 0.0, 0.0};
  double q2 = 0.0;
  void add(const glm::vec3& source, float weight);
};

// A vMF lobe at one point: mean direction and concentration; kappa 0: none.
struct VmfLobe {
  glm::vec3 mu{0.0f, 0.0f, 1.0f};
  float kappa = 0.0f;
  float pdf(const glm::vec3& w) const;              // sr⁻¹, w unit
  glm::vec3 sample(glm::vec2 u, float* pdf) const;  // u uniform in [0, 1)²
};

// The frozen lobe of a leaf: centroid and spread of its sources.
struct SourceLobe {
  static constexpr float kSharpness = 3.0f;
  static constexpr float kMinKappa = 4.0f;
  static constexpr float kMaxKappa = 1e5f;
  static constexpr float kMinSpread = 1e-6f;

  glm::vec3 centre{0.0f};
  float spread2 = 0.0f;  // σ², m²; 0: no lobe (no records with a source)

  static SourceLobe fit(const SourceMoments& m);
  // The lobe at x, or kappa 0 where there is none or x is too near the cloud.
  VmfLobe at(const glm::vec3& x) const;
};

}  // namespace camsim
