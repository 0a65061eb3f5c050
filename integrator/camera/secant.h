// The secant method on a function that may be undefined (a ray that misses a surface):
// lens_trace.cpp's chief ray and psf_image.cpp's object point aim a ray through the stop's
// centre with it.
//
//   x_{k+1} = x_k − g(x_k)·(x_k − x_{k−1}) / (g(x_k) − g(x_{k−1}))
#pragma once

#include <cmath>
#include <optional>

namespace camsim {

// The x with |g(x)| < tolerance, from the starts x0 and x1 (at most 60 steps; stops early
// once |g| < 1e-13). None if g is undefined at an iterate, flat between two, or not within
// tolerance after the last step. g(x0) == 0 returns x0.
template <class G>
std::optional<double> secantRoot(G&& g, double x0, double x1, double tolerance = 1e-9) {
  std::optional<double> g0 = g(x0);
  if (g0 && *g0 == 0.0) return x0;
  std::optional<double> g1 = g(x1);
  for (int iteration = 0; iteration < 60 && g0 && g1; ++iteration) {
    if (std::abs(*g1) < 1e-13) break;
    if (*g1 == *g0) return std::nullopt;
    const double x2 = x1 - *g1 * (x1 - x0) / (*g1 - *g0);
    x0 = x1;
    g0 = g1;
    x1 = x2;
    g1 = g(x1);
  }
  if (!g1 || !(std::abs(*g1) < tolerance)) return std::nullopt;
  return x1;
}

}  // namespace camsim
