// PsfGrid: the stop's Fraunhofer PSF (StopPsf::analytic) tabulated on a Cartesian grid in
// the film's axes, sampled exactly from the table, and integrated exactly over any
// axis-aligned box — what diffraction's per-wavelength weights need (diffraction.h).
//
// | parameter | unit | meaning |
// |-----------|------|---------|
// | blades, rotation | —, rad | the stop's shape and turn (ApertureShape); the grid is in film axes |
// | u         | λN_w | image-plane offset from the geometric image point, x right, y up |
// | p(u)      | (λN_w)⁻² | the table's density: ∫ p d²u = 1 over the grid |
// | M(box)    | —    | the table's probability inside an axis-aligned box [lo, hi] |
//
// The grid: per axis the edges ±b·sinh(k/a), k = 0 … K (b/a = 1/16 λN_w at the centre, a
// ratio e^{1/a} = 1.02 per cell far out) up to kExtent = 256
// λN_w, so 2K cells per axis. A cell's probability is the analytic PSF integrated over it
// (two-point Gauss–Legendre on sub-cells of at most ½ λN_w per side; the circle's Airy
// pattern read from radial tables; the PSF's central symmetry p(−u) = p(u) computes half the
// cells, an unturned N-gon's mirror in the x axis a quarter, the circle's x ↔ y symmetry an
// eighth), normalised to 1; the energy past the grid is
// truncatedEnergy(). Sampling picks a cell with its probability and a point uniform in it.
//
// Box integrals: with S(i, j) the summed probability of the cells below column i and row j,
// the cumulative C(x, y) = M((−∞, x] × (−∞, y]) is bilinear inside each cell (the density
// is constant there): C = S₀₀ + f·(S₁₀ − S₀₀) + g·(S₀₁ − S₀₀) + f·g·m, with (f, g) the point's
// fractions in its cell and m the cell's probability. Then
//   M([lo, hi]) = C(hi.x, hi.y) − C(lo.x, hi.y) − C(hi.x, lo.y) + C(lo.x, lo.y),
// exact for the sampled distribution (to double rounding, ~1e-16 of S).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>

#include "integrator/camera/aperture.h"

namespace camsim {

class PsfGrid {
 public:
  static constexpr double kExtent = 256.0;  // λN_w: the grid's half-width

  explicit PsfGrid(const ApertureShape& stop);
  // The shared grid of a stop (built once per blade count and rotation, then kept;
  // thread-safe).
  static std::shared_ptr<const PsfGrid> forStop(const ApertureShape& stop);

  // An offset u (λN_w, film axes) with density density(u), from uniform numbers in [0,1)².
  glm::dvec2 sample(glm::vec2 u) const;
  // The table's density at u ((λN_w)⁻²); 0 past the grid.
  double density(glm::dvec2 u) const;
  // The table's probability inside the box [lo, hi] (λN_w; lo ≤ hi componentwise).
  double boxMass(glm::dvec2 lo, glm::dvec2 hi) const;
  // The PSF's energy past the grid, left out of the table (fraction of the total).
  double truncatedEnergy() const { return truncated_; }

  int cellsPerAxis() const { return cells_; }
  // Edge k (λN_w) of either axis, k = 0 … cellsPerAxis(); edge(cellsPerAxis()/2) = 0.
  double edge(int k) const { return edges_[static_cast<size_t>(k)]; }

 private:
  // The cell along an axis that x lies in and x's fraction across it, clamped to the grid
  // (below: cell 0, fraction 0; above: the last cell, fraction 1).
  struct AxisPosition {
    int cell;
    double fraction;
  };
  AxisPosition locate(double x) const;
  double cumulative(AxisPosition x, AxisPosition y) const;
  double summed(int i, int j) const {
    return summed_[static_cast<size_t>(j) * static_cast<size_t>(cells_ + 1) +
                   static_cast<size_t>(i)];
  }

  // Guide buckets per λN_w for locate(): no cell is narrower (the centre's is 1/16 λN_w).
  static constexpr double kGuidePerUnit = 16.0;
  // sample()'s guides: the rows' cumulative and each row's own cut into equal shares of
  // probability; a share's search starts between its two bounds (a few cells, not log₂ 514
  // probes through two 4 KB rows).
  static constexpr size_t kRowShares = 1024, kColumnShares = 64;

  int cells_ = 0;               // per axis
  std::vector<int> guide_;      // per bucket of |x|: the first cell it meets, from the centre
  std::vector<double> edges_;   // cells_ + 1 (λN_w)
  std::vector<double> summed_;  // (cells_ + 1)², S(i, j)
  // cells_ + 1: R(j) = S(cells_, j), the rows' cumulative — a deliberate contiguous copy of
  // the summed table's last column, so that sample()'s row search reads 4 KB in order
  // instead of one cache line per row (the column is strided by a whole row).
  std::vector<double> rows_;
  std::vector<std::uint16_t> rowGuide_;     // kRowShares + 1 (buildGuide, psf_grid.cpp)
  std::vector<std::uint16_t> columnGuide_;  // per row kColumnShares + 1
  double truncated_ = 0.0;
};

}  // namespace camsim
