#include "integrator/sampling/sobol_sampler.h"

#include "sensor/base/simd.h"

namespace camsim {
namespace {

// The loops below are the same arithmetic as get1D/get2D written over the lanes, for the
// compiler to vectorise (8 × 32-bit lanes in AVX2). The plain templates are the reference,
// compiled for the build's target; with CAMSIM_SIMD_X86 each also has a copy compiled with
// CAMSIM_TARGET_AVX2, used on CPUs that have it (always_inline: a call into the baseline
// copy from the AVX2 function would run baseline code).

// Seeds of N consecutive dimensions from firstDimension (unsigned: wraps as seedsOf does).
template <int N>
[[gnu::always_inline]] inline void fillSeeds(std::uint64_t pixelKey, std::uint32_t firstDimension,
                                             std::uint32_t* shuffle, std::uint32_t* x,
                                             std::uint32_t* y) {
  for (int i = 0; i < N; ++i) {
    const SobolSampler::Seeds s =
        SobolSampler::seedsOf(pixelKey, firstDimension + static_cast<std::uint32_t>(i));
    shuffle[i] = s.shuffle;
    x[i] = s.x;
    y[i] = s.y;
  }
}

// x and y of N dimensions from their seeds.
template <int N>
[[gnu::always_inline]] inline void fillLanes(const std::uint32_t* shuffleSeeds,
                                             const std::uint32_t* xSeeds,
                                             const std::uint32_t* ySeeds,
                                             std::uint32_t reversedIndex, float* x, float* y) {
  for (int i = 0; i < N; ++i) {
    const std::uint32_t index = SobolSampler::shuffled(shuffleSeeds[i], reversedIndex);
    x[i] = SobolSampler::xOf(index, xSeeds[i]);
    y[i] = SobolSampler::yOf(index, ySeeds[i]);
  }
}

#if CAMSIM_SIMD_X86
constexpr int kBlock = SobolSampler::kBlock;

CAMSIM_TARGET_AVX2 void fillSeedsAvx2(std::uint64_t pixelKey, std::uint32_t firstDimension,
                                      std::uint32_t* shuffle, std::uint32_t* x, std::uint32_t* y) {
  fillSeeds<kBlock>(pixelKey, firstDimension, shuffle, x, y);
}

CAMSIM_TARGET_AVX2 void fillLanesAvx2(const std::uint32_t* shuffleSeeds,
                                      const std::uint32_t* xSeeds, const std::uint32_t* ySeeds,
                                      std::uint32_t reversedIndex, float* x, float* y) {
  fillLanes<kBlock>(shuffleSeeds, xSeeds, ySeeds, reversedIndex, x, y);
}
#endif

}  // namespace

SobolSampler::SobolSampler(std::uint64_t seed, SobolDraw draw)
    : seed_(seed), avx2_(simd::cpuHasAvx2()) {
  blocks_ = draw == SobolDraw::kBlocks || (draw == SobolDraw::kAuto && avx2_);
}

void SobolSampler::startPixelSample(glm::ivec2 pixel, int sampleIndex) {
  if (pixel != pixel_) {  // consecutive samples share the pixel's keys and seeds
    halfKeys_[0] = pixelKeyOf(seed_, pixel);
    halfKeys_[1] = pixelKeyOf(seed_ ^ kSecondHalfSalt, pixel);
    pixel_ = pixel;
    cachedEnd_[0] = cachedEnd_[1] = 0;
  }
  half_ = sampleIndex & 1;
  pixelKey_ = halfKeys_[half_];
  reversedIndex_ = sobol::reverseBits(static_cast<std::uint32_t>(sampleIndex) >> 1);
  dimension_ = 0;
  blockStart_ = kNoBlock;
}

void SobolSampler::seedsOfBlock(int firstDimension, std::uint32_t* shuffle, std::uint32_t* x,
                                std::uint32_t* y) const {
  const auto first = static_cast<std::uint32_t>(firstDimension);  // wraps, as seedsOf
#if CAMSIM_SIMD_X86
  if (avx2_)
    fillSeedsAvx2(pixelKey_, first, shuffle, x, y);
  else
    fillSeeds<kBlock>(pixelKey_, first, shuffle, x, y);
#else
  fillSeeds<kBlock>(pixelKey_, first, shuffle, x, y);
#endif
}

void SobolSampler::cacheSeeds(int end) {
  SeedCache& c = seeds_[half_];
  for (int& e = cachedEnd_[half_]; e < end; e += kBlock)
    seedsOfBlock(e, c.shuffle + e, c.x + e, c.y + e);
}

void SobolSampler::fillBlock() {
  static_assert(kCachedDimensions % kBlock == 0, "the cache fills whole blocks");
  blockStart_ = dimension_;
  const std::uint32_t *shuffle, *xs, *ys;
  std::uint32_t local[3][kBlock];
  // Blocks that end within the cache use it; any other dimension (negative, or up to
  // INT_MAX, whose block's lanes go past it: unsigned dimensions wrap) computes its seeds
  // here.
  if (dimension_ >= 0 && dimension_ <= kCachedDimensions - kBlock) {
    cacheSeeds(dimension_ + kBlock);
    const SeedCache& c = seeds_[half_];
    shuffle = c.shuffle + dimension_;
    xs = c.x + dimension_;
    ys = c.y + dimension_;
  } else {
    seedsOfBlock(dimension_, local[0], local[1], local[2]);
    shuffle = local[0];
    xs = local[1];
    ys = local[2];
  }
#if CAMSIM_SIMD_X86
  if (avx2_)
    fillLanesAvx2(shuffle, xs, ys, reversedIndex_, x_, y_);
  else
    fillLanes<kBlock>(shuffle, xs, ys, reversedIndex_, x_, y_);
#else
  fillLanes<kBlock>(shuffle, xs, ys, reversedIndex_, x_, y_);
#endif
}

}  // namespace camsim
