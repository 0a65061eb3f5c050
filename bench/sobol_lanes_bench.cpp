// sobol_lanes_bench: what drawing Sobol' numbers for many paths at once would save, the
// first measurement behind docs/performance.md "Next: several paths per thread".
//
// The tracer draws its ≈ 20 numbers per pixel sample one at a time (SobolSampler::get1D/
// get2D, inlined into the path loop): a dependent chain of 32-bit hashes, multiplies and
// bit reversals per number (in blocks of dimensions where the CPU has AVX2). A path loop that keeps several pixel samples in flight
// would draw the same dimension for all of them in one plain loop, which the compiler can
// vectorise. This program times both on the same numbers:
//   get1D          SobolSampler::startPixelSample + get1D over every dimension: one at a
//                  time (SobolDraw::kOneAtATime), and by default (blocks of kBlock
//                  dimensions with AVX2 where the CPU has it)
//   lanes          SobolSampler::number1D in a loop over pixel samples (same code), built
//                  for the build's target (x86-64: the SSE2 baseline), and for AVX2 where
//                  the CPU has it (CAMSIM_TARGET_AVX2, sensor/base/simd.h; not in the
//                  portable build, CAMSIM_SIMD=OFF)
// and checks that every variant gives the same numbers bit for bit (error: 0 mismatches).
//
// usage: sobol_lanes_bench [--rounds N]   (default 64; prints ns per number, best of 5)
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "bench/bench_rounds.h"
#include "integrator/sampling/sobol_sampler.h"
#include "sensor/base/simd.h"

namespace {

using camsim::SobolDraw;
using camsim::SobolSampler;

constexpr int kTile = 64;  // pixel samples: a 64 × 64 tile, 2 samples each
constexpr int kSamples = 2;
constexpr int kDimensions = 32;  // ≈ a path of seven bounces (4 dimensions each)
constexpr std::uint64_t kSeed = 7;

struct Lanes {
  std::vector<std::uint64_t> pixelKeys;
  std::vector<std::uint32_t> reversedIndices;
};

Lanes makeLanes() {
  Lanes lanes;
  for (int y = 0; y < kTile; ++y)
    for (int x = 0; x < kTile; ++x)
      for (int s = 0; s < kSamples; ++s) {
        lanes.pixelKeys.push_back(SobolSampler::pixelKeyOf(kSeed, {x, y}));
        lanes.reversedIndices.push_back(camsim::sobol::reverseBits(static_cast<std::uint32_t>(s)));
      }
  return lanes;
}

// out[d·n + i]: dimension d of pixel sample i, drawn through the sampler's get1D.
void drawn(SobolDraw draw, std::vector<float>& out) {
  SobolSampler sampler(kSeed, draw);
  const size_t n = static_cast<size_t>(kTile * kTile * kSamples);
  size_t i = 0;
  for (int y = 0; y < kTile; ++y)
    for (int x = 0; x < kTile; ++x)
      for (int s = 0; s < kSamples; ++s, ++i) {
        sampler.startPixelSample({x, y}, s);
        for (int d = 0; d < kDimensions; ++d) out[static_cast<size_t>(d) * n + i] = sampler.get1D();
      }
}

// The same dimension for every pixel sample: a loop the compiler can vectorise. Inlined
// into each of the two builds below.
inline void lanes(const Lanes& lanes, std::vector<float>& out) {
  const size_t n = lanes.pixelKeys.size();
  for (int d = 0; d < kDimensions; ++d) {
    float* row = out.data() + static_cast<size_t>(d) * n;
    for (size_t i = 0; i < n; ++i)
      row[i] = SobolSampler::number1D(lanes.pixelKeys[i], lanes.reversedIndices[i], d);
  }
}

void lanesBaseline(const Lanes& l, std::vector<float>& out) {
  lanes(l, out);
}

// Called only if simd::cpuHasAvx2() (in the portable build: never, and without the target).
CAMSIM_TARGET_AVX2 void lanesAvx2(const Lanes& l, std::vector<float>& out) {
  lanes(l, out);
}

template <typename F>
double bestNsPerNumber(int rounds, F&& run) {
  const double numbers = static_cast<double>(kTile * kTile * kSamples) * kDimensions * rounds;
  double best = std::numeric_limits<double>::infinity();
  for (int repeat = 0; repeat < 5; ++repeat) {
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < rounds; ++r) run();
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best = std::min(best, s * 1e9 / numbers);
  }
  return best;
}

size_t mismatches(const std::vector<float>& a, const std::vector<float>& b) {
  size_t count = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(&a[i], &b[i], sizeof(float)) != 0) ++count;
  return count;
}

}  // namespace

int main(int argc, char** argv) {
  const std::optional<int> parsed = camsim::bench::parseRounds(argc, argv, "sobol_lanes_bench", 64);
  if (!parsed) return 2;
  const int rounds = *parsed;
  const Lanes lanes = makeLanes();
  const size_t total = lanes.pixelKeys.size() * kDimensions;
  std::vector<float> reference(total), sampler(total), baseline(total), avx2(total);
  drawn(SobolDraw::kOneAtATime, reference);
  drawn(SobolDraw::kAuto, sampler);
  lanesBaseline(lanes, baseline);
  const bool haveAvx2 = camsim::simd::cpuHasAvx2();
  if (haveAvx2) lanesAvx2(lanes, avx2);

  const double tOne = bestNsPerNumber(rounds, [&] { drawn(SobolDraw::kOneAtATime, reference); });
  const double tSampler = bestNsPerNumber(rounds, [&] { drawn(SobolDraw::kAuto, sampler); });
  const double tBase = bestNsPerNumber(rounds, [&] { lanesBaseline(lanes, baseline); });
  std::printf("Sobol' numbers, %zu pixel samples x %d dimensions, best of 5 x %d rounds:\n",
              lanes.pixelKeys.size(), kDimensions, rounds);
  std::printf("  %-34s %6.2f ns/number  1.00x\n", "get1D, one at a time", tOne);
  std::printf("  %-34s %6.2f ns/number  %.2fx  mismatches %zu\n",
              SobolSampler(kSeed).drawsBlocks() ? "get1D, AVX2 blocks"
                                                : "get1D, default (no AVX2: one at a time)",
              tSampler, tOne / tSampler, mismatches(reference, sampler));
  std::printf("  %-34s %6.2f ns/number  %.2fx  mismatches %zu\n", "lanes, the build's target",
              tBase, tOne / tBase, mismatches(reference, baseline));
  if (haveAvx2) {
    const double tAvx = bestNsPerNumber(rounds, [&] { lanesAvx2(lanes, avx2); });
    std::printf("  %-34s %6.2f ns/number  %.2fx  mismatches %zu\n", "lanes, AVX2", tAvx,
                tOne / tAvx, mismatches(reference, avx2));
  } else {
    std::printf("  lanes, AVX2: %s\n",
                CAMSIM_SIMD_X86 ? "this CPU has no AVX2" : "not built (portable build)");
  }
  const bool equal = mismatches(reference, sampler) == 0 && mismatches(reference, baseline) == 0 &&
                     (!haveAvx2 || mismatches(reference, avx2) == 0);
  if (!equal) std::fprintf(stderr, "sobol_lanes_bench: the variants' numbers differ\n");
  return equal ? 0 : 1;
}
