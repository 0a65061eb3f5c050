#include "integrator/camera/glass.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sensor/base/check.h"

namespace camsim {

Glass Glass::constant(double nd) {
  CAMSIM_CHECK(nd >= 1.0);
  Glass g;
  g.model_ = nd == 1.0 ? GlassModel::kAir : GlassModel::kConstant;
  g.nd_ = nd;
  g.cauchyA_ = nd;
  return g;
}

Glass Glass::abbe(double nd, double abbeNumber) {
  CAMSIM_CHECK(nd > 1.0 && abbeNumber > 0.0);
  Glass g;
  g.model_ = GlassModel::kAbbe;
  g.nd_ = nd;
  // n_F − n_C = B (1/λ_F² − 1/λ_C²) = (n_d − 1)/V_d; n_d = A + B/λ_d².
  g.cauchyB_ =
      (nd - 1.0) / abbeNumber / (1.0 / (kLambdaFNm * kLambdaFNm) - 1.0 / (kLambdaCNm * kLambdaCNm));
  g.cauchyA_ = nd - g.cauchyB_ / (kLambdaDNm * kLambdaDNm);
  return g;
}

Glass Glass::table(std::string name, std::vector<double> lambdaNm, std::vector<double> eta,
                   double nd) {
  const size_t n = lambdaNm.size();
  CAMSIM_CHECK(n >= 2 && eta.size() == n && nd >= 1.0);
  for (size_t i = 1; i < n; ++i) CAMSIM_CHECK(lambdaNm[i] > lambdaNm[i - 1]);
  // Natural cubic spline: m_0 = m_{n-1} = 0 and, inside, the tridiagonal system
  //   h_{i-1} m_{i-1} + 2 (h_{i-1} + h_i) m_i + h_i m_{i+1} = 6 (s_i − s_{i-1}),
  // h_i = x_{i+1} − x_i, s_i = (y_{i+1} − y_i)/h_i, solved by the Thomas algorithm.
  Spline s{std::move(lambdaNm), std::move(eta), std::vector<double>(n, 0.0)};
  if (n > 2) {
    std::vector<double> diag(n, 0.0), rhs(n, 0.0);
    for (size_t i = 1; i + 1 < n; ++i) {
      const double h0 = s.x[i] - s.x[i - 1], h1 = s.x[i + 1] - s.x[i];
      diag[i] = 2.0 * (h0 + h1);
      rhs[i] = 6.0 * ((s.y[i + 1] - s.y[i]) / h1 - (s.y[i] - s.y[i - 1]) / h0);
    }
    for (size_t i = 2; i + 1 < n; ++i) {  // eliminate the sub-diagonal h_{i-1}
      const double w = (s.x[i] - s.x[i - 1]) / diag[i - 1];
      diag[i] -= w * (s.x[i] - s.x[i - 1]);
      rhs[i] -= w * rhs[i - 1];
    }
    for (size_t i = n - 2; i >= 1; --i)
      s.m[i] = (rhs[i] - (s.x[i + 1] - s.x[i]) * s.m[i + 1]) / diag[i];
  }
  Glass g;
  g.model_ = GlassModel::kTable;
  g.nd_ = nd;
  g.name_ = std::move(name);
  g.spline_ = std::make_shared<const Spline>(std::move(s));
  g.shift_ = nd - (*g.spline_)(kLambdaDNm);
  return g;
}

double Glass::Spline::operator()(double at) const {
  if (!(at > x.front())) return y.front();  // also NaN: the first value
  if (at >= x.back()) return y.back();
  const size_t i = static_cast<size_t>(std::upper_bound(x.begin(), x.end(), at) - x.begin()) - 1;
  const double h = x[i + 1] - x[i], a = (x[i + 1] - at) / h, b = 1.0 - a;
  return a * y[i] + b * y[i + 1] +
         ((a * a * a - a) * m[i] + (b * b * b - b) * m[i + 1]) * h * h / 6.0;
}

double Glass::index(double lambdaNm) const {
  switch (model_) {
    case GlassModel::kAir:
      return 1.0;
    case GlassModel::kConstant:
      return nd_;
    case GlassModel::kAbbe:
      return cauchyA_ + cauchyB_ / (lambdaNm * lambdaNm);
    case GlassModel::kTable:
      return (*spline_)(lambdaNm) + shift_;
  }
  return nd_;
}

double Glass::abbeNumber() const {
  if (!disperses()) return std::numeric_limits<double>::infinity();
  return (nd_ - 1.0) / (index(kLambdaFNm) - index(kLambdaCNm));
}

}  // namespace camsim
