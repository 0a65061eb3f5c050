#include "integrator/camera/psf_grid.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "integrator/camera/stop_psf.h"
#include "sensor/base/check.h"

namespace camsim {
namespace {

// Edges ±kB·sinh(k/kA): 1/16 λN_w per cell at the centre, 2 % wider per cell far out.
const double kA = 1.0 / std::log(1.02);
const double kB = kA / 16.0;
// Gauss–Legendre sub-cells per λN_w along each axis (each of 2 points), and the two-point
// rule's node offset 1/√3.
constexpr double kSubPerUnit = 2.0;
const double kGauss = 1.0 / std::sqrt(3.0);

// One axis's quadrature nodes: positions and weights, cell c's nodes in [first[c], first[c+1]).
struct AxisNodes {
  std::vector<double> x, w;
  std::vector<size_t> first;
};

AxisNodes axisNodes(const std::vector<double>& edges) {
  AxisNodes n;
  for (size_t c = 0; c + 1 < edges.size(); ++c) {
    n.first.push_back(n.x.size());
    const double e0 = edges[c], width = edges[c + 1] - e0;
    const int subs = std::max(1, static_cast<int>(std::ceil(kSubPerUnit * width)));
    const double d = width / subs;
    for (int s = 0; s < subs; ++s) {
      const double mid = e0 + (s + 0.5) * d;
      for (const double x : {mid - 0.5 * d * kGauss, mid + 0.5 * d * kGauss}) {
        n.x.push_back(x);
        n.w.push_back(0.5 * d);
      }
    }
  }
  n.first.push_back(n.x.size());
  return n;
}

// The cells' probabilities, unnormalised: the analytic PSF integrated over each cell of the
// grid with these edges (both axes), in film axes for the stop's turn.
std::vector<double> cellMasses(const ApertureShape& stop, const std::vector<double>& edges) {
  const StopPsf shape(stop.blades);
  const int n = static_cast<int>(edges.size()) - 1, half = n / 2;
  const AxisNodes nodes = axisNodes(edges);
  // The PSF's symmetries pick each cell's representative: p(−u) = p(u) always; an unturned
  // N-gon (a vertex on +x) and the circle are mirrored in the x axis too, so in both axes;
  // the circle is also symmetric under x ↔ y (the grid's axes share their edges).
  const bool quadrant = stop.blades == 0 || stop.rotation == 0.0;
  const bool transpose = stop.blades == 0;
  auto representative = [&](int cx, int cy) {
    if (quadrant) {
      cx = cx >= half ? cx : n - 1 - cx;
      cy = cy >= half ? cy : n - 1 - cy;
      if (transpose && cx < cy) std::swap(cx, cy);
    } else if (cy < half) {
      cx = n - 1 - cx;
      cy = n - 1 - cy;
    }
    return static_cast<size_t>(cy) * static_cast<size_t>(n) + static_cast<size_t>(cx);
  };
  // The analytic PSF at u (film axes): the N-gon's edge sum at R⁻¹u; the circle's Airy
  // pattern from radial tables (J₁ costs microseconds), linear between points 1/256 λN_w apart
  // within 16 λN_w (within 1e-5 of the peak) and 1/32 λN_w apart beyond (within 0.3 % of the
  // rings' own level, below 1e-7 of the peak).
  const double c = std::cos(stop.rotation), s = std::sin(stop.rotation);
  constexpr double kNear = 16.0, kFinePerUnit = 256.0, kCoarsePerUnit = 32.0;
  std::vector<double> fine, coarse;
  auto tabulate = [&](std::vector<double>& t, double perUnit, double from, double to) {
    t.resize(static_cast<size_t>(std::ceil((to - from) * perUnit)) + 2);
    tbb::parallel_for(size_t{0}, t.size(), [&](size_t k) {
      t[k] = shape.analytic({from + static_cast<double>(k) / perUnit, 0.0});
    });
  };
  if (transpose) {
    tabulate(fine, kFinePerUnit, 0.0, kNear);
    tabulate(coarse, kCoarsePerUnit, kNear, edges.back() * M_SQRT2);
  }
  auto lerp = [](const std::vector<double>& t, double x) {
    const size_t k = std::min(static_cast<size_t>(x), t.size() - 2);
    return t[k] + (x - static_cast<double>(k)) * (t[k + 1] - t[k]);
  };
  auto psfAt = [&](double x, double y) {
    if (!transpose) return shape.analytic({c * x + s * y, -s * x + c * y});
    const double r = std::hypot(x, y);
    return r < kNear ? lerp(fine, r * kFinePerUnit) : lerp(coarse, (r - kNear) * kCoarsePerUnit);
  };
  std::vector<double> mass(static_cast<size_t>(n) * static_cast<size_t>(n), 0.0);
  tbb::parallel_for(half, n, [&](int cy) {
    for (int cx = 0; cx < n; ++cx) {
      const size_t i = static_cast<size_t>(cy) * static_cast<size_t>(n) + static_cast<size_t>(cx);
      if (representative(cx, cy) != i) continue;
      double m = 0.0;
      for (size_t b = nodes.first[static_cast<size_t>(cy)];
           b < nodes.first[static_cast<size_t>(cy) + 1]; ++b)
        for (size_t a = nodes.first[static_cast<size_t>(cx)];
             a < nodes.first[static_cast<size_t>(cx) + 1]; ++a)
          m += nodes.w[a] * nodes.w[b] * psfAt(nodes.x[a], nodes.x[b]);
      mass[i] = m;
    }
  });
  // Every other cell from its representative (computed above, never overwritten: it is its
  // own).
  for (int cy = 0; cy < n; ++cy)
    for (int cx = 0; cx < n; ++cx) {
      double& m = mass[static_cast<size_t>(cy) * static_cast<size_t>(n) + static_cast<size_t>(cx)];
      m = mass[representative(cx, cy)];
    }
  return mass;
}

// A guide to a nondecreasing cumulative F(0) = 0 … F(n) cut into `shares` equal parts:
// entry b (b = 0 … shares) is the last index i < n with F(i) ≤ (b/shares)·F(n).
template <class Cumulative>
void buildGuide(const Cumulative& f, size_t n, size_t shares, std::uint16_t* guide) {
  size_t i = 0;
  for (size_t b = 0; b <= shares; ++b) {
    const double bound = static_cast<double>(b) / static_cast<double>(shares) * f(n);
    while (i + 1 < n && f(i + 1) <= bound) ++i;
    guide[b] = static_cast<std::uint16_t>(i);
  }
}

// The index lo < n with F(lo) ≤ t < F(lo + 1) for t in [0, F(n)): a binary search between
// the guide's entries for t's share (widened by a step if rounding put t past them).
template <class Cumulative>
size_t guidedFind(const Cumulative& f, size_t n, double t, size_t shares,
                  const std::uint16_t* guide) {
  // t's share; NaN (a zero total, a NaN t) and ≤ 0 start at the first.
  const double share = t / f(n) * static_cast<double>(shares);
  const size_t b =
      share > 0.0 ? static_cast<size_t>(std::min(share, static_cast<double>(shares - 1))) : 0;
  size_t lo = guide[b], hi = std::min<size_t>(guide[b + 1] + 1u, n);
  while (lo > 0 && f(lo) > t) --lo;
  while (hi < n && f(hi) <= t) ++hi;
  while (hi - lo > 1) {  // f(lo) ≤ t < f(hi)
    const size_t mid = (lo + hi) / 2;
    (f(mid) <= t ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

PsfGrid::PsfGrid(const ApertureShape& stop) {
  const int half = static_cast<int>(std::ceil(kA * std::asinh(kExtent / kB)));
  cells_ = 2 * half;
  edges_.resize(static_cast<size_t>(cells_) + 1);
  for (int k = 0; k <= half; ++k) {
    const double e = kB * std::sinh(static_cast<double>(k) / kA);
    edges_[static_cast<size_t>(half + k)] = e;
    edges_[static_cast<size_t>(half - k)] = -e;
  }
  // The guide: bucket b of |x| ∈ [b, b + 1)/kGuidePerUnit starts in cell guide_[b] from the
  // centre.
  guide_.resize(static_cast<size_t>(kExtent * kGuidePerUnit) + 2);
  for (size_t b = 0, k = 0; b < guide_.size(); ++b) {
    const double r = static_cast<double>(b) / kGuidePerUnit;
    while (k + 1 < static_cast<size_t>(half) && r >= edges_[static_cast<size_t>(half) + k + 1]) ++k;
    guide_[b] = static_cast<int>(k);
  }
  std::vector<double> mass = cellMasses(stop, edges_);
  long double total = 0.0L;
  for (const double m : mass) total += static_cast<long double>(m);
  truncated_ = 1.0 - static_cast<double>(total);  // the table's energy against Parseval's 1
  for (double& m : mass) m = static_cast<double>(static_cast<long double>(m) / total);
  // S(i, j): the cells below column i and row j, accumulated in long double.
  const size_t stride = static_cast<size_t>(cells_) + 1;
  summed_.assign(stride * stride, 0.0);
  std::vector<long double> column(stride, 0.0L);  // column i's cells below the current row
  for (size_t j = 0; j < static_cast<size_t>(cells_); ++j) {
    long double row = 0.0L;
    for (size_t i = 0; i < static_cast<size_t>(cells_); ++i) {
      column[i + 1] += static_cast<long double>(mass[j * static_cast<size_t>(cells_) + i]);
      row += column[i + 1];
      summed_[(j + 1) * stride + i + 1] = static_cast<double>(row);
    }
  }
  rows_.resize(stride);
  for (size_t j = 0; j < stride; ++j) rows_[j] = summed_[j * stride + stride - 1];
  const size_t n = static_cast<size_t>(cells_);
  CAMSIM_CHECK(n <= 65535);  // the guides' entries are 16-bit cell indices
  rowGuide_.resize(kRowShares + 1);
  buildGuide([&](size_t j) { return rows_[j]; }, n, kRowShares, rowGuide_.data());
  columnGuide_.resize(n * (kColumnShares + 1));
  for (size_t j = 0; j < n; ++j) {
    const double* below = &summed_[j * stride];
    const double* above = below + stride;
    buildGuide([&](size_t i) { return above[i] - below[i]; }, n, kColumnShares,
               &columnGuide_[j * (kColumnShares + 1)]);
  }
}

std::shared_ptr<const PsfGrid> PsfGrid::forStop(const ApertureShape& stop) {
  static std::mutex mutex;
  static std::map<std::pair<int, double>, std::shared_ptr<const PsfGrid>> grids;
  const std::lock_guard<std::mutex> lock(mutex);
  std::shared_ptr<const PsfGrid>& g = grids[{stop.blades, stop.blades == 0 ? 0.0 : stop.rotation}];
  // Built in an isolated arena: its parallel loops never pick up an outer task that could
  // wait on this lock.
  if (!g) tbb::this_task_arena::isolate([&] { g = std::make_shared<const PsfGrid>(stop); });
  return g;
}

PsfGrid::AxisPosition PsfGrid::locate(double x) const {
  if (!(x > edges_.front())) return {0, 0.0};
  if (!(x < edges_.back())) return {cells_ - 1, 1.0};
  // |x|'s cell k from the centre: the guide's first guess, or the next cell (no cell is
  // narrower than a guide bucket, so a bucket meets at most two).
  const int half = cells_ / 2;
  const double r = std::abs(x);
  const size_t bucket = std::min(static_cast<size_t>(r * kGuidePerUnit), guide_.size() - 1);
  int k = guide_[bucket];
  if (r >= edges_[static_cast<size_t>(half + k + 1)]) ++k;
  const int cell = x >= 0.0 ? half + k : half - 1 - k;
  const double e0 = edges_[static_cast<size_t>(cell)], e1 = edges_[static_cast<size_t>(cell) + 1];
  return {cell, std::clamp((x - e0) / (e1 - e0), 0.0, 1.0)};
}

double PsfGrid::cumulative(AxisPosition x, AxisPosition y) const {
  const int i = x.cell, j = y.cell;
  const double s00 = summed(i, j), s10 = summed(i + 1, j), s01 = summed(i, j + 1),
               s11 = summed(i + 1, j + 1);
  return s00 + x.fraction * (s10 - s00) + y.fraction * (s01 - s00) +
         x.fraction * y.fraction * (s11 - s10 - s01 + s00);
}

double PsfGrid::boxMass(glm::dvec2 lo, glm::dvec2 hi) const {
  const AxisPosition x0 = locate(lo.x), x1 = locate(hi.x), y0 = locate(lo.y), y1 = locate(hi.y);
  const double m =
      cumulative(x1, y1) - cumulative(x0, y1) - cumulative(x1, y0) + cumulative(x0, y0);
  return std::max(m, 0.0);  // rounding can leave −1e-17 for an empty box
}

// A cell by its probability, from the summed table itself (so sampling and boxMass read the
// same numbers): the row j whose cumulative R(j) = S(n, j) brackets u_y·R(n), then the
// column i whose in-row cumulative S(i, j+1) − S(i, j) brackets u_x times the row's total
// (each found from its guide); the remainders place the point uniformly in the cell.
glm::dvec2 PsfGrid::sample(glm::vec2 u) const {
  const size_t n = static_cast<size_t>(cells_), stride = n + 1;
  const auto row = [&](size_t j) { return rows_[j]; };
  const double ty = static_cast<double>(u.y) * rows_[n];
  const size_t j = guidedFind(row, n, ty, kRowShares, rowGuide_.data());
  const double* below = &summed_[j * stride];
  const double* above = below + stride;
  const auto inRow = [&](size_t i) { return above[i] - below[i]; };
  const double tx = static_cast<double>(u.x) * inRow(n);
  const size_t i = guidedFind(inRow, n, tx, kColumnShares, &columnGuide_[j * (kColumnShares + 1)]);
  const double cellMass = inRow(i + 1) - inRow(i), rowMass = rows_[j + 1] - rows_[j];
  const double fx = cellMass > 0.0 ? std::clamp((tx - inRow(i)) / cellMass, 0.0, 1.0) : 0.5;
  const double fy = rowMass > 0.0 ? std::clamp((ty - rows_[j]) / rowMass, 0.0, 1.0) : 0.5;
  return {edges_[i] + fx * (edges_[i + 1] - edges_[i]),
          edges_[j] + fy * (edges_[j + 1] - edges_[j])};
}

double PsfGrid::density(glm::dvec2 u) const {
  if (!(std::abs(u.x) < edges_.back() && std::abs(u.y) < edges_.back())) return 0.0;
  const AxisPosition x = locate(u.x), y = locate(u.y);
  const size_t i = static_cast<size_t>(x.cell), j = static_cast<size_t>(y.cell);
  const double area = (edges_[i + 1] - edges_[i]) * (edges_[j + 1] - edges_[j]);
  const double m = summed(x.cell + 1, y.cell + 1) - summed(x.cell + 1, y.cell) -
                   summed(x.cell, y.cell + 1) + summed(x.cell, y.cell);
  return std::max(m, 0.0) / area;
}

}  // namespace camsim
