// SobolSampler: Owen-scrambled, shuffled Sobol' (0,2)-sequences, one independent pair per
// dimension slot ("padded" Sobol', Burley 2020, "Practical Hash-based Owen Scrambling").
//
// A pixel's samples are two independent replicates (issue 38): sample index s belongs to
// half h = s mod 2 as its point i = ⌊s/2⌋, and each half has its own pixel key, so the
// even-indexed and the odd-indexed samples are independently scrambled nets of ⌈n/2⌉ and
// ⌊n/2⌋ points. Their two half images are then independent estimates of the pixel, whose
// difference estimates the render's error (integrator/render/error_estimate.h); split from
// one net, the halves would be complementary strata (even and odd Sobol' points lie in
// opposite halves of the pixel) and their difference would measure the image's structure,
// not its noise. The price: each half is stratified on its own, not the union
// (docs/performance.md, "Error estimate", measures it).
//
// For dimension d of pixel p and point i of half h:
//   (lo, hi) = the two halves of the pixel key hash(render seed, p) for h = 0,
//              hash(render seed ⊕ kSecondHalfSalt, p) for h = 1
//   k       = h(h(d ⊕ hi) ⊕ lo),   s0 = h(k ⊕ hi),   s1 = h(k + C₁),   s2 = h(k + C₂)
//             (h: a 32-bit integer hash, sobol::hash32)
//   i'      = owen(i, s0)                      (shuffles which sample gets which point)
//   (x, y)  = (owen(sobol₀(i'), s1), owen(sobol₁(i'), s2))
// sobol₀ is the van der Corput sequence (bit reversal) and sobol₁ the second Sobol'
// dimension (direction numbers vₖ = vₖ₋₁ ⊕ (vₖ₋₁ ≫ 1), v₀ = 2³¹); together the first 2^m
// points of every pair form a (0, m, 2)-net: every 2D projection of the measurement
// integral (pixel, lens, time × wavelength, each bounce) is stratified, and scrambling
// keeps the estimator unbiased. owen() is a nested uniform scramble built from a
// Laine–Karras-style hash on the bit-reversed value. No tables.
//
// Cost: this sits on the hot path (≈ 20 numbers per pixel sample), so get1D/get2D fold the
// bit reversals that cancel (sobol₀ is itself a reversal), compute sobol₁ without a loop
// over the index bits, and derive a pair's three scramble seeds with 32-bit hashes (which
// vectorise 8-wide in AVX2, where 64-bit mixes do not); the pixel's key, and in block mode
// the seeds of its first kCachedDimensions dimensions, are reused by consecutive samples of
// the same pixel. What each of these saved: docs/performance.md.
#pragma once

#include <cstdint>
#include <limits>

#include "integrator/sampling/sampler.h"

