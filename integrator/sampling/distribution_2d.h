// PiecewiseConstant2D: samples the unit square [0,1)² with a density proportional to a
// grid of non-negative cell weights f[row][column] (row = v, column = u), by the marginal
// over rows and the conditional over the columns of the chosen row (both
// DiscreteDistribution). Used for environment-map importance sampling.
//
// | parameter | unit | meaning |
// |-----------|------|---------|
// | nu, nv    | —    | columns (u) and rows (v) |
// | f         | any  | weight of cell (i, j), ≥ 0; at least one > 0 |
//
//   p(u, v) = f(i, j) / (mean of f),  i = ⌊u·nu⌋, j = ⌊v·nv⌋   (∫∫ p du dv = 1)
#pragma once

#include <span>
#include <vector>

#include <glm/vec2.hpp>

#include "integrator/sampling/distribution.h"
#include "sensor/base/check.h"

namespace camsim {

struct Sample2D {
  glm::vec2 uv{0.0f};       // in [0,1)²
  int column = 0, row = 0;  // the cell uv lies in
  float pdf = 0.0f;         // density over the unit square
};

class PiecewiseConstant2D {
 public:
  PiecewiseConstant2D() = default;
  // weights: nv rows of nu values, row by row.
  PiecewiseConstant2D(std::span<const double> weights, int nu, int nv) : nu_(nu), nv_(nv) {
    CAMSIM_CHECK(nu > 0 && nv > 0 &&
                 weights.size() == static_cast<size_t>(nu) * static_cast<size_t>(nv));
    std::vector<double> rowSums(static_cast<size_t>(nv), 0.0);
    rows_.reserve(static_cast<size_t>(nv));
    for (int j = 0; j < nv; ++j) {
      const std::span<const double> row = weights.subspan(
          static_cast<size_t>(j) * static_cast<size_t>(nu), static_cast<size_t>(nu));
      for (double w : row) rowSums[static_cast<size_t>(j)] += w;
      rows_.emplace_back(row);
    }
    marginal_ = DiscreteDistribution(rowSums);
  }

  bool empty() const { return !(marginal_.total() > 0.0); }
  int nu() const { return nu_; }
  int nv() const { return nv_; }

  Sample2D sample(glm::vec2 u) const {
    CAMSIM_CHECK(!empty());
    Sample2D s;
    float uRow = 0.0f, uColumn = 0.0f;
    const size_t j = marginal_.sample(u.y, &uRow);
    const size_t i = rows_[j].sample(u.x, &uColumn);
    s.row = static_cast<int>(j);
    s.column = static_cast<int>(i);
    s.uv = {(static_cast<float>(i) + uColumn) / static_cast<float>(nu_),
            (static_cast<float>(j) + uRow) / static_cast<float>(nv_)};
    s.pdf = cellPdf(s.column, s.row);
    return s;
  }

  // Density of the cell (column, row) over the unit square.
  float cellPdf(int column, int row) const {
    const size_t j = static_cast<size_t>(row);
    if (rows_[j].total() <= 0.0) return 0.0f;
    return marginal_.pmf(j) * static_cast<float>(nv_) * rows_[j].pmf(static_cast<size_t>(column)) *
           static_cast<float>(nu_);
  }

  float pdf(glm::vec2 uv) const {
    if (empty()) return 0.0f;
    return cellPdf(clampIndex(uv.x, nu_), clampIndex(uv.y, nv_));
  }

  static int clampIndex(float x, int n) {
    const int i = static_cast<int>(x * static_cast<float>(n));
    return i < 0 ? 0 : (i >= n ? n - 1 : i);
  }

 private:
  int nu_ = 0, nv_ = 0;
  std::vector<DiscreteDistribution> rows_;
  DiscreteDistribution marginal_;
};

}  // namespace camsim
