#include "integrator/sobol_sampler.h"

namespace camsim {
namespace {

// x and y of kBlock consecutive dimensions, the same arithmetic as get1D/get2D written as
// plain loops over the lanes, for the compiler to vectorise (8 × 32-bit lanes in AVX2).
template <int N>
void fillLanes(std::uint64_t pixelKey, std::uint32_t reversedIndex, int firstDimension, float* x,
               float* y) {
  std::uint64_t keys[N];
  for (int i = 0; i < N; ++i) keys[i] = SobolSampler::dimensionKey(pixelKey, firstDimension + i);
  for (int i = 0; i < N; ++i) {
    const glm::vec2 p = SobolSampler::pair(keys[i], reversedIndex);
    x[i] = p.x;
    y[i] = p.y;
  }
}

__attribute__((target("avx2"))) void fillLanesAvx2(std::uint64_t pixelKey,
                                                   std::uint32_t reversedIndex, int firstDimension,
                                                   float* x, float* y) {
  fillLanes<SobolSampler::kBlock>(pixelKey, reversedIndex, firstDimension, x, y);
}

}  // namespace

SobolSampler::SobolSampler(std::uint64_t seed, SobolDraw draw)
    : seed_(seed), avx2_(__builtin_cpu_supports("avx2")) {
  blocks_ = draw == SobolDraw::kBlocks || (draw == SobolDraw::kAuto && avx2_);
}

void SobolSampler::startPixelSample(glm::ivec2 pixel, int sampleIndex) {
  if (pixel != pixel_) {  // consecutive samples share the pixel's key
    pixelKey_ = pixelKeyOf(seed_, pixel);
    pixel_ = pixel;
  }
  reversedIndex_ = sobol::reverseBits(static_cast<std::uint32_t>(sampleIndex));
  dimension_ = 0;
  blockStart_ = kNoBlock;
}

void SobolSampler::fillBlock() {
  blockStart_ = dimension_;
  if (avx2_)
    fillLanesAvx2(pixelKey_, reversedIndex_, dimension_, x_, y_);
  else
    fillLanes<kBlock>(pixelKey_, reversedIndex_, dimension_, x_, y_);
}

}  // namespace camsim
