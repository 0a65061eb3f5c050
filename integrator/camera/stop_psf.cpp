#include "integrator/camera/stop_psf.h"

#include <cmath>

#include "sensor/base/check.h"

namespace camsim {
namespace {

constexpr double kPupilArea = 0.25 * M_PI;  // the stop of diameter 1 and its N-gon

// sin(x)/x, 1 at 0.
double sinc(double x) {
  return std::abs(x) < 1e-8 ? 1.0 - x * x / 6.0 : std::sin(x) / x;
}

}  // namespace

double StopPsf::airyEncircledEnergy(double r) {
  if (!(r > 0.0)) return 0.0;
  const double v = M_PI * r;
  const double j0 = std::cyl_bessel_j(0.0, v), j1 = std::cyl_bessel_j(1.0, v);
  return 1.0 - j0 * j0 - j1 * j1;
}

StopPsf::StopPsf(int blades) : blades_(blades) {
  CAMSIM_CHECK(blades == 0 || blades >= 3);
  if (blades == 0) return;
  const double circumradius =
      std::sqrt(2.0 * kPupilArea / (blades * std::sin(2.0 * M_PI / blades)));
  for (int k = 0; k < blades; ++k) {
    const double a0 = 2.0 * M_PI * k / blades, a1 = 2.0 * M_PI * (k + 1) / blades;
    const glm::dvec2 v0(std::cos(a0), std::sin(a0)), v1(std::cos(a1), std::sin(a1));
    const glm::dvec2 edge = circumradius * (v1 - v0);
    // Counter-clockwise: the outward normal is the tangent turned clockwise.
    polygonEdges_.push_back(
        {glm::dvec2(edge.y, -edge.x), 0.5 * edge, 0.5 * circumradius * (v0 + v1)});
  }
}

std::complex<double> StopPsf::pupilTransform(glm::dvec2 k) const {
  const std::vector<Edge>& edges = polygonEdges_;
  const double k2 = k.x * k.x + k.y * k.y;
  if (blades_ == 0) {
    const double x = 0.5 * std::sqrt(k2);  // the stop's radius is 1/2
    return kPupilArea * (x < 1e-8 ? 1.0 : 2.0 * std::cyl_bessel_j(1.0, x) / x);
  }
  if (k2 < 1e-24) return kPupilArea;
  std::complex<double> sum = 0.0;
  for (const Edge& e : edges) {
    const double phase = -(k.x * e.midpoint.x + k.y * e.midpoint.y);
    sum += (k.x * e.normal.x + k.y * e.normal.y) *
           sinc(k.x * e.halfTangent.x + k.y * e.halfTangent.y) *
           std::complex<double>(std::cos(phase), std::sin(phase));
  }
  return std::complex<double>(0.0, 1.0) * sum / k2;
}

double StopPsf::analytic(glm::dvec2 u) const {
  return std::norm(pupilTransform(2.0 * M_PI * u)) / kPupilArea;
}

}  // namespace camsim
