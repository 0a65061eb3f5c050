// Locating a slanted edge in a region of interest (ISO 12233:2017 e-SFR, first half; the
// method of Burns' sfrmat3/sfrmat4). The ROI arrives as an EdgePatch already turned so that
// the edge runs down its rows (a horizontal edge is transposed by the caller), with
//
//   rows      along the edge (y, px), cols across it (x, px); pixel c of a row spans
//             [c, c+1], its centre is c + ½ (so is a row's: r + ½)
//   d_r(c+1)  = s·(a[r][c+1] − a[r][c]): the derivative across the edge at the boundary
//             x = c + 1 between two pixels, s = ±1 so that the edge rises (dark → bright)
//   w(x)      = 0.54 + 0.46·cos(π (x − m)/h): a Hamming window centred on m, h the
//             distance from m to the farther end of the row (sfrmat's ahamming)
//   x_r       = Σ x·w·d_r / Σ w·d_r: the edge in row r (centroid of the windowed derivative)
//   x(y)      = c₀ + c₁·y [+ c₂·y²]: least squares through (r + ½, x_r), order 1 (ISO
//             12233:2017, sfrmat4's default npol = 1) or 2 (sfrmat4's npol = 2)
//
// Two passes, as sfrmat4: the first window is centred on the row's middle, the second on
// the first fit's x(r + ½); the fit is made again. Rows whose Σ w·d_r is not positive (no
// rising edge in the window) are left out of the fit.
#pragma once

#include <cstddef>
#include <vector>

namespace camsim {

// Samples of a ROI, row by row, rows along the edge. rows·cols values.
struct EdgePatch {
  int rows = 0;
  int cols = 0;
  std::vector<double> values;  // values[r·cols + c]
  double at(int r, int c) const {
    return values[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) +
                  static_cast<std::size_t>(c)];
  }
};

// The mean of the first and of the last k columns (k = max(1, min(5, cols/8)), as sfrmat4
// compares its 5 outer columns): the two sides of the edge.
struct EdgeSides {
  double low = 0.0;   // the mean of the first columns
  double high = 0.0;  // the mean of the last columns
  // (high − low)/(|high| + |low|), in [−1, 1]; 0 when both are 0.
  double contrast() const;
};
EdgeSides edgeSides(const EdgePatch& patch);

// The fitted edge x(y) in patch coordinates (px).
struct EdgeLine {
  std::vector<double> coefficients;  // c₀, c₁[, c₂]: x(y) = Σ c_k y^k
  double at(double y) const;
  double slope(double y) const;  // dx/dy
};

struct EdgeLocation {
  EdgeLine line;
  std::vector<double> rowCentroids;  // x_r per row (px); rows left out hold 0
  std::vector<bool> rowUsed;         // false: Σ w·d_r ≤ 0 in the last pass
  int rowsFitted = 0;
};

// The edge of `patch`, rising when `rising` (else the derivative is negated), fitted with
// a polynomial of `order` (1 or 2). Fewer than max(3, order + 2) usable rows leave
// rowsFitted below that and the line flat at the middle: the caller reports it.
EdgeLocation locateEdge(const EdgePatch& patch, bool rising, int order);

// Least squares polynomial of `order` through (x_i, y_i) (a 2×2 or 3×3 normal system in
// centred, scaled x); the coefficients of y = Σ c_k x^k. Needs more points than order.
std::vector<double> fitPolynomial(const std::vector<double>& x, const std::vector<double>& y,
                                  int order);

}  // namespace camsim
