#include "integrator/camera/stop_psf.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

#include "sensor/base/check.h"

namespace camsim {
namespace {

// Radial edges r_k = kB·sinh(k/kA): 1/16 λN_w per cell at the centre, 2 % wider per cell far
// out (kA = 1/ln 1.02); about 257 cells to kRadius.
const double kA = 1.0 / std::log(1.02);
const double kB = kA / 16.0;
constexpr double kPupilArea = 0.25 * M_PI;  // the stop of diameter 1 and its N-gon
constexpr int kAngularCells = 1024;         // about this many over 2π for an N-gon
// Gauss–Legendre sub-cells per λN_w along the radius and along the arc (each of 2 × 2
// points), and the two-point rule's node offset 1/√3.
constexpr double kSubPerRadius = 2.0;
constexpr double kSubPerArc = 1.0;
const double kGauss = 1.0 / std::sqrt(3.0);

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
  rows_ = static_cast<int>(std::ceil(kA * std::asinh(kRadius / kB)));
  edges_.resize(static_cast<size_t>(rows_) + 1);
  for (int k = 0; k <= rows_; ++k) edges_[static_cast<size_t>(k)] = radialEdge(k);
  if (blades == 0) {
    buildCircle();
    return;
  }
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
  buildPolygon();
}

std::shared_ptr<const StopPsf> StopPsf::forBlades(int blades) {
  static std::mutex mutex;
  static std::map<int, std::shared_ptr<const StopPsf>> tables;
  const std::lock_guard<std::mutex> lock(mutex);
  std::shared_ptr<const StopPsf>& t = tables[blades];
  if (!t) t = std::make_shared<const StopPsf>(blades);
  return t;
}

double StopPsf::radialEdge(int k) const {
  return kB * std::sinh(static_cast<double>(k) / kA);
}

int StopPsf::radialCell(double r) const {
  if (!(r < edges_.back())) return rows_;
  // k = ⌊a·asinh(r/b)⌋ in float (asinh x = log(x + √(x² + 1)); a third of double asinh's
  // time on the camera's hot path), then corrected against the stored edges: its error is far
  // below one cell.
  const float x = static_cast<float>(r / kB);
  const float cell = static_cast<float>(kA) * std::log(x + std::sqrt(x * x + 1.0f));
  int k = std::clamp(static_cast<int>(cell), 0, rows_ - 1);
  if (r < edges_[static_cast<size_t>(k)] && k > 0) --k;
  if (r >= edges_[static_cast<size_t>(k) + 1] && k < rows_ - 1) ++k;
  return k;
}

void StopPsf::buildCircle() {
  columns_ = period_ = 1;
  std::vector<double> mass(static_cast<size_t>(rows_));
  double total = 0.0;
  for (int k = 0; k < rows_; ++k) {
    const size_t i = static_cast<size_t>(k);
    mass[i] = airyEncircledEnergy(edges_[i + 1]) - airyEncircledEnergy(edges_[i]);
    total += mass[i];
  }
  truncated_ = 1.0 - airyEncircledEnergy(edges_.back());
  density_.resize(static_cast<size_t>(rows_));
  for (int k = 0; k < rows_; ++k) {
    const size_t i = static_cast<size_t>(k);
    const double area = M_PI * (edges_[i + 1] * edges_[i + 1] - edges_[i] * edges_[i]);
    density_[i] = mass[i] / total / area;
  }
  table_ = PiecewiseConstant2D(mass, 1, rows_);
}

// One period 2π/N of cells integrated by Gauss–Legendre on sub-cells, repeated N times.
// The N-gon (a vertex on +x) is symmetric about the period's middle, θ = π/N: the second half
// of the period's cells mirrors the first (period_ is even).
void StopPsf::buildPolygon() {
  period_ = 2 * ((kAngularCells / 2 + blades_ - 1) / blades_);
  columns_ = period_ * blades_;
  const double dTheta = 2.0 * M_PI / columns_;
  const size_t period = static_cast<size_t>(period_);
  std::vector<double> mass(static_cast<size_t>(rows_) * period);
  double total = 0.0;
  for (int k = 0; k < rows_; ++k) {
    const double r0 = edges_[static_cast<size_t>(k)], r1 = edges_[static_cast<size_t>(k) + 1];
    const int nr = std::max(1, static_cast<int>(std::ceil(kSubPerRadius * (r1 - r0))));
    const int nt = std::max(1, static_cast<int>(std::ceil(kSubPerArc * r1 * dTheta)));
    for (int c = 0; c < period_ / 2; ++c) {
      // Two-point Gauss–Legendre on nr × nt sub-cells: nodes at the sub-interval's middle
      // ± its half-width/√3, equal weights.
      double m = 0.0;
      for (int i = 0; i < nr; ++i) {
        const double dr = (r1 - r0) / nr, rc = r0 + (i + 0.5) * dr;
        for (const double r : {rc - 0.5 * dr * kGauss, rc + 0.5 * dr * kGauss})
          for (int j = 0; j < nt; ++j) {
            const double dt = dTheta / nt, tc = (c + (j + 0.5) / nt) * dTheta;
            for (const double t : {tc - 0.5 * dt * kGauss, tc + 0.5 * dt * kGauss})
              m += analytic({r * std::cos(t), r * std::sin(t)}) * r * (0.25 * dr * dt);
          }
      }
      const size_t row = static_cast<size_t>(k) * period;
      mass[row + static_cast<size_t>(c)] = mass[row + period - 1 - static_cast<size_t>(c)] = m;
      total += 2.0 * m;
    }
  }
  truncated_ = 1.0 - total * blades_;  // the table's energy against Parseval's 1
  density_.resize(mass.size());
  std::vector<double> weights(static_cast<size_t>(rows_) * static_cast<size_t>(columns_));
  for (int k = 0; k < rows_; ++k) {
    const double r0 = edges_[static_cast<size_t>(k)], r1 = edges_[static_cast<size_t>(k) + 1];
    const double area = 0.5 * (r1 * r1 - r0 * r0) * dTheta;
    for (int c = 0; c < columns_; ++c) {
      const size_t i = static_cast<size_t>(k) * period + static_cast<size_t>(c) % period;
      weights[static_cast<size_t>(k) * static_cast<size_t>(columns_) + static_cast<size_t>(c)] =
          mass[i];
      if (c < period_) density_[i] = mass[i] / (total * blades_) / area;
    }
  }
  table_ = PiecewiseConstant2D(weights, columns_, rows_);
}

glm::dvec2 StopPsf::sample(glm::vec2 u) const {
  const Sample2D s = table_.sample(u);
  const size_t k = static_cast<size_t>(s.row);
  // Where uv falls inside its cell, in [0, 1).
  const double fr = std::clamp(static_cast<double>(s.uv.y) * rows_ - s.row, 0.0, 1.0);
  const double ft = std::clamp(static_cast<double>(s.uv.x) * columns_ - s.column, 0.0, 1.0);
  const double r0 = edges_[k], r1 = edges_[k + 1];
  const double r = std::sqrt(r0 * r0 + fr * (r1 * r1 - r0 * r0));  // uniform over the area
  const double theta = (s.column + ft) * (2.0 * M_PI / columns_);
  return {r * std::cos(theta), r * std::sin(theta)};
}

int StopPsf::densityColumn(glm::dvec2 u) const {
  if (blades_ == 0) return 0;
  const double periodAngle = 2.0 * M_PI / blades_;
  double t = std::fmod(std::atan2(u.y, u.x), periodAngle);
  if (t < 0.0) t += periodAngle;
  return std::clamp(static_cast<int>(t / periodAngle * period_), 0, period_ - 1);
}

double StopPsf::densityAt(double r, int column) const {
  const int k = radialCell(r);
  if (k >= rows_) return 0.0;
  return density_[static_cast<size_t>(k) * static_cast<size_t>(period_) +
                  static_cast<size_t>(column)];
}

double StopPsf::density(glm::dvec2 u) const {
  return densityAt(std::hypot(u.x, u.y), densityColumn(u));
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
