// What every Sampler (integrator/sampling/sampler.h) promises, checked the same way for each:
// numbers depend only on (seed, pixel, sample index, dimension) — not on the draws before
// nor on the sampler object — and another seed gives other numbers; a draw, 1D or 2D, takes
// one dimension — the number after a 2D draw at d is the one at d + 1, and a 2D draw's x is
// the 1D number of the same dimension.
#pragma once

#include <gtest/gtest.h>

#include "integrator/sampling/sampler.h"

namespace camsim {

// a and b: two samplers made alike (same kind, seed and options; b may be a copy of a);
// other: the same kind with another seed.
inline void expectNumbersDependOnlyOnPixelSampleAndDimension(Sampler& a, Sampler& b,
                                                             Sampler& other) {
  int sameAcrossSeeds = 0;
  for (int i = 0; i < 64; ++i) {
    a.startPixelSample({3, 4}, i);
    a.setDimension(kDimLens);
    const glm::vec2 pa = a.get2D();
    b.startPixelSample({3, 4}, i);
    b.setDimension(kDimWavelength);
    b.get1D();
    b.get2D();                                   // kDimPixel
    EXPECT_EQ(pa, b.get2D()) << "sample " << i;  // reached by drawing
    b.get1D();
    b.setDimension(kDimLens);
    EXPECT_EQ(pa, b.get2D()) << "sample " << i;  // jumped back to
    other.startPixelSample({3, 4}, i);
    other.setDimension(kDimLens);
    sameAcrossSeeds += other.get2D() == pa ? 1 : 0;
  }
  EXPECT_EQ(sameAcrossSeeds, 0);
}

// a and b: two samplers made alike (same kind, seed and options).
inline void expectEveryDrawTakesOneDimension(Sampler& a, Sampler& b) {
  for (int i = 0; i < 32; ++i) {
    a.startPixelSample({5, 6}, i);
    b.startPixelSample({5, 6}, i);
    a.setDimension(kDimPath);
    const glm::vec2 p = a.get2D();
    const float next = a.get1D();
    b.setDimension(kDimPath);
    EXPECT_EQ(p.x, b.get1D()) << "sample " << i;
    b.setDimension(kDimPath + 1);
    EXPECT_EQ(next, b.get1D()) << "sample " << i;
  }
}

}  // namespace camsim