namespace camsim {

namespace sobol {

// Bit reversal: three swap steps, then a byte swap (one instruction) for the rest.
inline std::uint32_t reverseBits(std::uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  return __builtin_bswap32(x);
}

// A hash in which each bit depends only on itself and lower bits: applied to the
// bit-reversed value it is a nested uniform (Owen) scramble.
inline std::uint32_t laineKarras(std::uint32_t x, std::uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// reverseBits(sobol₁(i)) without a loop over i's bits. Bit r of the reversed
// value is the XOR of the index bits k with r ⊆ k (direction number k is row k of Pascal's
// triangle mod 2, and C(k, r) is odd iff r ⊆ k, Lucas): a superset-sum transform over
// GF(2), five shift-mask-xor steps.
inline std::uint32_t reversedDimension1(std::uint32_t i) {
  i ^= (i >> 1) & 0x55555555u;
  i ^= (i >> 2) & 0x33333333u;
  i ^= (i >> 4) & 0x0F0F0F0Fu;
  i ^= (i >> 8) & 0x00FF00FFu;
  i ^= (i >> 16) & 0x0000FFFFu;
  return i;
}

// A 32-bit integer hash with full avalanche: two multiply–xorshift rounds (the constants
// of C. Wellons' "lowbias32").
inline std::uint32_t hash32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x21f0aaadu;
  x ^= x >> 15;
  x *= 0xd35a2d97u;
  x ^= x >> 15;
  return x;
}

}  // namespace sobol

// How a SobolSampler computes its numbers; all give the same numbers, bit for bit.
//   kAuto        blocks of kBlock dimensions at a time with AVX2 where the CPU has it
//                (and the build has the SIMD path, sensor/base/simd.h), else kOneAtATime
//   kOneAtATime  each number when it is drawn
//   kBlocks      blocks always, with AVX2 where kAuto would use it (tests the block
//                logic on any CPU and in the portable build)
enum class SobolDraw { kAuto, kOneAtATime, kBlocks };

// get1D/get2D are defined here so that the render loop, which is compiled for this final
// class (see render.cpp), inlines them. With the reversals folded:
//   shuffled = owen(i, s0) = rev(LK(rev(i), s0))
//   x = owen(sobol₀(shuffled), s1) = rev(LK(shuffled, s1))            (sobol₀ = rev)
//   y = owen(sobol₁(shuffled), s2) = rev(LK(rev(sobol₁(shuffled)), s2))
// Blocks: the dimensions of a pixel sample are independent, so on CPUs with AVX2 the first
// draw in a block computes x and y for its kBlock dimensions in vectorised loops
// (fillBlock: the seeds if not cached, then the numbers), and the draws that follow read
// them. Some are never used (paths end, a 1D draw leaves its y), but many at once cost less
// than two or three one at a time (bench/sobol_lanes_bench: 4.7× per number for AVX2
// lanes). A fill is one long dependent chain (two hashes of four 10-cycle multiplies, two
// bit reversals), so its time is latency: 16 dimensions are two 8-lane vectors whose
// chains overlap, at about the cost of one, and a pixel sample needs fewer fills than with
// 8 (Cornell box, 16 spp, 1 thread: render −5 %; 32 was slower again).
class SobolSampler final : public Sampler {
 public:
  static constexpr int kBlock = 16;

  explicit SobolSampler(std::uint64_t seed, SobolDraw draw = SobolDraw::kAuto);

  void startPixelSample(glm::ivec2 pixel, int sampleIndex) override;
  void setDimension(int dimension) override { dimension_ = dimension; }
  float get1D() override {
    if (!blocks_) return number1D(pixelKey_, reversedIndex_, dimension_++);
    const int slot = blockSlot();
    ++dimension_;
    return x_[slot];
  }
  glm::vec2 get2D() override {
    if (!blocks_) {
      return pair(pixelKey_, reversedIndex_, dimension_++);
    }
    const int slot = blockSlot();
    ++dimension_;
    return {x_[slot], y_[slot]};
  }
  bool drawsBlocks() const { return blocks_; }

