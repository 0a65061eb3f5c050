// SobolSampler: Owen-scrambled, shuffled Sobol' (0,2)-sequences, one independent pair per
// dimension slot ("padded" Sobol', Burley 2020, "Practical Hash-based Owen Scrambling").
//
// For dimension d of pixel p and sample index i:
//   seed  = hash(render seed, p, d)
//   i'    = owen(i, seed)                      (shuffles which sample gets which point)
//   (x,y) = (owen(sobol₀(i'), h(seed,1)), owen(sobol₁(i'), h(seed,2)))
// sobol₀ is the van der Corput sequence (bit reversal) and sobol₁ the second Sobol'
// dimension (direction numbers vₖ = vₖ₋₁ ⊕ (vₖ₋₁ ≫ 1), v₀ = 2³¹); together the first 2^m
// points of every pair form a (0, m, 2)-net: every 2D projection of the measurement
// integral (pixel, lens, time × wavelength, each bounce) is stratified, and scrambling
// keeps the estimator unbiased. owen() is a nested uniform scramble built from a
// Laine–Karras-style hash on the bit-reversed value. No tables.
#pragma once

#include <cstdint>
#include <memory>

#include "integrator/sampler.h"

namespace camsim {

std::uint32_t sobolDimension0(std::uint32_t index);
std::uint32_t sobolDimension1(std::uint32_t index);
std::uint32_t owenScramble(std::uint32_t value, std::uint32_t seed);

class SobolSampler final : public Sampler {
 public:
  explicit SobolSampler(std::uint64_t seed) : seed_(seed) {}

  void startPixelSample(glm::ivec2 pixel, int sampleIndex) override;
  void setDimension(int dimension) override { dimension_ = dimension; }
  float get1D() override;
  glm::vec2 get2D() override;
  std::unique_ptr<Sampler> clone() const override { return std::make_unique<SobolSampler>(*this); }

 private:
  std::uint64_t seed_;
  std::uint64_t pixelKey_ = 0;
  std::uint32_t index_ = 0;
  int dimension_ = 0;
};

}  // namespace camsim
