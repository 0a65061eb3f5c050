// The SD-tree (integrator/render/sd_tree.h): the cylindrical map, the directional
// quadtree's density (integrates to 1 over the sphere; its samples follow it) and the
// spatial tree's refinement. Records come from fixed-seed hashes: every number is fixed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include "integrator/render/path_guide.h"
#include "integrator/render/sd_tree.h"
#include "integrator/sampling/rng.h"

namespace camsim::sd_tree_test {
namespace {

constexpr double kPi = 3.14159265358979323846;

float uniform(std::uint64_t i, std::uint64_t salt) {
  return unitFloat(static_cast<std::uint32_t>(mix64(hashValues(i, salt)) >> 32));
}

// A quadtree trained twice (record, refine, record) on a peaked energy: records uniform on
// the square with weight exp(−|p − (0.3, 0.7)|²/(2·0.05²)) plus a uniform floor of 10⁻³.
DirectionalQuadtree peakedTree() {
  DirectionalQuadtree tree;
  for (int pass = 0; pass < 3; ++pass) {
    DirectionalQuadtree next = pass == 0 ? DirectionalQuadtree() : tree.refined();
    for (std::uint64_t i = 0; i < 20000; ++i) {
      const glm::vec2 p(uniform(i, 1 + pass), uniform(i, 11 + pass));
      const float d2 = glm::dot(p - glm::vec2(0.3f, 0.7f), p - glm::vec2(0.3f, 0.7f));
      next.record(p, std::exp(-d2 / (2.0f * 0.05f * 0.05f)) + 1e-3f);
    }
    tree = std::move(next);
  }
  return tree;
}

TEST(SdTree, CylindricalMapRoundTrips) {
  for (std::uint64_t i = 0; i < 1000; ++i) {
    const glm::vec2 p(uniform(i, 3), uniform(i, 4));
    const glm::vec3 w = squareToDirection(p);
    EXPECT_NEAR(glm::length(w), 1.0f, 1e-5f);
    const glm::vec2 back = directionToSquare(w);
    EXPECT_NEAR(back.x, p.x, 1e-5f);
    // φ wraps: compare on the circle.
    const float dv = std::abs(back.y - p.y);
    EXPECT_LT(std::min(dv, 1.0f - dv), 1e-5f);
  }
}

// The map's azimuth is a polynomial atan2 (sd_tree.cpp): against atan2 in double over
// 400 000 directions on all octants (and the axes), φ = 2πv within 8·10⁻⁷ rad on the
// circle (measured 5.7·10⁻⁷: the polynomial's 1.4·10⁻⁷ plus float's rounding of v near 1,
// an ulp of 6·10⁻⁸ = 3.7·10⁻⁷ rad; a wrong coefficient errs by 10⁻⁵ or more), v in [0, 1].
TEST(SdTree, AzimuthMatchesAtan2) {
  double worst = 0.0;
  for (std::uint64_t i = 0; i < 400000; ++i) {
    glm::vec3 w = squareToDirection({uniform(i, 11), uniform(i, 12)});
    if (i % 1000 == 0) w = glm::vec3(i % 3000 == 0 ? 1.0f : -1.0f, 0.0f, 0.0f);
    if (i % 1000 == 500) w = glm::vec3(0.0f, i % 2000 == 500 ? 1.0f : -1.0f, 0.0f);
    const float v = directionToSquare(w).y;
    ASSERT_GE(v, 0.0f);
    ASSERT_LE(v, 1.0f);
    double ref = std::atan2(static_cast<double>(w.y), static_cast<double>(w.x));
    if (ref < 0.0) ref += 2.0 * std::numbers::pi;
    double d = std::abs(2.0 * std::numbers::pi * static_cast<double>(v) - ref);
    d = std::min(d, 2.0 * std::numbers::pi - d);
    worst = std::max(worst, d);
  }
  std::printf("[measured] azimuth: worst error %.3g rad\n", worst);
  EXPECT_LT(worst, 8e-7);
}

TEST(SdTree, RefinementFollowsTheEnergy) {
  const DirectionalQuadtree tree = peakedTree();
  EXPECT_GT(tree.nodeCount(), 8u);    // subdivided around the peak …
  EXPECT_LT(tree.nodeCount(), 400u);  // … not everywhere: ≤ 1/ρ cells per level
  EXPECT_GT(tree.pdf({0.3f, 0.7f}), 20.0f * tree.pdf({0.8f, 0.2f}));
}

// ∫ p_Ω dω over the sphere, numerically, two ways:
//  - midpoint rule in (z = cos θ, φ) on a 2048² grid, dω = dz dφ, directions built with
//    trig (not squareToDirection): the grid is aligned with the tree's cells (none finer
//    than 2⁻¹¹ here), so the sum is exact up to float rounding: 1 within 10⁻⁵;
//  - midpoint rule in (θ, φ) with sin θ dθ dφ, 2048 × 4096, which also checks the map's
//    Jacobian 1/(4π) but cuts the cells' edges: 1 within 1 % (measured 0.25 %).
// An empty tree is uniform on the sphere.
TEST(SdTree, GuidePdfIntegratesToOneOverTheSphere) {
  const DirectionalQuadtree tree = peakedTree();
  const auto direction = [](double z, double phi) {
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return glm::vec3(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
                     static_cast<float>(z));
  };
  const int n = 2048;
  double aligned = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      aligned += static_cast<double>(
          PathGuide::pdf(tree, direction(-1.0 + (i + 0.5) * 2.0 / n, (j + 0.5) * 2.0 * kPi / n)));
  aligned *= (2.0 / n) * (2.0 * kPi / n);
  const int nTheta = 2048, nPhi = 4096;
  double sum = 0.0;
  for (int i = 0; i < nTheta; ++i) {
    const double theta = (i + 0.5) * kPi / nTheta;
    double ring = 0.0;
    for (int j = 0; j < nPhi; ++j)
      ring += static_cast<double>(
          PathGuide::pdf(tree, direction(std::cos(theta), (j + 0.5) * 2.0 * kPi / nPhi)));
    sum += ring * std::sin(theta);
  }
  const double byTheta = sum * (kPi / nTheta) * (2.0 * kPi / nPhi);
  std::printf("[measured] guide pdf over the sphere: %.7f (z, phi grid), %.5f (theta, phi)\n",
              aligned, byTheta);
  EXPECT_NEAR(aligned, 1.0, 1e-5);
  EXPECT_NEAR(byTheta, 1.0, 1e-2);
  EXPECT_NEAR(PathGuide::pdf(DirectionalQuadtree(), {0.0f, 0.0f, 1.0f}), 1.0 / (4.0 * kPi), 1e-7);
}

// 400 000 samples binned on a 16 × 16 grid of the square against the pdf's integral per bin
// (midpoint rule, 64² points per bin): each bin within 5σ of its binomial count + 1 %; the
// density sample() reports is pdf() at the point (but on cell edges).
TEST(SdTree, SamplesFollowThePdf) {
  const DirectionalQuadtree tree = peakedTree();
  const int bins = 16, n = 400000;
  std::vector<int> count(bins * bins, 0);
  int offEdge = 0;
  for (int i = 0; i < n; ++i) {
    float density = 0.0f;
    const glm::vec2 p = tree.sample(
        {uniform(static_cast<std::uint64_t>(i), 21), uniform(static_cast<std::uint64_t>(i), 22)},
        &density);
    // The density met on the way down is pdf() at the point, except where float rounding
    // put the point on the edge of the next cell (counted: ≤ 10⁻⁴ of the samples).
    if (std::abs(density - tree.pdf(p)) > 1e-5f * density) ++offEdge;
    ASSERT_TRUE(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f);
    ++count[static_cast<int>(p.y * bins) * bins + static_cast<int>(p.x * bins)];
  }
  std::printf("[measured] %d of %d samples on a cell edge\n", offEdge, n);
  EXPECT_LE(offEdge, n / 10000);
  const int m = 64;
  for (int by = 0; by < bins; ++by)
    for (int bx = 0; bx < bins; ++bx) {
      double mass = 0.0;
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i)
          mass += static_cast<double>(
              tree.pdf({(static_cast<float>(bx) + (static_cast<float>(i) + 0.5f) / m) / bins,
                        (static_cast<float>(by) + (static_cast<float>(j) + 0.5f) / m) / bins}));
      mass /= static_cast<double>(m * m * bins * bins);
      const double expected = mass * n;
      const double sigma = std::sqrt(expected * (1.0 - mass)) + 1.0;
      EXPECT_NEAR(count[by * bins + bx], expected, 5.0 * sigma + 0.01 * expected)
          << "bin " << bx << "," << by;
    }
}

// 100 000 records spread over the cube: iteration 0's threshold (kSpatialC = 4000) splits
// the root into 2^5 = 32 leaves (100 000 / 2^5 ≈ 3125 ≤ 4000); every leaf then samples the
// parent's density and source lobe, and leafAt finds a leaf for any point, inside or outside the cube.
TEST(SdTree, SpatialRefinement) {
  SDTree tree({-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f});
  for (std::uint64_t i = 0; i < 100000; ++i) {
    const glm::vec3 p(2.0f * uniform(i, 31) - 1.0f, 2.0f * uniform(i, 32) - 1.0f,
                      2.0f * uniform(i, 33) - 1.0f);
    // Every record's light left one point: each leaf's source lobe is that point.
    tree.record(p, directionToSquare(glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f))), 1.0f,
                {0.5f, 4.0f, -0.25f}, 2.0f);
  }
  tree.refine(0);
  EXPECT_EQ(tree.leafCount(), 32u);
  for (std::size_t l = 0; l < tree.leafCount(); ++l) {
    const GuideLeaf& leaf = tree.leaf(static_cast<int>(l));
    EXPECT_FLOAT_EQ(leaf.sampling.total(), 100000.0f);
    EXPECT_NEAR(glm::length(leaf.lobe.centre - glm::vec3(0.5f, 4.0f, -0.25f)), 0.0f, 1e-5f);
    EXPECT_FLOAT_EQ(leaf.lobe.spread2, SourceLobe::kMinSpread);
  }
  EXPECT_GE(tree.leafAt({5.0f, -5.0f, 0.0f}), 0);
  EXPECT_NE(tree.leafAt({-0.9f, -0.9f, -0.9f}), tree.leafAt({0.9f, 0.9f, 0.9f}));
  tree.freeze();
  EXPECT_GT(tree.bytes(), 32u * sizeof(GuideLeaf));
}

}  // namespace
}  // namespace camsim::sd_tree_test
