// Tests for integrator/geometry/math.h: offsetRayOrigin moves a point out of its error box, along the
// normal, to the requested side; erfInv against std::erf.
#include "integrator/geometry/math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace camsim {
namespace {

// The offset origin lies strictly on w's side of the slab the error box spans along n,
// measured in double: for points from 1e-6 to 1e4 m from the origin (and at it), error
// bounds from 0 to 1e-3 of the coordinates, random unit normals and both sides.
TEST(Math, OffsetRayOriginLeavesTheErrorBox) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const float scales[] = {0.0f, 1e-6f, 1e-2f, 1.0f, 37.0f, 1e4f};
  const float errors[] = {0.0f, 1e-7f, 1e-5f, 1e-3f};
  int checked = 0;
  for (const float scale : scales)
    for (const float relError : errors)
      for (int k = 0; k < 2000; ++k) {
        const glm::vec3 p(u(rng) * scale, u(rng) * scale, u(rng) * scale);
        const glm::vec3 pError = relError * absComponents(p) +
                                 glm::vec3(1e-9f * std::abs(u(rng)));  // some absolute error
        glm::vec3 n(u(rng), u(rng), u(rng));
        if (glm::dot(n, n) < 1e-4f) continue;
        n = glm::normalize(n);
        const glm::vec3 w = (k % 2 ? 1.0f : -1.0f) * n + 0.3f * glm::vec3(u(rng), u(rng), u(rng));
        const glm::vec3 o = offsetRayOrigin(p, pError, n, w);
        const double side = glm::dot(glm::dvec3(w), glm::dvec3(n)) < 0.0 ? -1.0 : 1.0;
        const double along = side * glm::dot(glm::dvec3(o) - glm::dvec3(p), glm::dvec3(n));
        const double extent = glm::dot(glm::abs(glm::dvec3(n)), glm::dvec3(pError));
        ASSERT_GT(along, extent) << "p " << p.x << " " << p.y << " " << p.z << " pError "
                                 << pError.x << " n " << n.x << " " << n.y << " " << n.z;
        // and not much further: the margin is 2⁻²¹ ≈ 4.8e-7 of the coordinates, plus rounding
        ASSERT_LT(along, extent * (1.0 + 1e-5) + 8e-7 * (static_cast<double>(scale) + extent));
        ++checked;
      }
  EXPECT_GT(checked, 40000);
}

// erf(erfInv(x)) = x over (−1, 1) to within single-precision rounding of the result
// (|Δx| ≤ erf′(y)·|y|·4e-7), odd, and finite up to 1 ∓ 1e-7.
TEST(Math, ErfInvInvertsErf) {
  double worst = 0.0;
  for (int i = -99999; i <= 99999; ++i) {
    const float x = static_cast<float>(i) * 1e-5f;
    const double y = erfInv(x);
    const double slope = 2.0 / std::sqrt(M_PI) * std::exp(-y * y);
    const double error = std::abs(std::erf(y) - static_cast<double>(x));
    worst = std::max(worst, error);
    ASSERT_LE(error, slope * std::abs(y) * 4e-7 + 1e-12) << x;
    ASSERT_EQ(erfInv(-x), -erfInv(x)) << x;
  }
  EXPECT_LT(worst, 2e-7);
  EXPECT_EQ(erfInv(1.0f), std::numeric_limits<float>::infinity());
  EXPECT_EQ(erfInv(-1.0f), -std::numeric_limits<float>::infinity());
  for (float x : {1.0f - 1e-7f, 1.0f - 1e-6f}) {
    const double y = erfInv(x);
    EXPECT_TRUE(std::isfinite(y));
    EXPECT_NEAR(std::erfc(y), 1.0 - static_cast<double>(x), 1e-3 * (1.0 - static_cast<double>(x)));
  }
}

}  // namespace
}  // namespace camsim
