// StopPsf: the stop's Fraunhofer PSF against closed forms (Airy), the polygon's Fourier
// transform against direct quadrature, the table's normalisation, and its samples against
// the Airy encircled energy (KS and chi-square) and the hexagon's six spikes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "integrator/camera/stop_psf.h"
#include "integrator/sampling/rng.h"

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

TEST(StopPsf, TableIsNormalisedAndFollowsThePsf) {
  for (int blades : {0, 3, 6}) {
    const StopPsf psf(blades);
    // Σ density × cell area = 1, and the truncated energy is small (stated in stop_psf.h).
    double total = 0.0;
    const double dTheta = 2.0 * M_PI / psf.columns();
    for (int k = 0; k < psf.rows(); ++k) {
      const double r0 = psf.radialEdge(k), r1 = psf.radialEdge(k + 1), rm = 0.5 * (r0 + r1);
      for (int c = 0; c < psf.columns(); ++c) {
        const double t = (c + 0.5) * dTheta;
        total +=
            psf.density({rm * std::cos(t), rm * std::sin(t)}) * 0.5 * (r1 * r1 - r0 * r0) * dTheta;
      }
    }
    EXPECT_NEAR(total, 1.0, 1e-9) << blades;
    EXPECT_GT(psf.truncatedEnergy(), 4e-4) << blades;
    EXPECT_LT(psf.truncatedEnergy(), 2e-3) << blades;
    EXPECT_GE(psf.radialEdge(psf.rows()), StopPsf::kRadius);
    EXPECT_EQ(psf.density({StopPsf::kRadius * 1.1, 0.0}), 0.0);
    // Near the centre, where cells are 1/16 λN wide, the table is the PSF within 2 % of the
    // peak; the cell averages of the first ring stay close to it.
    for (const glm::dvec2 u : {glm::dvec2(0.1, 0.05), glm::dvec2(0.5, -0.2), glm::dvec2(-0.3, 0.6)})
      EXPECT_NEAR(psf.density(u), psf.analytic(u), 0.02 * 0.25 * M_PI) << blades;
  }
  EXPECT_NEAR(StopPsf(0).truncatedEnergy(),
              1.0 - StopPsf::airyEncircledEnergy(StopPsf(0).radialEdge(StopPsf(0).rows())), 1e-15);
}

// Samples of the circle's table against the Airy encircled energy E(r)/E(R): the KS distance
// of the radii to the continuous E (n = 2^18; critical value at α = 0.001 is 1.95/√n =
// 0.0038; the table's constant density within a cell departs from E between cell edges by
// less than that), and a chi-square over bins made of whole table cells, each closed once it
// holds 5 % of the energy, with expected counts from E itself: at cell edges the table's
// distribution is Airy's exactly (critical value at α = 0.001 for bins − 1 degrees of
// freedom, Wilson–Hilferty: k(1 − 2/(9k) + 3.09√(2/(9k)))³, 43.8 for k = 19).
TEST(StopPsf, CircleSamplesFollowTheAiryEncircledEnergy) {
  const StopPsf psf(0);
  const double norm = StopPsf::airyEncircledEnergy(psf.radialEdge(psf.rows()));
  constexpr int n = 1 << 18;
  Pcg32 rng(17, 3);
  std::vector<double> radii(n);
  for (double& r : radii) {
    const glm::dvec2 u = psf.sample({rng.uniform(), rng.uniform()});
    r = std::hypot(u.x, u.y);
  }
  std::sort(radii.begin(), radii.end());
  double ks = 0.0;
  for (int i = 0; i < n; ++i) {
    const double cdf = StopPsf::airyEncircledEnergy(radii[static_cast<size_t>(i)]) / norm;
    ks = std::max({ks, std::abs(cdf - double(i) / n), std::abs(cdf - double(i + 1) / n)});
  }
  EXPECT_LT(ks, 1.95 / std::sqrt(double(n))) << "KS distance " << ks;
  std::vector<double> edges = {0.0};
  for (int k = 1; k <= psf.rows(); ++k) {
    const double e = psf.radialEdge(k);
    const double held =
        (StopPsf::airyEncircledEnergy(e) - StopPsf::airyEncircledEnergy(edges.back())) / norm;
    if (held >= 0.05 || k == psf.rows()) edges.push_back(e);
  }
  const int bins = static_cast<int>(edges.size()) - 1;
  const double dof = bins - 1, a = 2.0 / (9.0 * dof);
  const double critical = dof * std::pow(1.0 - a + 3.09 * std::sqrt(a), 3.0);
  ASSERT_GE(bins, 10);
  double chi2 = 0.0;
  for (int b = 0; b < bins; ++b) {
    const double lo = edges[static_cast<size_t>(b)], hi = edges[static_cast<size_t>(b) + 1];
    const double expected =
        n * (StopPsf::airyEncircledEnergy(hi) - StopPsf::airyEncircledEnergy(lo)) / norm;
    const auto count =
        std::count_if(radii.begin(), radii.end(), [&](double r) { return r >= lo && r < hi; });
    chi2 += (double(count) - expected) * (double(count) - expected) / expected;
  }
  EXPECT_LT(chi2, critical) << "chi-square " << chi2 << " over " << bins << " bins";
  RecordProperty("ks_distance", std::to_string(ks));
}

// Angles (degrees in [0, 360)) of samples whose radius lies in [rMin, rMax] (λN_w).
std::vector<double> sampleAngles(const StopPsf& psf, double rMin, double rMax, int n) {
  Pcg32 rng(29, static_cast<std::uint64_t>(psf.blades()));
  std::vector<double> angles;
  for (int i = 0; i < n; ++i) {
    const glm::dvec2 u = psf.sample({rng.uniform(), rng.uniform()});
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
// normals. A 5-blade stop
// (odd) gives ten spikes, at its normals 36° + 72°k and their opposites.
TEST(StopPsf, BladedStopsShowSpikesAlongTheEdgeNormals) {
  const StopPsf hexagon(6);
  const std::vector<double> angles = sampleAngles(hexagon, 3.0, 64.0, 1 << 19);
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

  const StopPsf pentagon(5);
  const std::vector<double> five = sampleAngles(pentagon, 3.0, 64.0, 1 << 19);
  int spikes = 0, between = 0;
  for (double a : five) {
    // Spikes every 36° starting at 0°+36°/… : the normals 36° + 72°k and their opposites
    // 216° + 72°k are the angles 36°·m for odd m and even m alike, i.e. every multiple of 36°.
    const double d = std::abs(std::remainder(a, 36.0));
    spikes += d <= 2.0 ? 1 : 0;
    between += std::abs(d - 18.0) <= 2.0 ? 1 : 0;
  }
  EXPECT_GT(spikes, 8 * between) << spikes << " vs " << between;
}

}  // namespace stop_psf_test
}  // namespace camsim
