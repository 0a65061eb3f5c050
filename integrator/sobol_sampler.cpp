#include "integrator/sobol_sampler.h"

namespace camsim {

void SobolSampler::startPixelSample(glm::ivec2 pixel, int sampleIndex) {
  if (pixel != pixel_) {  // consecutive samples share the pixel's key
    pixelKey_ =
        hashValues(seed_, static_cast<std::uint32_t>(pixel.x), static_cast<std::uint32_t>(pixel.y));
    pixel_ = pixel;
  }
  reversedIndex_ = sobol::reverseBits(static_cast<std::uint32_t>(sampleIndex));
  dimension_ = 0;
}

}  // namespace camsim