  // The static functions below are the code get1D/get2D run, for loops over many pixel
  // samples or dimensions at once (fillBlock, bench/sobol_lanes_bench.cpp): the pixel's
  // key; number1D is what get1D() returns at `dimension` of the sample whose index
  // bit-reversed is reversedIndex.
  static std::uint64_t pixelKeyOf(std::uint64_t seed, glm::ivec2 pixel) {
    return hashValues(seed, static_cast<std::uint32_t>(pixel.x),
                      static_cast<std::uint32_t>(pixel.y));
  }
  // The second half's seed is the render seed with these bits flipped.
  static constexpr std::uint64_t kSecondHalfSalt = 0x9e3779b97f4a7c15ull;
  // The pair's three scramble seeds from (pixel key, dimension); see the top of the file.
  // The dimension as unsigned 32 bits (a negative int wraps; blocks of lanes wrap alike).
  struct Seeds {
    std::uint32_t shuffle, x, y;
  };
  static Seeds seedsOf(std::uint64_t pixelKey, std::uint32_t dimension) {
    const auto lo = static_cast<std::uint32_t>(pixelKey);
    const auto hi = static_cast<std::uint32_t>(pixelKey >> 32);
    const std::uint32_t k = sobol::hash32(sobol::hash32(dimension ^ hi) ^ lo);
    return {sobol::hash32(k ^ hi), sobol::hash32(k + 0x5bd1e995u), sobol::hash32(k + 0x68e31da4u)};
  }
  // The three steps of a pair from its seeds (get1D needs only the first two).
  static std::uint32_t shuffled(std::uint32_t shuffleSeed, std::uint32_t reversedIndex) {
    return sobol::reverseBits(sobol::laineKarras(reversedIndex, shuffleSeed));
  }
  static float xOf(std::uint32_t shuffledIndex, std::uint32_t xSeed) {
    return unitFloat(sobol::reverseBits(sobol::laineKarras(shuffledIndex, xSeed)));
  }
  static float yOf(std::uint32_t shuffledIndex, std::uint32_t ySeed) {
    return unitFloat(
        sobol::reverseBits(sobol::laineKarras(sobol::reversedDimension1(shuffledIndex), ySeed)));
  }
  static float number1D(std::uint64_t pixelKey, std::uint32_t reversedIndex, int dimension) {
    const Seeds seeds = seedsOf(pixelKey, static_cast<std::uint32_t>(dimension));
    return xOf(shuffled(seeds.shuffle, reversedIndex), seeds.x);
  }
  // What get2D() returns at `dimension`.
  static glm::vec2 pair(std::uint64_t pixelKey, std::uint32_t reversedIndex, int dimension) {
    const Seeds seeds = seedsOf(pixelKey, static_cast<std::uint32_t>(dimension));
    const std::uint32_t i = shuffled(seeds.shuffle, reversedIndex);
    return {xOf(i, seeds.x), yOf(i, seeds.y)};
  }

  // Block mode keeps the seeds of a pixel's first kCachedDimensions dimensions (used by
  // blocks that end within them): they do not depend on the sample index, so the pixel's
  // later samples skip the five hashes per dimension.
  static constexpr int kCachedDimensions = 256;

 private:
  // The slot of dimension_ in the current block, after filling a new block from dimension_
  // if it is not in it.
  int blockSlot() {
    // unsigned: wraps instead of overflowing for dimensions below the block or far above
    const unsigned slot = static_cast<unsigned>(dimension_) - static_cast<unsigned>(blockStart_);
    if (slot < static_cast<unsigned>(kBlock)) return static_cast<int>(slot);
    fillBlock();
    return 0;
  }
  void fillBlock();  // x_, y_ for dimensions dimension_ … dimension_ + kBlock − 1
  // The cached seeds of dimensions up to `end` (≤ kCachedDimensions).
  void cacheSeeds(int end);
  // The seeds of the kBlock dimensions from firstDimension, with AVX2 if avx2_.
  void seedsOfBlock(int firstDimension, std::uint32_t* shuffle, std::uint32_t* x,
                    std::uint32_t* y) const;

  std::uint64_t seed_;
  std::uint64_t pixelKey_ = 0;       // the current half's
  glm::ivec2 pixel_{-1};             // no pixel yet (pixels are never negative)
  int half_ = 0;                     // the current sample's half (sample index mod 2)
  std::uint64_t halfKeys_[2] = {};   // pixel_'s key for each half
  std::uint32_t reversedIndex_ = 0;  // the sample's point in its half, bit-reversed
  int dimension_ = 0;
  static constexpr int kNoBlock = std::numeric_limits<int>::min() / 2;  // far from any dimension

  bool blocks_ = false;
  bool avx2_ = false;          // simd::cpuHasAvx2(): the SIMD build on a CPU with AVX2
  int blockStart_ = kNoBlock;  // first dimension of x_, y_
  float x_[kBlock] = {}, y_[kBlock] = {};
  // Per half: dimensions [0, cachedEnd_[h]) of pixel_ have their seeds in seeds_[h].
  int cachedEnd_[2] = {};
  struct SeedCache {
    std::uint32_t shuffle[kCachedDimensions], x[kCachedDimensions], y[kCachedDimensions];
  };
  SeedCache seeds_[2] = {};
};

}  // namespace camsim
