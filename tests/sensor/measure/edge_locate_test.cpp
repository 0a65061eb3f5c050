// Tests of the edge location (sensor/measure/edge_locate.h): the polynomial fit is exact on
// polynomial data; the per-row centroids of a synthesised edge lie on it; a falling edge is
// found with rising = false; rows without an edge are left out of the fit.
#include "sensor/measure/edge_locate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/support/slanted_edge_image.h"

namespace camsim {
namespace edge_locate_test {

TEST(EdgeLocate, PolynomialFitIsExactOnPolynomials) {
  std::vector<double> x, line, parabola;
  for (int i = 0; i < 50; ++i) {
    x.push_back(100.0 + i);  // far from 0: the centred, scaled fit keeps its accuracy
    line.push_back(3.0 - 0.25 * x.back());
    parabola.push_back(1.0 + 0.5 * x.back() - 2e-3 * x.back() * x.back());
  }
  const std::vector<double> c1 = fitPolynomial(x, line, 1);
  ASSERT_EQ(c1.size(), 2u);
  EXPECT_NEAR(c1[0], 3.0, 1e-9);
  EXPECT_NEAR(c1[1], -0.25, 1e-12);
  const std::vector<double> c2 = fitPolynomial(x, parabola, 2);
  ASSERT_EQ(c2.size(), 3u);
  EXPECT_NEAR(c2[0], 1.0, 1e-7);
  EXPECT_NEAR(c2[1], 0.5, 1e-9);
  EXPECT_NEAR(c2[2], -2e-3, 1e-12);
  // One abscissa only: flat at the mean.
  const std::vector<double> flat = fitPolynomial({2.0, 2.0, 2.0}, {1.0, 2.0, 3.0}, 1);
  EXPECT_DOUBLE_EQ(flat[0], 2.0);
  EXPECT_DOUBLE_EQ(flat[1], 0.0);
}

EdgePatch patchOf(const Image& img) {
  EdgePatch p;
  p.rows = img.height;
  p.cols = img.width;
  for (float v : img.pixels) p.values.push_back(v);
  return p;
}

TEST(EdgeLocate, RowCentroidsLieOnTheSynthesisedEdge) {
  for (const bool falling : {false, true}) {
    test::SyntheticEdge e;  // through (32.3, 64), 5°, σ = 0.5 px
    e.centreX = 32.3;
    if (falling) std::swap(e.dark, e.bright);
    const EdgePatch p = patchOf(test::syntheticEdgeImage(e));
    const EdgeSides sides = edgeSides(p);
    EXPECT_EQ(sides.high > sides.low, !falling);
    EXPECT_NEAR(std::abs(sides.contrast()), 0.8, 1e-3);
    const EdgeLocation loc = locateEdge(p, !falling, 1);
    EXPECT_EQ(loc.rowsFitted, 128);
    const double s = std::tan(5.0 * std::numbers::pi / 180.0);
    EXPECT_NEAR(loc.line.coefficients[1], s, 2e-4);
    EXPECT_NEAR(loc.line.at(64.0), 32.3, 0.01);
    for (int r = 0; r < 128; r += 16)
      EXPECT_NEAR(loc.rowCentroids[static_cast<size_t>(r)], 32.3 + s * (r + 0.5 - 64.0), 0.05) << r;
  }
}

TEST(EdgeLocate, RowsWithoutAnEdgeAreLeftOut) {
  test::SyntheticEdge e;
  Image img = test::syntheticEdgeImage(e);
  for (int x = 0; x < 64; ++x) img.at(x, 10, 0) = 0.5f;  // a flat row
  const EdgeLocation loc = locateEdge(patchOf(img), true, 1);
  EXPECT_FALSE(loc.rowUsed[10]);
  EXPECT_EQ(loc.rowsFitted, 127);
  EXPECT_NEAR(loc.line.at(64.0), 32.0, 0.01);
}

}  // namespace edge_locate_test
}  // namespace camsim
