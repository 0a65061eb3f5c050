// Numerical tools of the BSDF checks (bsdf_check.h): directions from (cos θ, φ), nested
// adaptive Simpson quadrature over cells of the sphere (dω = sin θ dθ dφ), and the χ²
// p-value through the regularised upper incomplete gamma function.
//
// | option         | default | meaning                                                |
// |----------------|---------|--------------------------------------------------------|
// | minDepth       | 3       | forced bisections of every panel                       |
// | maxDepth       | 22      | refinement limit                                       |
// | relTol, absTol | 1e-5, 1e-8  | per-panel tolerance max(absTol, relTol |S₂|)       |
// | maxEvaluations | 1e6     | integrand evaluations per cell (then panels are kept)  |
//
//   Simpson  S[a,b] = (b − a)/6 (f(a) + 4 f(m) + f(b)); a panel is accepted as
//            S₂ + (S₂ − S)/15 when |S₂ − S| ≤ 15 max(absTol, relTol |S₂|)
//   p-value  p = Q(dof/2, χ²/2)
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/vec3.hpp>

#include "sensor/spectra/sampled_spectrum.h"

namespace camsim::bsdfcheck {
inline constexpr double kTwoPi = 6.283185307179586476925;

// Unit direction from cos θ and φ (computed in double, so z near ±1 stays accurate).
inline glm::vec3 direction(double z, double phi) {
  z = std::clamp(z, -1.0, 1.0);
  const double s = std::sqrt(std::max(0.0, (1.0 - z) * (1.0 + z)));
  return {static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
          static_cast<float>(z)};
}

// ---------------------------------------------------------------- quadrature
struct QuadratureOptions {
  int minDepth = 3;      // forced bisections of every panel (2³ = 8 sub-panels); raise it
                         // for very narrow lobes so that the first points see the peak
  int maxDepth = 22;     // refinement limit
  double relTol = 1e-5;  // panel accepted when |S₂ − S| ≤ 15 max(absTol, relTol |S₂|)
  double absTol = 1e-8;
  long maxEvaluations = 1000000;   // per cell; beyond it panels are accepted as they are
  long* exhaustedCells = nullptr;  // if set: incremented for each cell that ran out
};

// Value of a spectral integrand: one double per wavelength sample.
using Channels = std::array<double, kWavelengthSamples>;

namespace detail {
inline double magnitude(double v) {
  return std::abs(v);
}
inline double magnitude(const Channels& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}
inline Channels operator+(Channels a, const Channels& b) {
  for (std::size_t i = 0; i < a.size(); ++i) a[i] += b[i];
  return a;
}
inline Channels operator-(Channels a, const Channels& b) {
  for (std::size_t i = 0; i < a.size(); ++i) a[i] -= b[i];
  return a;
}
inline Channels operator*(double s, Channels a) {
  for (double& x : a) x *= s;
  return a;
}

struct SimpsonTolerance {
  int minDepth, maxDepth;
  double relTol, absTol;
  long* budget;  // evaluations left (shared by the nested integrals of one cell)
};

template <class V, class F>
V simpsonStep(const F& f, double a, double b, const V& fa, const V& fm, const V& fb, const V& whole,
              int depth, const SimpsonTolerance& t) {
  const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const V flm = f(lm), frm = f(rm);
  const V left = ((m - a) / 6.0) * (fa + 4.0 * flm + fm);
  const V right = ((b - m) / 6.0) * (fm + 4.0 * frm + fb);
  const V both = left + right;
  const double tol = std::max(t.absTol, t.relTol * magnitude(both));
  if (depth >= t.maxDepth || *t.budget <= 0 ||
      (depth >= t.minDepth && magnitude(both - whole) <= 15.0 * tol))
    return both + (1.0 / 15.0) * (both - whole);
  return simpsonStep(f, a, m, fa, flm, fm, left, depth + 1, t) +
         simpsonStep(f, m, b, fm, frm, fb, right, depth + 1, t);
}

template <class V, class F>
V adaptiveSimpson(const F& f, double a, double b, const SimpsonTolerance& t) {
  using detail::operator+;
  using detail::operator*;
  const V fa = f(a), fm = f(0.5 * (a + b)), fb = f(b);
  const V whole = ((b - a) / 6.0) * (fa + 4.0 * fm + fb);
  return simpsonStep<V>(f, a, b, fa, fm, fb, whole, 0, t);
}
}  // namespace detail

// ∫ g(ω) dω over the cell z ∈ [z0, z1], φ ∈ [φ0, φ1] (g returns V: double or Channels), by
// nested adaptive Simpson: outer in θ (dω = sin θ dθ dφ), inner in φ.
//  - θ resolves lobes at the poles (α wide in θ but α² in z); as sin θ hides the pole
//    value, a polar cell's θ range is graded (1/4096, 1/256, 1/16 of its width) so that
//    the first evaluations reach θ ~ 1e-4 there;
//  - the inner integrals use a tolerance 4× tighter than the outer one, so their
//    rounding noise does not drive the outer refinement;
//  - a cell that uses up maxEvaluations (a feature narrower than the panels can follow)
//    is counted in *exhaustedCells: its value is then unreliable.
template <class V = double, class G>
V integrateCell(const G& g, double z0, double z1, double phi0, double phi1,
                const QuadratureOptions& o) {
  using detail::operator+;
  long budget = o.maxEvaluations;
  const detail::SimpsonTolerance outerTol{o.minDepth, o.maxDepth, o.relTol, o.absTol, &budget};
  const detail::SimpsonTolerance innerTol{o.minDepth, o.maxDepth, o.relTol / 50.0, o.absTol / 50.0,
                                          &budget};
  const auto inner = [&](double theta) -> V {
    const double st = std::sin(theta), ct = std::cos(theta);
    const V ring = detail::adaptiveSimpson<V>(
        [&](double phi) -> V {
          --budget;
          const glm::vec3 w(static_cast<float>(st * std::cos(phi)),
                            static_cast<float>(st * std::sin(phi)), static_cast<float>(ct));
          return g(w);
        },
        phi0, phi1, innerTol);
    using detail::operator*;
    return st * ring;
  };
  const double t0 = std::acos(std::clamp(z1, -1.0, 1.0)), t1 = std::acos(std::clamp(z0, -1.0, 1.0));
  std::array<double, 8> edges{};
  std::size_t n = 0;
  edges[n++] = t0;
  if (z1 >= 1.0)
    for (double q : {1.0 / 4096, 1.0 / 256, 1.0 / 16}) edges[n++] = t0 + q * (t1 - t0);
  if (z0 <= -1.0)
    for (double q : {1.0 / 16, 1.0 / 256, 1.0 / 4096}) edges[n++] = t1 - q * (t1 - t0);
  edges[n++] = t1;
  V sum{};
  for (std::size_t i = 0; i + 1 < n; ++i)
    sum = sum + detail::adaptiveSimpson<V>(inner, edges[i], edges[i + 1], outerTol);
  if (budget <= 0 && o.exhaustedCells != nullptr) ++*o.exhaustedCells;
  return sum;
}

// ∫ g dω over the sphere, cell by cell on the χ² grid (cell edges catch the z = 0 jump).
template <class V = double, class G>
V integrateSphere(const G& g, int cosThetaBins, int phiBins, const QuadratureOptions& o) {
  using detail::operator+;
  V sum{};
  for (int i = 0; i < cosThetaBins; ++i)
    for (int j = 0; j < phiBins; ++j)
      sum = sum + integrateCell<V>(g, -1.0 + 2.0 * i / cosThetaBins,
                                   -1.0 + 2.0 * (i + 1) / cosThetaBins, kTwoPi * j / phiBins,
                                   kTwoPi * (j + 1) / phiBins, o);
  return sum;
}

// ---------------------------------------------------------------- χ² statistics
// Regularised upper incomplete gamma Q(a, x) (series for x < a + 1, else Lentz continued
// fraction), accurate to ~1e-12 for the a, x of χ² tests.
inline double gammaQ(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double logPrefix = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 100000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * 1e-15) break;
    }
    return std::max(0.0, 1.0 - sum * std::exp(logPrefix));
  }
  constexpr double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int n = 1; n < 100000; ++n) {
    const double an = -n * (n - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-15) break;
  }
  return std::exp(logPrefix) * h;
}

inline double chiSquarePValue(double statistic, int dof) {
  return dof <= 0 ? 1.0 : gammaQ(0.5 * dof, 0.5 * statistic);
}

}  // namespace camsim::bsdfcheck
