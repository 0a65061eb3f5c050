#include "integrator/camera/lens_pupil.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "integrator/sampling/rng.h"
#include "sensor/base/check.h"

namespace camsim {
namespace {

// Whether the ray from a film point (r, 0, −s), r one of an interval's radii, to (x, y, 0)
// passes at any wavelength.
struct PassTest {
  const LensSystem& lens;
  const std::vector<LensSystem::Indices>& indices;
  double sensorDistance;
  std::array<double, 3> radii;
  long long& traced;

  bool operator()(double x, double y) const {
    for (const double r : radii) {
      const glm::dvec3 film(r, 0.0, -sensorDistance);
      const LensRay ray{film, glm::normalize(glm::dvec3(x, y, 0.0) - film)};
      for (const LensSystem::Indices& n : indices) {
        ++traced;
        if (lens.traceFromFilm(ray, n)) return true;
      }
    }
    return false;
  }
};

// The coarse box (grown by two cells) of the passing cells over [−E, E] × [0, E], E doubled
// while a passing cell touches the border; empty if none passes.
PupilBox coarseBox(const PassTest& passes, double extent, int grid) {
  const int rows = grid / 2;
  PupilBox box;
  for (int attempt = 0; attempt < 6; ++attempt, extent *= 2.0) {
    const double cell = 2.0 * extent / grid;
    double loX = HUGE_VAL, hiX = -HUGE_VAL, hiY = -HUGE_VAL;
    bool touchesBorder = false;
    for (int iy = 0; iy < rows; ++iy)
      for (int ix = 0; ix < grid; ++ix) {
        const double x = -extent + (ix + 0.5) * cell, y = (iy + 0.5) * cell;
        if (!passes(x, y)) continue;
        loX = std::min(loX, x);
        hiX = std::max(hiX, x);
        hiY = std::max(hiY, y);
        touchesBorder = touchesBorder || ix == 0 || ix == grid - 1 || iy == rows - 1;
      }
    box = PupilBox{};
    if (hiX >= loX)  // two cells: a sliver narrower than a cell may pass beyond the last centre
      box = PupilBox{{loX - 2.0 * cell, -hiY - 2.0 * cell}, {hiX + 2.0 * cell, hiY + 2.0 * cell}};
    if (!touchesBorder) break;
  }
  return box;
}

}  // namespace

ExitPupilBounds::ExitPupilBounds(const LensSystem& lens, double sensorDistance, double filmRadius,
                                 const Options& options)
    : filmRadius_(filmRadius), sensorDistance_(sensorDistance) {
  CAMSIM_CHECK(filmRadius > 0.0 && sensorDistance > 0.0 && options.intervals >= 1);
  CAMSIM_CHECK(options.coarseGrid >= 4 && options.coarseGrid % 2 == 0);
  CAMSIM_CHECK(options.columns >= 2 && options.rows >= 2);
  std::vector<double> lambdas = options.wavelengthsNm;
  if (lambdas.empty())
    lambdas = lens.disperses() ? std::vector<double>{360.0, kLambdaDNm, 830.0}
                               : std::vector<double>{kLambdaDNm};
  std::vector<LensSystem::Indices> indices;
  for (const double lambda : lambdas) indices.push_back(lens.indicesAt(lambda));
  bounds_.resize(static_cast<size_t>(options.intervals));
  for (int k = 0; k < options.intervals; ++k) {
    const double r0 = filmRadius * k / options.intervals;
    const double r1 = filmRadius * (k + 1) / options.intervals;
    const PassTest passes{lens, indices, sensorDistance, {r0, 0.5 * (r0 + r1), r1}, raysTraced_};
    const PupilBox coarse = coarseBox(passes, 1.5 * lens.rearClearRadius(), options.coarseGrid);
    if (coarse.empty()) continue;

    // The fine rows over the coarse box's upper half.
    const int columns = options.columns, rows = options.rows;
    const double cx = (coarse.hi.x - coarse.lo.x) / columns, cy = coarse.hi.y / rows;
    std::vector<double> minX(static_cast<size_t>(rows), HUGE_VAL);
    std::vector<double> maxX(static_cast<size_t>(rows), -HUGE_VAL);
    for (int iy = 0; iy < rows; ++iy)
      for (int ix = 0; ix < columns; ++ix) {
        const double x = coarse.lo.x + (ix + 0.5) * cx, y = (iy + 0.5) * cy;
        if (!passes(x, y)) continue;
        minX[static_cast<size_t>(iy)] = std::min(minX[static_cast<size_t>(iy)], x);
        maxX[static_cast<size_t>(iy)] = std::max(maxX[static_cast<size_t>(iy)], x);
      }
    Bound& b = bounds_[static_cast<size_t>(k)];
    double half = 0.0;
    for (int iy = 0; iy < rows; ++iy) {
      double x0 = HUGE_VAL, x1 = -HUGE_VAL;
      for (int j = std::max(0, iy - 1); j <= std::min(rows - 1, iy + 1); ++j) {
        x0 = std::min(x0, minX[static_cast<size_t>(j)]);
        x1 = std::max(x1, maxX[static_cast<size_t>(j)]);
      }
      if (!(x1 >= x0)) continue;
      const Row row{iy * cy, (iy + 1) * cy, x0 - cx, x1 + cx};
      b.rows.push_back(row);
      half += (row.y1 - row.y0) * (row.x1 - row.x0);
      b.cdf.push_back(half);
      b.box.lo = glm::dvec2(std::min(b.box.empty() ? row.x0 : b.box.lo.x, row.x0), -row.y1);
      b.box.hi = glm::dvec2(std::max(b.box.empty() ? row.x1 : b.box.hi.x, row.x1), row.y1);
    }
    for (double& c : b.cdf) c /= half;
    b.area = 2.0 * half;
  }
}

std::optional<PupilSample> ExitPupilBounds::sample(glm::dvec2 filmPoint, glm::dvec2 u) const {
  const double r = glm::length(filmPoint);
  if (!(r <= filmRadius_)) return std::nullopt;
  const int k = std::min(static_cast<int>(r / filmRadius_ * intervals()), intervals() - 1);
  const Bound& b = bounds_[static_cast<size_t>(k)];
  if (b.rows.empty()) return std::nullopt;
  // u.y picks the half (y < 0 mirrored), then a row by area, then y within the row.
  const bool lower = u.y < 0.5;
  const double v = lower ? 2.0 * u.y : 2.0 * u.y - 1.0;
  const size_t i =
      std::min(static_cast<size_t>(std::upper_bound(b.cdf.begin(), b.cdf.end(), v) - b.cdf.begin()),
               b.rows.size() - 1);
  const double c0 = i > 0 ? b.cdf[i - 1] : 0.0;
  const double t = std::clamp((v - c0) / (b.cdf[i] - c0), 0.0, 1.0);
  const Row& row = b.rows[i];
  const double y = (row.y0 + t * (row.y1 - row.y0)) * (lower ? -1.0 : 1.0);
  const double x = row.x0 + u.x * (row.x1 - row.x0);
  const double c = r > 0.0 ? filmPoint.x / r : 1.0, s = r > 0.0 ? filmPoint.y / r : 0.0;
  return PupilSample{{c * x - s * y, s * x + c * y, 0.0}, b.area};
}

bool ExitPupilBounds::covers(glm::dvec2 filmPoint, glm::dvec2 rearPoint) const {
  const double r = glm::length(filmPoint);
  if (!(r <= filmRadius_)) return false;
  const int k = std::min(static_cast<int>(r / filmRadius_ * intervals()), intervals() - 1);
  const double c = r > 0.0 ? filmPoint.x / r : 1.0, s = r > 0.0 ? filmPoint.y / r : 0.0;
  const double x = c * rearPoint.x + s * rearPoint.y,
               y = std::abs(-s * rearPoint.x + c * rearPoint.y);
  for (const Row& row : bounds_[static_cast<size_t>(k)].rows)
    if (y >= row.y0 && y <= row.y1 && x >= row.x0 && x <= row.x1) return true;
  return false;
}

PupilLoss measurePupilLoss(const LensSystem& lens, const ExitPupilBounds& bounds,
                           glm::dvec2 sensorSize, int samples, double lambdaNm) {
  const LensSystem::Indices n = lens.indicesAt(lambdaNm);
  Pcg32 rng(39, 7);
  const auto uniform = [&rng] { return (rng.next() + 0.5) * 0x1p-32; };
  PupilLoss loss;
  for (int i = 0; i < samples; ++i) {
    const glm::dvec2 film((uniform() - 0.5) * sensorSize.x, (uniform() - 0.5) * sensorSize.y);
    const glm::dvec2 u(uniform(), uniform());
    const std::optional<PupilSample> p = bounds.sample(film, u);
    if (!p) {
      ++loss.noBox;
      continue;
    }
    const glm::dvec3 origin(film, -bounds.sensorDistance());
    ++loss.rays;
    if (!lens.traceFromFilm({origin, glm::normalize(p->point - origin)}, n)) ++loss.lost;
  }
  return loss;
}

}  // namespace camsim
