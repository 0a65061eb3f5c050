#include "integrator/sobol_sampler.h"

namespace camsim {

void SobolSampler::startPixelSample(glm::ivec2 pixel, int sampleIndex) {
  if (pixel != pixel_) {  // consecutive samples share the pixel's key
    pixelKey_ = pixelKeyOf(seed_, pixel);
    pixel_ = pixel;
  }
  reversedIndex_ = sobol::reverseBits(static_cast<std::uint32_t>(sampleIndex));
  dimension_ = 0;
}

}  // namespace camsim
