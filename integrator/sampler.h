// Sampler: the uniform numbers one pixel sample consumes, dimension by dimension.
// startPixelSample() fixes the stream for (pixel, sample index), so a sample's numbers
// do not depend on which thread renders it or in what order.
#pragma once

#include <cstdint>
#include <memory>

#include <glm/vec2.hpp>

#include "integrator/rng.h"

namespace camsim {

class Sampler {
 public:
  virtual ~Sampler() = default;
  virtual void startPixelSample(glm::ivec2 pixel, int sampleIndex) = 0;
  virtual float get1D() = 0;
  virtual glm::vec2 get2D() = 0;
  // The position within the pixel's photosensitive area.
  virtual glm::vec2 getPixel2D() = 0;
  virtual std::unique_ptr<Sampler> clone() const = 0;
};

// Independent uniform numbers from PCG32 keyed by (seed, pixel, sample index).
class IndependentSampler final : public Sampler {
 public:
  explicit IndependentSampler(std::uint64_t seed) : seed_(seed) {}

  void startPixelSample(glm::ivec2 pixel, int sampleIndex) override {
    rng_.seed(hashValues(seed_, static_cast<std::uint32_t>(pixel.x), static_cast<std::uint32_t>(pixel.y)),
              static_cast<std::uint64_t>(sampleIndex));
  }
  float get1D() override { return rng_.uniform(); }
  glm::vec2 get2D() override {
    const float a = rng_.uniform();
    return {a, rng_.uniform()};
  }
  glm::vec2 getPixel2D() override { return get2D(); }
  std::unique_ptr<Sampler> clone() const override { return std::make_unique<IndependentSampler>(*this); }

 private:
  std::uint64_t seed_;
  Pcg32 rng_;
};

}  // namespace camsim
