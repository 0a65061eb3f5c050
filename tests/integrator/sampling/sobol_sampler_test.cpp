// SobolSampler: a pixel's even- and odd-indexed samples are two independent replicates
// (their half images uncorrelated); in each, every 2D pair of the first 2^m points — and of
// every aligned block of 2^m points, i.e. each pair is a (0, 2)-sequence — is a (0, m, 2)-net
// (one point in every elementary interval), 1D slots are stratified, 1D and 2D results are
// deterministic, and pixels/dimensions get independent scrambles; drawing in AVX2 blocks
// gives the numbers of drawing one at a time, bit for bit, whatever the order of draws.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <memory>
#include <random>
#include <set>
#include <vector>

#include "integrator/sampling/sobol_sampler.h"
#include "sensor/base/simd.h"
#include "tests/integrator/sampler_contract.h"

namespace camsim {
namespace {

// Points 0 … n − 1 of one half (sample indices 2i + half).
std::vector<glm::vec2> pairs(std::uint64_t seed, glm::ivec2 pixel, int dimension, int n,
                             int half = 0) {
  SobolSampler s(seed);
  std::vector<glm::vec2> out;
  for (int i = 0; i < n; ++i) {
    s.startPixelSample(pixel, 2 * i + half);
    s.setDimension(dimension);
    out.push_back(s.get2D());
  }
  return out;
}

TEST(SobolSampler, EveryPairIsAZeroMTwoNet) {
  for (int half : {0, 1})
    for (int dimension : {1, 3, 6, 9, 40})
      for (int m = 1; m <= 10; ++m) {
        const int n = 1 << m;
        const auto pts = pairs(7, {5, 9}, dimension, n, half);
        for (int a = 0; a <= m; ++a) {  // intervals of 2^-a × 2^-(m-a)
          std::set<std::pair<int, int>> cells;
          for (const glm::vec2& p : pts)
            cells.emplace(static_cast<int>(std::ldexp(static_cast<double>(p.x), a)),
                          static_cast<int>(std::ldexp(static_cast<double>(p.y), m - a)));
          EXPECT_EQ(static_cast<int>(cells.size()), n)
              << "dimension " << dimension << " m " << m << " a " << a;
        }
      }
}

// The (0, 2)-sequence property: not only the first 2^m samples but every aligned block of
// 2^m consecutive sample indices [k·2^m, (k+1)·2^m) of every pair is a (0, m, 2)-net, so a
// render that continues past a power of two stays stratified. (The index shuffle maps
// aligned blocks to aligned blocks: bit j of owen(i) depends only on bits ≥ j of i.)
TEST(SobolSampler, EveryAlignedBlockOfEveryPairIsAZeroMTwoNet) {
  for (int half : {0, 1})
    for (int dimension : {1, 6, 11})
      for (int m = 1; m <= 8; ++m)
        for (int block : {1, 2, 5}) {
          const int n = 1 << m;
          const auto all = pairs(13, {2, 7}, dimension, (block + 1) * n, half);
          const std::vector<glm::vec2> pts(all.begin() + block * n, all.end());
          for (int a = 0; a <= m; ++a) {
            std::set<std::pair<int, int>> cells;
            for (const glm::vec2& p : pts)
              cells.emplace(static_cast<int>(std::ldexp(static_cast<double>(p.x), a)),
                            static_cast<int>(std::ldexp(static_cast<double>(p.y), m - a)));
            EXPECT_EQ(static_cast<int>(cells.size()), n)
                << "dimension " << dimension << " m " << m << " block " << block << " a " << a;
          }
        }
}

// A pair depends only on (seed, pixel, sample index, dimension): not on the sampler copy nor
// on what was drawn before; another render seed gives other points.
TEST(SobolSampler, TwoDimensionalPairsAreDeterministic) {  // sampler_contract.h
  for (const SobolDraw draw : {SobolDraw::kBlocks, SobolDraw::kOneAtATime}) {
    SobolSampler a(5, draw), other(6, draw);
    SobolSampler b = a;  // a copy
    expectNumbersDependOnlyOnPixelSampleAndDimension(a, b, other);
  }
}

// The Sampler contract (sampler_contract.h), in blocks and one at a time.
TEST(SobolSampler, EveryDrawTakesOneDimension) {
  for (const SobolDraw draw : {SobolDraw::kBlocks, SobolDraw::kOneAtATime}) {
    SobolSampler a(9, draw), b(9, draw);
    expectEveryDrawTakesOneDimension(a, b);
  }
}

TEST(SobolSampler, OneDimensionalSlotsAreStratifiedAndDeterministic) {
  SobolSampler s(3), t(3);
  std::set<int> strata[2];
  for (int i = 0; i < 512; ++i) {
    s.startPixelSample({1, 2}, i);
    t.startPixelSample({1, 2}, i);
    s.setDimension(kDimTime);
    t.setDimension(kDimTime);
    const float u = s.get1D();
    EXPECT_EQ(u, t.get1D());
    strata[i % 2].insert(static_cast<int>(u * 256.0f));
  }
  EXPECT_EQ(strata[0].size(), 256u);
  EXPECT_EQ(strata[1].size(), 256u);
}

// The halves are independent replicates: over 4000 pixels, the correlation of the even and
// the odd samples' means of f(x) = x (2 points each) is 0 within 4 standard errors
// (1/√4000 each). Halves cut from one net would be complementary strata: −1 (the even points
// of a Sobol' pair lie in one half of [0, 1), the odd ones in the other).
TEST(SobolSampler, TheTwoHalvesAreUncorrelated) {
  for (int dimension : {int{kDimPixel}, kDimPath + 3}) {
    constexpr int kPixels = 4000;
    double sa = 0.0, sb = 0.0, saa = 0.0, sbb = 0.0, sab = 0.0;
    for (int p = 0; p < kPixels; ++p) {
      SobolSampler s(11);
      double mean[2] = {0.0, 0.0};
      for (int i = 0; i < 4; ++i) {
        s.startPixelSample({p % 64, p / 64}, i);
        s.setDimension(dimension);
        mean[i % 2] += 0.5 * static_cast<double>(s.get2D().x);
      }
      sa += mean[0], sb += mean[1], saa += mean[0] * mean[0], sbb += mean[1] * mean[1];
      sab += mean[0] * mean[1];
    }
    const double n = kPixels;
    const double cov = sab / n - (sa / n) * (sb / n);
    const double corr =
        cov / std::sqrt((saa / n - sa * sa / (n * n)) * (sbb / n - sb * sb / (n * n)));
    EXPECT_LT(std::abs(corr), 4.0 / std::sqrt(n)) << "dimension " << dimension;
  }
}

TEST(SobolSampler, PixelsAndDimensionsAreScrambledIndependently) {
  const auto a = pairs(7, {0, 0}, 1, 16), b = pairs(7, {1, 0}, 1, 16), c = pairs(7, {0, 0}, 3, 16);
  int sameAB = 0, sameAC = 0;
  for (int i = 0; i < 16; ++i) {
    sameAB += a[static_cast<size_t>(i)] == b[static_cast<size_t>(i)] ? 1 : 0;
    sameAC += a[static_cast<size_t>(i)] == c[static_cast<size_t>(i)] ? 1 : 0;
  }
  EXPECT_EQ(sameAB, 0);
  EXPECT_EQ(sameAC, 0);
}

// Integration error of a smooth 2D function: scrambled Sobol' at 1024 points is far below
// the independent sampler's σ ≈ 0.29/√1024 ≈ 0.009 (asserted < 0.002 over 16 pixels).
TEST(SobolSampler, IntegratesSmoothFunctionsAccurately) {
  double worst = 0.0;
  for (int px = 0; px < 16; ++px) {
    double sum = 0.0;
    for (const glm::vec2& p : pairs(11, {px, 0}, 1, 1024))
      sum += std::sin(3.0 * static_cast<double>(p.x)) * std::exp(static_cast<double>(p.y));
    const double exact = (1.0 - std::cos(3.0)) / 3.0 * (std::exp(1.0) - 1.0);
    worst = std::max(worst, std::abs(sum / 1024.0 - exact));
  }
  EXPECT_LT(worst, 0.002);
}

// One draw (1D or 2D) from both samplers; the numbers must agree bit for bit. Returns how
// many numbers were compared.
testing::AssertionResult sameDraw(SobolSampler& blocks, SobolSampler& single, bool twoD,
                                  int& compared) {
  const auto bits = [](float x) { return std::bit_cast<std::uint32_t>(x); };
  if (!twoD) {
    const float a = blocks.get1D(), b = single.get1D();
    ++compared;
    if (bits(a) == bits(b)) return testing::AssertionSuccess();
    return testing::AssertionFailure() << "1D: " << a << " (blocks) != " << b;
  }
  const glm::vec2 a = blocks.get2D(), b = single.get2D();
  compared += 2;
  if (bits(a.x) == bits(b.x) && bits(a.y) == bits(b.y)) return testing::AssertionSuccess();
  return testing::AssertionFailure()
         << "2D: (" << a.x << ", " << a.y << ") (blocks) != (" << b.x << ", " << b.y << ")";
}

TEST(SobolSampler, BlocksGiveTheNumbersOfOneAtATime) {
  // kBlocks: blocks on any CPU (the AVX2 fill where there is AVX2 and the SIMD build, else
  // the same loop for the build's target), so the block logic is tested everywhere.
  SobolSampler blocks(11, SobolDraw::kBlocks), single(11, SobolDraw::kOneAtATime);
  EXPECT_TRUE(blocks.drawsBlocks());
  EXPECT_FALSE(single.drawsBlocks());
  // kAuto: blocks exactly where the AVX2 fill is built and the CPU has AVX2.
  EXPECT_EQ(SobolSampler(11).drawsBlocks(), simd::cpuHasAvx2());
  // Draws before the first startPixelSample: pixel key 0, index 0, from dimension 0.
  EXPECT_EQ(std::bit_cast<std::uint32_t>(blocks.get1D()),
            std::bit_cast<std::uint32_t>(single.get1D()));
  // Random walks through the dimensions: 1D and 2D draws, jumps forwards and backwards
  // across block boundaries (and one far beyond), several samples of a pixel, changes of
  // pixel, and copies of a sampler in the middle of a pixel sample.
  std::mt19937 rng(5);
  int compared = 0;
  for (int pixelSample = 0; pixelSample < 400; ++pixelSample) {
    if (pixelSample % 50 == 25) {
      // Mid-sample, blocks is replaced by a fresh sampler and then restored from a copy:
      // the block and the seed cache must travel with the copy.
      const SobolSampler copy = blocks;
      blocks = SobolSampler(11, SobolDraw::kBlocks);
      blocks = copy;
    }
    const glm::ivec2 pixel(pixelSample / 7, 3);
    const int index = pixelSample % 7;
    blocks.startPixelSample(pixel, index);
    single.startPixelSample(pixel, index);
    for (int draw = 0; draw < 40; ++draw) {
      const unsigned what = rng() % 8;
      if (what == 0) {
        const int d = draw == 20 ? 2000000000 : static_cast<int>(rng() % 60);
        blocks.setDimension(d);
        single.setDimension(d);
      } else {
        ASSERT_TRUE(sameDraw(blocks, single, what >= 5, compared))
            << "pixel sample " << pixelSample << " draw " << draw;
      }
    }
  }
  EXPECT_GT(compared, 15000);
}

// The seed cache's edge: blocks that start just below, at and above the last cached block
// (kCachedDimensions − kBlock), and draws that walk across kCachedDimensions, over several
// samples of each pixel (the later ones read the cache) and two pixels.
TEST(SobolSampler, BlocksAcrossTheEndOfTheSeedCacheGiveTheNumbersOfOneAtATime) {
  SobolSampler blocks(12, SobolDraw::kBlocks), single(12, SobolDraw::kOneAtATime);
  constexpr int kEnd = SobolSampler::kCachedDimensions;
  // Each walk spans more than a block (one dimension per draw): from the last cached block,
  // it goes on into the first block past the cache.
  constexpr int kDraws = SobolSampler::kBlock + 6;
  static_assert(kDraws % 2 == 0);
  int compared = 0;
  for (const glm::ivec2 pixel : {glm::ivec2(3, 4), glm::ivec2(4, 4)}) {
    for (int sample = 0; sample < 4; ++sample) {
      for (int start = kEnd - SobolSampler::kBlock - 3; start <= kEnd + 2; ++start) {
        blocks.startPixelSample(pixel, sample);
        single.startPixelSample(pixel, sample);
        blocks.setDimension(start);
        single.setDimension(start);
        for (int draw = 0; draw < kDraws; ++draw)  // 1D, 2D, 1D, …
          ASSERT_TRUE(sameDraw(blocks, single, draw % 2 == 1, compared))
              << "start " << start << " draw " << draw;
      }
    }
  }
  // pixels, samples, starts, numbers (a 1D and a 2D draw give three)
  EXPECT_EQ(compared, 2 * 4 * (SobolSampler::kBlock + 6) * (kDraws / 2 * 3));
}

}  // namespace
}  // namespace camsim
