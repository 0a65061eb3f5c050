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

// A window of the rear plane's upper half searched by a grid: x in [x0, x1], y in [0, y1].
struct Window {
  double x0, x1, y1;
};

// The passing cells of a grid × grid/2 search of `w`: their centres' extent and count.
struct GridHits {
  double loX = HUGE_VAL, hiX = -HUGE_VAL, hiY = -HUGE_VAL;
  double cell = 0.0;  // the larger of the cell's sides
  int count = 0;
  bool touchesBorder = false;
};

GridHits searchGrid(const PassTest& passes, const Window& w, int grid) {
  const int rows = grid / 2;
  const double cx = (w.x1 - w.x0) / grid, cy = w.y1 / rows;
  GridHits h;
  h.cell = std::max(cx, cy);
  for (int iy = 0; iy < rows; ++iy)
    for (int ix = 0; ix < grid; ++ix) {
      const double x = w.x0 + (ix + 0.5) * cx, y = (iy + 0.5) * cy;
      if (!passes(x, y)) continue;
      h.loX = std::min(h.loX, x);
      h.hiX = std::max(h.hiX, x);
      h.hiY = std::max(h.hiY, y);
      ++h.count;
      h.touchesBorder = h.touchesBorder || ix == 0 || ix == grid - 1 || iy == rows - 1;
    }
  return h;
}

// Enough passing cells that the bundle's extent is known to a few cells.
constexpr int kResolvedCells = 24;

// The coarse box (grown by two cells) of the passing cells, empty if none passes. Searched
// over `w`, doubled about its centre while a passing cell touches the border; then, while fewer than
// kResolvedCells pass, again over the box found, with cells that much smaller: found by
// probing, a double-Gauss stopped to f/30 had a bundle on the rear plane about one 0.94 mm
// cell wide, so some film radii found no cell centre in it (black pixels) or one (a bound of
// the wrong size), and the exposure fell to 0.8 of the camera equation's.
PupilBox coarseBox(const PassTest& passes, Window w, int grid) {
  GridHits h;
  for (int attempt = 0; attempt < 6; ++attempt) {
    h = searchGrid(passes, w, grid);
    if (!h.touchesBorder) break;
    const double centre = 0.5 * (w.x0 + w.x1), half = w.x1 - w.x0;  // twice as wide, same centre
    w = {centre - half, centre + half, 2.0 * w.y1};
  }
  for (int zoom = 0; zoom < 4 && h.count > 0 && h.count < kResolvedCells; ++zoom) {
    const Window inner{h.loX - 2.0 * h.cell, h.hiX + 2.0 * h.cell, h.hiY + 2.0 * h.cell};
    const GridHits finer = searchGrid(passes, inner, grid);
    if (finer.count <= h.count) break;  // no finer than it was: keep the box found
    h = finer;
  }
  if (h.count == 0) return {};
  return PupilBox{{h.loX - 2.0 * h.cell, -h.hiY - 2.0 * h.cell},
                  {h.hiX + 2.0 * h.cell, h.hiY + 2.0 * h.cell}};
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
  const int n = options.intervals;
  bounds_.resize(static_cast<size_t>(n));
  const auto passTest = [&](int k) {
    const double r0 = filmRadius * k / n, r1 = filmRadius * (k + 1) / n;
    return PassTest{lens, indices, sensorDistance, {r0, 0.5 * (r0 + r1), r1}, raysTraced_};
  };
  // Each interval's coarse box over the rear element; one whose grid no ray passed is
  // searched again around its neighbour's box (the bundle moves little from one interval to
  // the next: a bundle narrower than a cell can fall between the centres), forwards then
  // backwards. Still empty: no ray passes there (beyond the image circle).
  const double e = 1.5 * lens.rearClearRadius();
  std::vector<PupilBox> coarseBoxes(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k)
    coarseBoxes[static_cast<size_t>(k)] = coarseBox(passTest(k), {-e, e, e}, options.coarseGrid);
  // No interval found its bundle: a stop so small (f/40 on a 50 mm lens) that the bundle
  // falls between the cell centres everywhere. The axis's bundle is centred on it: searched
  // in windows halved about the axis until a cell centre falls inside it.
  const auto allEmpty = [&] {
    return std::all_of(coarseBoxes.begin(), coarseBoxes.end(),
                       [](const PupilBox& b) { return b.empty(); });
  };
  for (double window = 0.5 * e; allEmpty() && window > 1e-6 * e; window *= 0.5)
    coarseBoxes[0] = coarseBox(passTest(0), {-window, window, window}, options.coarseGrid);
  const auto fromNeighbour = [&](int k, int neighbour) {
    PupilBox& box = coarseBoxes[static_cast<size_t>(k)];
    const PupilBox& near = coarseBoxes[static_cast<size_t>(neighbour)];
    if (!box.empty() || near.empty()) return;
    const double grow = std::max(near.hi.x - near.lo.x, near.hi.y);
    box = coarseBox(passTest(k), {near.lo.x - grow, near.hi.x + grow, near.hi.y + grow},
                    options.coarseGrid);
  };
  for (int k = 1; k < n; ++k) fromNeighbour(k, k - 1);
  for (int k = n - 2; k >= 0; --k) fromNeighbour(k, k + 1);

  for (int k = 0; k < n; ++k) {
    const PassTest passes = passTest(k);
    const PupilBox& coarse = coarseBoxes[static_cast<size_t>(k)];
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
