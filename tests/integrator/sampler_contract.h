// What every Sampler (integrator/sampler.h) promises, checked the same way for each:
// a draw, 1D or 2D, takes one dimension — the number after a 2D draw at d is the one at
// d + 1, and a 2D draw's x is the 1D number of the same dimension.
#pragma once

#include <gtest/gtest.h>

#include "integrator/sampler.h"

namespace camsim {

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
