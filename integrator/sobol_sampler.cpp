#include "integrator/sobol_sampler.h"

namespace camsim {

std::uint32_t sobolDimension0(std::uint32_t index) { return sobol::reverseBits(index); }

std::uint32_t sobolDimension1(std::uint32_t index) {
  return sobol::reverseBits(sobol::reversedDimension1(index));
}

std::uint32_t owenScramble(std::uint32_t value, std::uint32_t seed) {
  return sobol::reverseBits(sobol::laineKarras(sobol::reverseBits(value), seed));
}

void SobolSampler::startPixelSample(glm::ivec2 pixel, int sampleIndex) {
  if (pixel != pixel_ || !havePixel_) {  // consecutive samples share the pixel's key
    pixelKey_ = hashValues(seed_, static_cast<std::uint32_t>(pixel.x), static_cast<std::uint32_t>(pixel.y));
    pixel_ = pixel;
    havePixel_ = true;
  }
  reversedIndex_ = sobol::reverseBits(static_cast<std::uint32_t>(sampleIndex));
  dimension_ = 0;
}

}  // namespace camsim
