// solidAngleDensity (integrator/camera/projection.h): whole-image sums against the solid
// angle the image covers, the pinhole's cos³θ / f², and every model against a central finite
// difference of unproject.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "integrator/camera/projection.h"
#include "tests/integrator/camera/projection_cases.h"

namespace camsim {
namespace {

double sumOverPixels(const Projection& p, glm::ivec2 size) {
  double sum = 0.0;
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x) sum += solidAngleDensity(p, glm::dvec2(x, y));
  return sum;
}

// A full-sphere equirectangular image: 720×360 pixels, the midpoint rule on cos φ (relative
// error ≈ Δφ²/24 = 3e-6).
TEST(ProjectionDensity, FullEquirectangularImageCoversTheSphere) {
  Projection p;
  p.model = ProjectionModel::kEquirectangular;
  p.fx = 720.0 / (2.0 * std::numbers::pi);
  p.fy = 360.0 / std::numbers::pi;
  p.cx = 359.5;
  p.cy = 179.5;
  const double sum = sumOverPixels(p, {720, 360});
  std::printf("equirectangular 720x360: sum dΩ/dA = %.9f, 4π = %.9f (rel. %.2g)\n", sum,
              4 * std::numbers::pi, sum / (4 * std::numbers::pi) - 1);
  EXPECT_NEAR(sum / (4.0 * std::numbers::pi), 1.0, 1e-5);
}

// An equidistant 180° image circle of radius 471 px: the pixel centres inside it cover the
// hemisphere; the circle's edge cuts pixels, so the tolerance is 2e-4 (measured: see output).
TEST(ProjectionDensity, EquidistantHemisphereCoversTwoPi) {
  Projection p;
  p.model = ProjectionModel::kEquidistant;
  p.fx = p.fy = 300.0;
  p.cx = p.cy = 499.5;
  p.maxFieldAngle = 0.5 * std::numbers::pi;
  const double sum = sumOverPixels(p, {1000, 1000});
  std::printf("equidistant 180°: sum dΩ/dA = %.9f, 2π = %.9f (rel. %.2g)\n", sum,
              2 * std::numbers::pi, sum / (2 * std::numbers::pi) - 1);
  EXPECT_NEAR(sum / (2.0 * std::numbers::pi), 1.0, 2e-5);
  // And an equisolid (equal-area) full sphere: dΩ/dA = 1/(fx fy) everywhere inside.
  p.model = ProjectionModel::kEquisolid;
  p.maxFieldAngle = std::numbers::pi;
  p.fx = p.fy = 240.0;
  EXPECT_DOUBLE_EQ(solidAngleDensity(p, {700.0, 300.0}), 1.0 / (240.0 * 240.0));
  const double sphere = sumOverPixels(p, {1000, 1000});
  std::printf("equisolid 360°: sum dΩ/dA = %.9f, 4π = %.9f (rel. %.2g)\n", sphere,
              4 * std::numbers::pi, sphere / (4 * std::numbers::pi) - 1);
  EXPECT_NEAR(sphere / (4.0 * std::numbers::pi), 1.0, 1e-4);
}

TEST(ProjectionDensity, PinholeIsCosCubedOverFSquared) {
  Projection p;  // opencv without distortion
  p.fx = p.fy = 450.0;
  for (int y = 0; y < 480; y += 7)
    for (int x = 0; x < 640; x += 7) {
      const double dx = x - p.cx, dy = y - p.cy;
      const double cosTheta = p.fx / std::sqrt(dx * dx + dy * dy + p.fx * p.fx);
      const double expected = cosTheta * cosTheta * cosTheta / (p.fx * p.fy);
      EXPECT_NEAR(solidAngleDensity(p, glm::dvec2(x, y)) / expected, 1.0, 1e-13);
    }
}

// dΩ/dA = |ω · (∂ω/∂u × ∂ω/∂v)| with central differences of unproject (h = 1e-4 px),
// within 1e-6 relative, at pixels whose difference stencil lies inside the image and, for
// the radial models, inside 99 % of the image circle's radius: orthographic, equisolid at
// 180° and unified with ξ > 1 are singular at their rim (dρ/dθ = 0), where a finite
// difference loses its accuracy.
TEST(ProjectionDensity, EveryModelMatchesAFiniteDifferenceOfUnproject) {
  const double h = 1e-4;
  for (const test::ProjectionCase& c : test::projectionCases()) {
    double worst = 0.0;
    int checked = 0;
    for (int y = 1; y < c.size.y; y += 11)
      for (int x = 1; x < c.size.x; x += 11) {
        const glm::dvec2 px(x + 0.25, y + 0.4);
        const glm::dvec2 m = (px - glm::dvec2(c.p.cx, c.p.cy)) / glm::dvec2(c.p.fx, c.p.fy);
        if (c.imageRadius > 0.0 && glm::length(m) > 0.99 * c.imageRadius) continue;
        const auto ux0 = unproject(c.p, px - glm::dvec2(h, 0.0)),
                   ux1 = unproject(c.p, px + glm::dvec2(h, 0.0)),
                   uy0 = unproject(c.p, px - glm::dvec2(0.0, h)),
                   uy1 = unproject(c.p, px + glm::dvec2(0.0, h)), w = unproject(c.p, px);
        if (!ux0 || !ux1 || !uy0 || !uy1 || !w) {
          EXPECT_TRUE(!w || solidAngleDensity(c.p, px) > 0.0) << c.name;
          continue;
        }
        const double numeric =
            std::abs(glm::dot(*w, glm::cross((*ux1 - *ux0) / (2 * h), (*uy1 - *uy0) / (2 * h))));
        const double analytic = solidAngleDensity(c.p, px);
        worst = std::max(worst, std::abs(analytic / numeric - 1.0));
        ++checked;
      }
    std::printf("%-16s dΩ/dA vs finite difference: %d pixels, largest relative difference %.3g\n",
                c.name, checked, worst);
    EXPECT_GT(checked, 500) << c.name;
    EXPECT_LE(worst, 1e-6) << c.name;
  }
}

TEST(ProjectionDensity, ZeroOutsideTheImageCircle) {
  for (const test::ProjectionCase& c : test::projectionCases()) {
    if (c.p.model == ProjectionModel::kOpenCv) continue;  // no image circle
    const glm::dvec2 far(c.p.cx + 50.0 * c.p.fx * 8.0, c.p.cy);
    EXPECT_FALSE(unproject(c.p, far)) << c.name;
    EXPECT_EQ(solidAngleDensity(c.p, far), 0.0) << c.name;
  }
}

}  // namespace
}  // namespace camsim
