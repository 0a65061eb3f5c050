// sensor/base/simd.h: anyLane agrees with OR-ing the four lanes for every comparison
// result, and the portable path never claims AVX2 (the SIMD path asks the CPU).
#include "sensor/base/simd.h"

#include <gtest/gtest.h>

namespace camsim {
namespace {

TEST(Simd, AnyLaneIsTrueIffSomeLaneIsTrue) {
  for (int bitsSet = 0; bitsSet < 16; ++bitsSet) {
    Int4 mask = {0, 0, 0, 0};
    for (int lane = 0; lane < 4; ++lane)
      if (bitsSet & (1 << lane)) mask[lane] = -1;
    EXPECT_EQ(simd::anyLane(mask), bitsSet != 0) << "lanes " << bitsSet;
  }
  // As the float code produces masks: a lane-wise comparison.
  const Float4 x = {1.0f, 2.0f, 3.0f, 4.0f};
  EXPECT_TRUE(simd::anyLane(x > 3.5f));
  EXPECT_FALSE(simd::anyLane(x > 4.0f));
}

TEST(Simd, PortablePathHasNoAvx2) {
  // The SIMD build asks the CPU; the portable one has no AVX2 code to choose.
  EXPECT_TRUE(CAMSIM_SIMD_X86 || !simd::cpuHasAvx2());
}

}  // namespace
}  // namespace camsim
