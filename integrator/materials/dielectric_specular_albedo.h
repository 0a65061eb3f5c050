// DielectricSpecularAlbedo: the directional albedo E(μ, r) of glTF's dielectric specular
// layer and its cosine-weighted mean E_avg(r), which MetallicRoughnessMaterial uses to
// dim its diffuse lobe by exactly what the specular layer reflects (energy conservation).
//
// | quantity | unit | meaning |
// |----------|------|---------|
// | μ        | —    | cos θ of the direction, in [0, 1] |
// | r        | —    | glTF's perceptual roughness, α = r² |
//
//   E(μ, r)  = ∫ F_d(wo·h) D G / (4 μ cos θi) cos θi dωi,   F_d = 0.04 + 0.96 (1 − wo·h)⁵,
//              GGX with α = r², Smith height-correlated (microfacet.h, the material's own
//              lobe); r = 0 is the smooth limit E = F_d(μ)
//   E_avg(r) = 2 ∫₀¹ E(μ, r) μ dμ
// Table: Q = E / F_d(μ) on 32 × 32 nodes, uniform in x = 1 − √(1 − u) and in √r, where
//   u = μ / √(μ² + α² (1 − μ²)) is the cosine in GGX's stretched space: masking dims E at
//   μ ≲ α, and this axis keeps that edge at the same nodes for every α (a grid in μ or √μ
//   was up to 0.04 off at grazing view); √r puts nodes where small roughness changes E fast
//   (uniform in r: 0.019 off at r = 0.01, cos θ = 10⁻⁶). Bilinear lookup; r = 0's row is
//   taken at α = 9·10⁻⁶.
// Each node integrates the lobe's own sampler (sampleReflection, weight f cos θi / pdf)
// over a 32 × 32 midpoint grid; E_avg integrates the table itself (256 midpoints in μ), so
// the diffuse lobe's albedo is c (1 − E_table(μo)) at each node's r. Against 400² per point
// the table is at most 9·10⁻⁴ below E (a white surface's energy excess) and 2.4·10⁻³ above
// (tests/integrator/materials/dielectric_specular_albedo_test.cpp). Built on first use,
// 0.2 s on the 2 GHz test machine (thread-safe, deterministic); the material asks for it
// when it is made, so a render never waits for it.
#pragma once

#include <array>

namespace camsim {

class DielectricSpecularAlbedo {
 public:
  static constexpr int kNodes = 32;
  static const DielectricSpecularAlbedo& get();

  // Arguments are clamped to [0, 1]; NaN is taken as 0.
  float albedo(float cosTheta, float roughness) const;  // E(μ, r)
  float average(float roughness) const;                 // E_avg(r)

  // E by quadrature of the lobe over an n × n midpoint grid (the table's nodes use 32).
  static double integrate(double cosTheta, double alpha, int n);
  // The dielectric's Schlick Fresnel at cos θ: 0.04 + 0.96 (1 − cos θ)⁵.
  static float fresnel(float cosTheta);

 private:
  DielectricSpecularAlbedo();
  std::array<float, kNodes * kNodes> q_{};  // [r node][x node]
  std::array<float, kNodes> average_{};
};

}  // namespace camsim
