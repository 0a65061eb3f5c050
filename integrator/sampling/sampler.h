// Sampler: the uniform numbers one pixel sample consumes, by dimension.
// startPixelSample() fixes the stream for (pixel, sample index); numbers are addressed by
// dimension, so a sample's numbers depend neither on the thread nor on which *other*
// dimensions were drawn. Every draw, get1D or get2D, takes one dimension: a 2D draw is one
// pair (for the Sobol' sampler a (0,2)-sequence), not two 1D draws. The render loop gives
// each dimension of the measurement integral a fixed slot (SampleDimension), so switching,
// say, time sampling on or off leaves every other number unchanged.
#pragma once

#include <cstdint>

#include <glm/vec2.hpp>

#include "integrator/sampling/rng.h"

namespace camsim {

// Fixed dimension slots of a camera sample; path tracing uses kPath onwards. Diffraction's
// two slots lie below 0, apart from all the others: a render with it on draws every other
// number as one without it does.
enum SampleDimension : int {
  kDimDiffraction = -2,            // 2D: the offset from the stop's PSF
  kDimDiffractionWavelength = -1,  // 1D: whose wavelength's PSF
  kDimWavelength = 0,
  kDimPixel = 1,  // 2D
  kDimLens = 2,   // 2D
  kDimTime = 3,
  kDimPath = 4,
};

class Sampler {
 public:
  virtual ~Sampler() = default;
  virtual void startPixelSample(glm::ivec2 pixel, int sampleIndex) = 0;
  virtual void setDimension(int dimension) = 0;
  virtual float get1D() = 0;
  virtual glm::vec2 get2D() = 0;
};

// Independent uniform numbers: u = hash(seed, pixel, sample index, dimension), a
// counter-based generator (no state carried between numbers).
class IndependentSampler final : public Sampler {
 public:
  explicit IndependentSampler(std::uint64_t seed) : seed_(seed) {}

  void startPixelSample(glm::ivec2 pixel, int sampleIndex) override {
    key_ = hashValues(seed_, static_cast<std::uint32_t>(pixel.x),
                      static_cast<std::uint32_t>(pixel.y), static_cast<std::uint32_t>(sampleIndex));
    dimension_ = 0;
  }
  void setDimension(int dimension) override { dimension_ = static_cast<std::uint64_t>(dimension); }
  float get1D() override { return unitFloat(static_cast<std::uint32_t>(next() >> 32)); }
  // Two 24-bit numbers from disjoint bits of one 64-bit hash (bits 40–63 and 16–39).
  glm::vec2 get2D() override {
    const std::uint64_t h = next();
    return {unitFloat(static_cast<std::uint32_t>(h >> 32)),
            unitFloat(static_cast<std::uint32_t>(h >> 8))};
  }

 private:
  std::uint64_t next() { return mix64(key_ + 0x9e3779b97f4a7c15ull * (++dimension_)); }

  std::uint64_t seed_;
  std::uint64_t key_ = 0;
  std::uint64_t dimension_ = 0;
};

}  // namespace camsim
