// PsfGrid: the table's normalisation and closeness to the analytic PSF, its box integrals
// against direct cell sums and against its own samples, its symmetry shortcuts against the
// direct computation, its sampling's exact inversion of the cumulative, and its samples
// against the Airy encircled energy (KS) and the bladed stops' spikes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/vec4.hpp>

#include "integrator/camera/psf_grid.h"
#include "integrator/camera/stop_psf.h"
#include "integrator/sampling/rng.h"

namespace camsim {
namespace psf_grid_test {

// Σ density × area over the cells in columns [i0, i1) and rows [j0, j1).
double cellSum(const PsfGrid& g, int i0, int i1, int j0, int j1) {
  double sum = 0.0;
  for (int j = j0; j < j1; ++j)
    for (int i = i0; i < i1; ++i) {
      const double w = g.edge(i + 1) - g.edge(i), h = g.edge(j + 1) - g.edge(j);
      sum += g.density({g.edge(i) + 0.5 * w, g.edge(j) + 0.5 * h}) * w * h;
    }
  return sum;
}

// The centre of the cell that u lies in.
glm::dvec2 cellCentre(const PsfGrid& g, glm::dvec2 u) {
  glm::dvec2 centre(0.0);
  for (int axis = 0; axis < 2; ++axis) {
    int i = 0;
    while (g.edge(i + 1) <= u[axis]) ++i;
    centre[axis] = 0.5 * (g.edge(i) + g.edge(i + 1));
  }
  return centre;
}

// Σ density × cell area = 1; the energy past the grid is small and, for the circle, between
// the Airy energy outside the grid's circumscribed and inscribed circles; near the centre,
// where cells are 1/16 λN wide, a cell's density is the PSF at its centre within 2 % of the
// peak.
TEST(PsfGrid, TableIsNormalisedAndFollowsThePsf) {
  for (int blades : {0, 3, 6}) {
    const PsfGrid grid(ApertureShape{blades, 0.0});
    const int n = grid.cellsPerAxis();
    EXPECT_NEAR(cellSum(grid, 0, n, 0, n), 1.0, 1e-9) << blades;
    EXPECT_GT(grid.truncatedEnergy(), 3e-4) << blades;
    EXPECT_LT(grid.truncatedEnergy(), 2e-3) << blades;
    EXPECT_GE(grid.edge(n), PsfGrid::kExtent);
    EXPECT_DOUBLE_EQ(grid.edge(n / 2), 0.0);
    EXPECT_EQ(grid.density({PsfGrid::kExtent * 1.1, 0.0}), 0.0);
    const StopPsf psf(blades);
    for (const glm::dvec2 u : {glm::dvec2(0.1, 0.05), glm::dvec2(0.5, -0.2), glm::dvec2(-0.3, 0.6)})
      EXPECT_NEAR(grid.density(u), psf.analytic(cellCentre(grid, u)), 0.02 * 0.25 * M_PI) << blades;
  }
  const PsfGrid circle(ApertureShape{0, 0.0});
  const double e = circle.edge(circle.cellsPerAxis());
  EXPECT_LT(circle.truncatedEnergy(), 1.0 - StopPsf::airyEncircledEnergy(e));
  EXPECT_GT(circle.truncatedEnergy(), 1.0 - StopPsf::airyEncircledEnergy(e * M_SQRT2));
}

// Box integrals: on cell edges, the sum of the cells inside (1e-12); a box and its mirror
// through the centre hold the same (1e-12: the PSF is centrosymmetric); and the share of 2^18 samples inside 12 boxes of all sizes
// and places is the box's probability within 4.5 binomial σ.
TEST(PsfGrid, BoxMassIsExactForTheSampledTable) {
  const PsfGrid grid(ApertureShape{6, 0.4});
  const int h = grid.cellsPerAxis() / 2;
  for (const glm::ivec4 b :
       {glm::ivec4(h - 3, h + 5, h - 20, h + 1), glm::ivec4(h + 40, h + 90, h - 7, h + 7),
        glm::ivec4(0, 2 * h, h, 2 * h)}) {
    const double direct = cellSum(grid, b.x, b.y, b.z, b.w);
    EXPECT_NEAR(grid.boxMass({grid.edge(b.x), grid.edge(b.z)}, {grid.edge(b.y), grid.edge(b.w)}),
                direct, 1e-12);
  }
  EXPECT_NEAR(grid.boxMass({-1e9, -1e9}, {1e9, 1e9}), 1.0, 1e-12);
  // The PSF's central symmetry, p(−u) = p(u), read through negative and positive edges alike.
  for (const auto& [lo, hi] : {std::pair{glm::dvec2(-0.71, 0.13), glm::dvec2(2.3, 0.9)},
                               std::pair{glm::dvec2(0.031, -5.2), glm::dvec2(7.7, 0.4)}})
    EXPECT_NEAR(grid.boxMass(-hi, -lo), grid.boxMass(lo, hi), 1e-12);
  const std::vector<std::pair<glm::dvec2, glm::dvec2>> boxes = {
      {{-0.05, -0.05}, {0.05, 0.05}},   {{0.0, 0.0}, {0.4, 0.3}},
      {{-1.3, 0.2}, {-0.6, 1.1}},       {{0.5, -2.0}, {3.0, -0.9}},
      {{-8.0, -8.0}, {8.0, 8.0}},       {{3.0, 3.0}, {40.0, 40.0}},
      {{-60.0, -5.0}, {-10.0, 5.0}},    {{0.013, -0.4}, {0.021, 0.4}},
      {{-0.3, -0.3}, {0.3, 0.3}},       {{1.0, 1.0}, {2.0, 2.0}},
      {{-200.0, 10.0}, {200.0, 250.0}}, {{-3.0, -1.0}, {-2.5, 6.0}}};
  constexpr int n = 1 << 18;
  std::vector<int> inside(boxes.size(), 0);
  Pcg32 rng(21, 6);
  for (int k = 0; k < n; ++k) {
    const glm::dvec2 u = grid.sample({rng.uniform(), rng.uniform()});
    for (size_t b = 0; b < boxes.size(); ++b)
      inside[b] += u.x >= boxes[b].first.x && u.x < boxes[b].second.x && u.y >= boxes[b].first.y &&
                           u.y < boxes[b].second.y
                       ? 1
                       : 0;
  }
  for (size_t b = 0; b < boxes.size(); ++b) {
    const double p = grid.boxMass(boxes[b].first, boxes[b].second);
    EXPECT_NEAR(static_cast<double>(inside[b]) / n, p, 4.5 * std::sqrt(p * (1.0 - p) / n) + 1e-9)
        << "box " << b;
  }
}

// Sampling inverts the table's cumulative exactly, whatever share of probability its
// guides start the search in: for a sample p from (u_x, u_y), the probability below p.y is
// u_y and, within p's row of cells, the share left of p.x is u_x (1e-9; a wrong row or
// column is off by at least a cell's probability, ≥ 1e-6 near the centre), for random
// numbers and for guide bounds themselves (every b/64 for the columns, every 16th b/1024
// for the rows), 0 and the largest float below 1.
TEST(PsfGrid, SamplingInvertsTheCumulative) {
  for (const ApertureShape stop : {ApertureShape{0, 0.0}, ApertureShape{5, 0.3}}) {
    const PsfGrid grid(stop);
    const int n = grid.cellsPerAxis();
    const double lo = grid.edge(0), hi = grid.edge(n);
    std::vector<glm::vec2> us;
    Pcg32 rng(5, 8);
    for (int k = 0; k < 2000; ++k) us.emplace_back(rng.uniform(), rng.uniform());
    const float below1 = std::nextafter(1.0f, 0.0f);
    for (int b = 0; b <= 64; ++b)
      us.emplace_back(std::min(static_cast<float>(b) / 64.0f, below1),
                      std::min(static_cast<float>(b * 16) / 1024.0f, below1));
    for (const glm::vec2 u : us) {
      const glm::dvec2 p = grid.sample(u);
      EXPECT_NEAR(grid.boxMass({lo, lo}, {hi, p.y}), u.y, 1e-9) << u.x << ", " << u.y;
      int j = 0;
      while (j + 1 < n && grid.edge(j + 1) <= p.y) ++j;
      const double row = grid.boxMass({lo, grid.edge(j)}, {hi, grid.edge(j + 1)});
      ASSERT_GT(row, 0.0);
      EXPECT_NEAR(grid.boxMass({lo, grid.edge(j)}, {p.x, grid.edge(j + 1)}) / row, u.x, 1e-9)
          << u.x << ", " << u.y;
    }
  }
}

// The symmetry shortcuts: a hexagon turned by 60° (computed over half the plane) is the
// unturned one (computed over a quarter) to rounding; the circle (an eighth) is the analytic
// PSF's own integral over an off-axis, off-diagonal block of cells (a 600 × 600 midpoint
// rule), within 5e-5 of the block's probability (measured 1.7e-5: the grid reads the Airy
// pattern from a radial table, linear between points 1/256 λN_w apart).
TEST(PsfGrid, SymmetryShortcutsMatchTheDirectComputation) {
  const PsfGrid turned(ApertureShape{6, M_PI / 3.0}), straight(ApertureShape{6, 0.0});
  for (const glm::dvec4 b : {glm::dvec4(-0.7, -1.9, 0.4, 0.2), glm::dvec4(0.3, 0.1, 5.0, 9.0),
                             glm::dvec4(-40.0, 2.0, -3.0, 30.0)})
    EXPECT_NEAR(turned.boxMass({b.x, b.y}, {b.z, b.w}), straight.boxMass({b.x, b.y}, {b.z, b.w}),
                1e-12);
  const PsfGrid circle(ApertureShape{0, 0.0});
  const StopPsf airy(0);
  const int h = circle.cellsPerAxis() / 2;
  const double x0 = circle.edge(h + 5), x1 = circle.edge(h + 21), y0 = circle.edge(h - 12),
               y1 = circle.edge(h - 2);
  constexpr int m = 600;
  double direct = 0.0;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i)
      direct += airy.analytic({x0 + (i + 0.5) * (x1 - x0) / m, y0 + (j + 0.5) * (y1 - y0) / m});
  direct *= (x1 - x0) * (y1 - y0) / (m * m);
  const double table = circle.boxMass({x0, y0}, {x1, y1}) * (1.0 - circle.truncatedEnergy());
  EXPECT_NEAR(table / direct, 1.0, 5e-5) << table << " vs " << direct;
}

// Samples of the circle's table against the Airy encircled energy E(r)/(1 − truncated) (the
// grid holds all of it within its inscribed radius): the KS distance of the radii to it
// (n = 2^18; critical value at α = 0.001 is 1.95/√n = 0.0038).
TEST(PsfGrid, CircleSamplesFollowTheAiryEncircledEnergy) {
  const PsfGrid grid(ApertureShape{0, 0.0});
  const double norm = 1.0 - grid.truncatedEnergy();
  constexpr int n = 1 << 18;
  Pcg32 rng(17, 3);
  std::vector<double> radii(n);
  for (double& r : radii) {
    const glm::dvec2 u = grid.sample({rng.uniform(), rng.uniform()});
    r = std::hypot(u.x, u.y);
  }
  std::sort(radii.begin(), radii.end());
  double ks = 0.0;
  for (int i = 0; i < n; ++i) {
    const double r = radii[static_cast<size_t>(i)];
    if (r > PsfGrid::kExtent) break;  // past the inscribed circle the square's corners hold
    const double cdf = StopPsf::airyEncircledEnergy(r) / norm;
    ks = std::max({ks, std::abs(cdf - double(i) / n), std::abs(cdf - double(i + 1) / n)});
  }
  EXPECT_LT(ks, 1.95 / std::sqrt(double(n))) << "KS distance " << ks;
  RecordProperty("ks_distance", std::to_string(ks));
}

// Angles (degrees in [0, 360)) of samples whose radius lies in [rMin, rMax] (λN_w).
std::vector<double> sampleAngles(const PsfGrid& grid, int seed, double rMin, double rMax, int n) {
  Pcg32 rng(29, static_cast<std::uint64_t>(seed));
  std::vector<double> angles;
  for (int i = 0; i < n; ++i) {
    const glm::dvec2 u = grid.sample({rng.uniform(), rng.uniform()});
    const double r = std::hypot(u.x, u.y);
    if (r < rMin || r > rMax) continue;
    double a = std::atan2(u.y, u.x) * 180.0 / M_PI;
    angles.push_back(a < 0.0 ? a + 360.0 : a);
  }
  return angles;
}

// Outside the core the N-gon's PSF is its spikes: streaks along the edge normals. For a
// hexagon with a vertex on +x the normals are at 30° + 60°k. Checked on the samples with
// radius 3–64 λN: (1) the count within ±3° of each normal is > 8× the count within ±3° of
// each vertex direction (0° + 60°k); (2) six-fold symmetry: the six 60° sectors centred on
// the normals hold equal counts (chi-square, 5 dof, critical value 20.5 at α = 0.001);
// (3) of 36 bins of 10° centred on 0°, 10°, … the six fullest are those centred on the
// normals. A 5-blade stop (odd) gives ten spikes, at its normals 36° + 72°k and their
// opposites.
TEST(PsfGrid, BladedStopsShowSpikesAlongTheEdgeNormals) {
  const PsfGrid hexagon(ApertureShape{6, 0.0});
  const std::vector<double> angles = sampleAngles(hexagon, 6, 3.0, 64.0, 1 << 19);
  ASSERT_GT(angles.size(), 5000u);
  auto within = [&](double centre, double half) {
    int count = 0;
    for (double a : angles) {
      const double d = std::abs(std::remainder(a - centre, 360.0));
      count += d <= half ? 1 : 0;
    }
    return count;
  };
  std::vector<int> sectors(6);
  for (int k = 0; k < 6; ++k) {
    const int normal = within(30.0 + 60.0 * k, 3.0), vertex = within(60.0 * k, 3.0);
    EXPECT_GT(normal, 8 * vertex) << "normal " << 30 + 60 * k << "°: " << normal << " vs vertex "
                                  << vertex;
    sectors[static_cast<size_t>(k)] = within(30.0 + 60.0 * k, 30.0);
  }
  const double expected = angles.size() / 6.0;
  double chi2 = 0.0;
  for (int s : sectors) chi2 += (s - expected) * (s - expected) / expected;
  EXPECT_LT(chi2, 20.5) << "six-fold symmetry, chi-square " << chi2;
  std::vector<int> bins(36, 0);
  for (double a : angles)  // bin k holds [10k − 5°, 10k + 5°)
    ++bins[static_cast<size_t>(static_cast<int>((a + 5.0) / 10.0) % 36)];
  std::vector<int> order(36);
  for (int i = 0; i < 36; ++i) order[static_cast<size_t>(i)] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return bins[static_cast<size_t>(a)] > bins[static_cast<size_t>(b)];
  });
  std::vector<int> top(order.begin(), order.begin() + 6);
  std::sort(top.begin(), top.end());
  EXPECT_EQ(top, (std::vector<int>{3, 9, 15, 21, 27, 33}));  // 30°, 90°, … 330°

  const PsfGrid pentagon(ApertureShape{5, 0.0});
  const std::vector<double> five = sampleAngles(pentagon, 5, 3.0, 64.0, 1 << 19);
  int spikes = 0, between = 0;
  for (double a : five) {
    // The normals 36° + 72°k and their opposites 216° + 72°k are every multiple of 36°.
    const double d = std::abs(std::remainder(a, 36.0));
    spikes += d <= 2.0 ? 1 : 0;
    between += std::abs(d - 18.0) <= 2.0 ? 1 : 0;
  }
  EXPECT_GT(spikes, 8 * between) << spikes << " vs " << between;
}

}  // namespace psf_grid_test
}  // namespace camsim
