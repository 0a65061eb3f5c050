// Aperture: area set by the f-number whatever the blade count; samples uniform inside.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "integrator/camera/aperture.h"
#include "integrator/sampling/rng.h"

namespace camsim {
namespace {

bool insidePolygon(glm::dvec2 p, int n, double R, double rotation) {
  for (int k = 0; k < n; ++k) {
    const double a0 = rotation + 2.0 * M_PI * k / n, a1 = rotation + 2.0 * M_PI * (k + 1) / n;
    const glm::dvec2 v0(R * std::cos(a0), R * std::sin(a0)), v1(R * std::cos(a1), R * std::sin(a1));
    const double cross = (v1.x - v0.x) * (p.y - v0.y) - (v1.y - v0.y) * (p.x - v0.x);
    if (cross < -1e-9 * R * R) return false;
  }
  return true;
}

TEST(Aperture, PolygonHasTheCircleAreaAndUniformSamplesInside) {
  const double D = 0.01;
  for (int blades : {0, 3, 5, 6, 9}) {
    const Aperture a(D, blades, 0.3);
    EXPECT_NEAR(a.area(), M_PI * 0.25 * D * D, 1e-15);
    if (blades > 0) {
      const double polygonArea =
          0.5 * blades * a.circumradius() * a.circumradius() * std::sin(2.0 * M_PI / blades);
      EXPECT_NEAR(polygonArea / a.area(), 1.0, 1e-12);
    }
    // Uniformity: the fraction of samples in the central disk of radius ρ equals its area
    // fraction (σ ≈ 0.0014 at n = 2^17; tolerance 0.006).
    Pcg32 rng(3, static_cast<std::uint64_t>(blades));
    constexpr int n = 1 << 17;
    const double rho = 0.3 * D;
    int inDisk = 0;
    for (int i = 0; i < n; ++i) {
      const glm::vec2 u(rng.uniform(), rng.uniform());
      const glm::dvec2 p(a.sample(u));
      if (blades == 0)
        ASSERT_LE(glm::length(p), 0.5 * D * (1.0 + 1e-6));
      else
        ASSERT_TRUE(insidePolygon(p, blades, a.circumradius(), 0.3));
      inDisk += glm::length(p) < rho ? 1 : 0;
    }
    EXPECT_NEAR(static_cast<double>(inDisk) / n, M_PI * rho * rho / a.area(), 0.006)
        << blades << " blades";
  }
}

}  // namespace
}  // namespace camsim
