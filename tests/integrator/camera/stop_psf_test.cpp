// StopPsf: the stop's Fraunhofer PSF against closed forms (Airy) and the polygon's Fourier
// transform against direct quadrature (its table: psf_grid_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "integrator/camera/stop_psf.h"

namespace camsim {
namespace stop_psf_test {

// ∫_P e^{−ik·ξ} d²ξ over the regular N-gon of area π/4 (a vertex on +x) by the midpoint rule
// on n × n sub-triangles of each of its N triangles (centre, v_k, v_k+1).
std::complex<double> polygonTransformByQuadrature(int blades, glm::dvec2 k, int n) {
  const double area = 0.25 * M_PI;
  const double R = std::sqrt(2.0 * area / (blades * std::sin(2.0 * M_PI / blades)));
  std::complex<double> sum = 0.0;
  for (int t = 0; t < blades; ++t) {
    const double a0 = 2.0 * M_PI * t / blades, a1 = 2.0 * M_PI * (t + 1) / blades;
    const glm::dvec2 v0(R * std::cos(a0), R * std::sin(a0)), v1(R * std::cos(a1), R * std::sin(a1));
    // Barycentric grid: the centroids of the n² small triangles, each of area A_t / n².
    const double cellArea = 0.5 * std::abs(v0.x * v1.y - v0.y * v1.x) / (n * n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n - i; ++j)
        for (int up = 0; up < (j < n - i - 1 ? 2 : 1); ++up) {
          const double s = (i + (up ? 2.0 : 1.0) / 3.0) / n, r = (j + (up ? 2.0 : 1.0) / 3.0) / n;
          const glm::dvec2 p = s * v0 + r * v1;
          const double phase = -(k.x * p.x + k.y * p.y);
          sum += cellArea * std::complex<double>(std::cos(phase), std::sin(phase));
        }
  }
  return sum;
}

TEST(StopPsf, PolygonTransformMatchesQuadrature) {
  for (int blades : {3, 6, 7}) {
    const StopPsf psf(blades);
    EXPECT_NEAR(std::abs(psf.pupilTransform({0.0, 0.0}) - 0.25 * M_PI), 0.0, 1e-15);
    for (const glm::dvec2 k : {glm::dvec2(1e-3, 0.0), glm::dvec2(3.0, 1.7), glm::dvec2(-9.0, 4.0),
                               glm::dvec2(20.0, -31.0)}) {
      const std::complex<double> quad = polygonTransformByQuadrature(blades, k, 400);
      EXPECT_NEAR(std::abs(psf.pupilTransform(k) - quad), 0.0, 2e-5)
          << blades << " blades, k = " << k.x << ", " << k.y;
    }
  }
}

TEST(StopPsf, CircleIsTheAiryPattern) {
  const StopPsf psf(0);
  EXPECT_NEAR(psf.analytic({0.0, 0.0}), 0.25 * M_PI, 1e-12);         // peak: A = π/4 per (λN)²
  EXPECT_NEAR(psf.analytic({1.2196698912665045, 0.0}), 0.0, 1e-12);  // first dark ring
  // Encircled energy at the first and second dark rings (Born & Wolf §8.5.2).
  EXPECT_NEAR(StopPsf::airyEncircledEnergy(1.2196698912665045), 0.8378, 1e-4);
  EXPECT_NEAR(StopPsf::airyEncircledEnergy(2.2331305943815286), 0.9099, 1e-4);
  // A 64-blade stop is nearly the circle of the same area.
  const StopPsf many(64);
  for (double r : {0.3, 0.8, 1.6, 3.1})
    EXPECT_NEAR(many.analytic({r, 0.4 * r}), psf.analytic({r, 0.4 * r}), 3e-3) << r;
}

}  // namespace stop_psf_test
}  // namespace camsim
