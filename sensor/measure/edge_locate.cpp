#include "sensor/measure/edge_locate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "sensor/base/check.h"

namespace camsim {

double EdgeSides::contrast() const {
  const double sum = std::abs(high) + std::abs(low);
  return sum > 0.0 ? (high - low) / sum : 0.0;
}

EdgeSides edgeSides(const EdgePatch& patch) {
  const int k = std::max(1, std::min(5, patch.cols / 8));
  EdgeSides s;
  for (int r = 0; r < patch.rows; ++r)
    for (int c = 0; c < k; ++c) {
      s.low += patch.at(r, c);
      s.high += patch.at(r, patch.cols - 1 - c);
    }
  const double n = static_cast<double>(k) * std::max(1, patch.rows);
  s.low /= n;
  s.high /= n;
  return s;
}

double EdgeLine::at(double y) const {
  double v = 0.0, p = 1.0;
  for (double c : coefficients) {
    v += c * p;
    p *= y;
  }
  return v;
}

double EdgeLine::slope(double y) const {
  double v = 0.0, p = 1.0;
  for (size_t k = 1; k < coefficients.size(); ++k) {
    v += static_cast<double>(k) * coefficients[k] * p;
    p *= y;
  }
  return v;
}

std::vector<double> fitPolynomial(const std::vector<double>& x, const std::vector<double>& y,
                                  int order) {
  CAMSIM_CHECK(order >= 1 && order <= 2 && x.size() == y.size());
  CAMSIM_CHECK(x.size() > static_cast<size_t>(order));
  const double n = static_cast<double>(x.size());
  double mean = 0.0;
  for (double v : x) mean += v;
  mean /= n;
  double scale = 0.0;
  for (double v : x) scale = std::max(scale, std::abs(v - mean));
  if (scale == 0.0) {  // one abscissa: the mean height, flat
    double my = 0.0;
    for (double v : y) my += v;
    std::vector<double> flat(static_cast<size_t>(order) + 1, 0.0);
    flat[0] = my / n;
    return flat;
  }
  // Normal equations in t = (x − mean)/scale: A a = b, A_jk = Σ t^(j+k), b_j = Σ y t^j.
  const int m = order + 1;
  std::array<std::array<double, 4>, 3> a{};  // augmented rows
  for (size_t i = 0; i < x.size(); ++i) {
    const double t = (x[i] - mean) / scale;
    std::array<double, 5> pw{1.0, t, t * t, t * t * t, t * t * t * t};
    for (int j = 0; j < m; ++j) {
      for (int k = 0; k < m; ++k) a[j][k] += pw[static_cast<size_t>(j + k)];
      a[j][static_cast<size_t>(m)] += y[i] * pw[static_cast<size_t>(j)];
    }
  }
  // Gaussian elimination with partial pivoting.
  for (int col = 0; col < m; ++col) {
    int pivot = col;
    for (int r = col + 1; r < m; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    std::swap(a[col], a[pivot]);
    if (a[col][col] == 0.0) continue;  // singular (too few distinct x): that term stays 0
    for (int r = 0; r < m; ++r) {
      if (r == col) continue;
      const double f = a[r][col] / a[col][col];
      for (int k = col; k <= m; ++k) a[r][k] -= f * a[col][k];
    }
  }
  std::array<double, 3> t{};
  for (int j = 0; j < m; ++j) t[j] = a[j][j] == 0.0 ? 0.0 : a[j][m] / a[j][j];
  // Back to powers of x: t = (x − μ)/s.
  const double s = scale, mu = mean;
  std::vector<double> c(static_cast<size_t>(m), 0.0);
  c[0] = t[0] - t[1] * mu / s + (m > 2 ? t[2] * mu * mu / (s * s) : 0.0);
  c[1] = t[1] / s - (m > 2 ? 2.0 * t[2] * mu / (s * s) : 0.0);
  if (m > 2) c[2] = t[2] / (s * s);
  return c;
}

namespace {

// The Hamming window of sfrmat's ahamming: centred on `centre`, reaching 0.08 at the
// farther of the two ends `first`, `last`.
double hammingAt(double x, double centre, double first, double last) {
  const double half = std::max({centre - first, last - centre, 1e-9});
  const double u = std::clamp((x - centre) / half, -1.0, 1.0);
  return 0.54 + 0.46 * std::cos(std::numbers::pi * u);
}

// One pass: each row's windowed-derivative centroid, the window centred on centre(r).
template <typename Centre>
void rowCentroids(const EdgePatch& p, double sign, Centre centre, EdgeLocation& out) {
  out.rowCentroids.assign(static_cast<size_t>(p.rows), 0.0);
  out.rowUsed.assign(static_cast<size_t>(p.rows), false);
  const double first = 1.0, last = p.cols - 1.0;  // boundaries between pixel centres
  for (int r = 0; r < p.rows; ++r) {
    const double m = std::clamp(centre(r), first, last);
    double sum = 0.0, moment = 0.0;
    for (int c = 0; c + 1 < p.cols; ++c) {
      const double x = c + 1.0;
      const double d = sign * (p.at(r, c + 1) - p.at(r, c)) * hammingAt(x, m, first, last);
      sum += d;
      moment += x * d;
    }
    if (sum > 0.0) {
      const double x = moment / sum;
      if (x >= 0.0 && x <= p.cols) {
        out.rowCentroids[static_cast<size_t>(r)] = x;
        out.rowUsed[static_cast<size_t>(r)] = true;
      }
    }
  }
}

void fitRows(int order, EdgeLocation& out, double middle) {
  std::vector<double> ys, xs;
  for (size_t r = 0; r < out.rowCentroids.size(); ++r)
    if (out.rowUsed[r]) {
      ys.push_back(static_cast<double>(r) + 0.5);
      xs.push_back(out.rowCentroids[r]);
    }
  out.rowsFitted = static_cast<int>(ys.size());
  if (out.rowsFitted < std::max(3, order + 2)) {
    out.line.coefficients.assign(static_cast<size_t>(order) + 1, 0.0);
    out.line.coefficients[0] = middle;
    return;
  }
  out.line.coefficients = fitPolynomial(ys, xs, order);
}

}  // namespace

EdgeLocation locateEdge(const EdgePatch& patch, bool rising, int order) {
  CAMSIM_CHECK(patch.rows >= 1 && patch.cols >= 2 && (order == 1 || order == 2));
  CAMSIM_CHECK(patch.values.size() ==
               static_cast<size_t>(patch.rows) * static_cast<size_t>(patch.cols));
  const double sign = rising ? 1.0 : -1.0;
  const double middle = 0.5 * patch.cols;
  EdgeLocation loc;
  rowCentroids(
      patch, sign, [&](int) { return middle; }, loc);
  fitRows(order, loc, middle);
  const EdgeLine first = loc.line;
  rowCentroids(
      patch, sign, [&](int r) { return first.at(r + 0.5); }, loc);
  fitRows(order, loc, middle);
  return loc;
}

}  // namespace camsim
