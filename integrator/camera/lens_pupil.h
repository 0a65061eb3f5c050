// ExitPupilBounds: where on the rear vertex plane (lens space z = 0) rays from a film
// point get through the lens, precomputed per field height so that a camera samples few
// rays that are lost (after pbrt-v4's realistic camera, §5.2.4 of its book).
//
// | parameter      | unit | default | meaning |
// |----------------|------|---------|---------|
// | sensorDistance | m    | —       | s: the sensor plane is z = −s (LensSystem::focusSensorDistance) |
// | filmRadius     | m    | —       | the largest film distance from the axis (the sensor's half diagonal) |
// | intervals      | —    | 64      | radial film intervals [r_k, r_k+1), r_k = k·filmRadius/intervals |
// | coarseGrid     | —    | 32      | cells per side of the first, coarse search square |
// | columns, rows  | —    | 64, 32  | the fine grid over the coarse box's upper half (y ≥ 0) |
// | wavelengths    | nm   | λ_d; 360, λ_d, 830 if the lens disperses | a cell passes if its ray passes at any |
//
// For each interval, rays from a film point (r, 0, −s) — r stratified across the interval
// by the van der Corput sequence, one r per cell — to cell centres on the rear plane are
// traced through the lens (the lens is symmetric about the axis, the film point is put on
// +x, and the passing set is symmetric about y = 0, so only y ≥ 0 is traced):
//   1. coarse: a square [−E, E]² (E = 1.5 × the rear clear radius, doubled while a passing
//      cell touches its border); the box of the passing cells, grown by two cells;
//   2. fine: that box's upper half in rows × columns; each row's span [x0, x1] is the
//      union of its own and its two neighbours' passing cells, grown by one column, so a
//      row covers its strip's passing points (the pupil of a vignetted lens, an
//      intersection of discs, is convex; the rows follow it where a box cannot).
// The bound is the rows and their mirror images (y < 0); sample() picks a row by its
// area and a point uniform in it, turned by the film point's angle θ about the axis.
//
// sample() returns the point and the rows' total area: a camera ray from the film point to
// it has density 1/area on the rear plane. Points whose ray is lost are the caller's (its
// weight 0); measurePupilLoss reports their fraction.
#pragma once

#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/camera/lens_system.h"

namespace camsim {

struct PupilBox {
  glm::dvec2 lo{0.0}, hi{-1.0};  // m, in the frame where the film point is on +x
  bool empty() const { return !(hi.x >= lo.x && hi.y >= lo.y); }
  double area() const { return empty() ? 0.0 : (hi.x - lo.x) * (hi.y - lo.y); }  // m²
};

struct PupilSample {
  glm::dvec3 point{0.0};  // m, lens space, on the rear vertex plane (z = 0)
  double area = 0.0;      // m², of the bound sampled: density 1/area
};

class ExitPupilBounds {
 public:
  struct Options {
    int intervals = 64;
    int coarseGrid = 32;
    int columns = 64;
    int rows = 32;
    std::vector<double> wavelengthsNm;  // empty: the defaults above
  };

  ExitPupilBounds(const LensSystem& lens, double sensorDistance, double filmRadius,
                  const Options& options);
  ExitPupilBounds(const LensSystem& lens, double sensorDistance, double filmRadius)
      : ExitPupilBounds(lens, sensorDistance, filmRadius, Options{}) {}

  // A point on the rear plane for the film point (x, y) (m, lens space, on the sensor) from
  // u ∈ [0, 1)²; none where no ray gets through (an empty bound, past filmRadius).
  std::optional<PupilSample> sample(glm::dvec2 filmPoint, glm::dvec2 u) const;
  // Whether the rear-plane point (x, y) (m) lies in the film point's bound: every ray that
  // passes should (tested).
  bool covers(glm::dvec2 filmPoint, glm::dvec2 rearPoint) const;
  // The box around interval k's rows (m, film point on +x) and their area (m²).
  const PupilBox& bound(int k) const { return bounds_[static_cast<size_t>(k)].box; }
  double area(int k) const { return bounds_[static_cast<size_t>(k)].area; }
  int intervals() const { return static_cast<int>(bounds_.size()); }
  double filmRadius() const { return filmRadius_; }
  double sensorDistance() const { return sensorDistance_; }
  long long raysTraced() const { return raysTraced_; }  // while building

 private:
  struct Row {
    double y0, y1, x0, x1;  // m, a strip of the upper half (y ≥ 0)
  };
  struct Bound {
    std::vector<Row> rows;    // non-empty rows, increasing y
    std::vector<double> cdf;  // cumulative row area over the half, normalised to 1 at the end
    PupilBox box;             // around the rows and their mirror images
    double area = 0.0;        // m², both halves
  };
  std::vector<Bound> bounds_;
  double filmRadius_ = 0.0;
  double sensorDistance_ = 0.0;
  long long raysTraced_ = 0;
};

// The fraction of camera rays lost: film points uniform over a sensor of sensorSize (m,
// centred on the axis), pupil points from bounds.sample, traced at lambdaNm; a fixed seed.
struct PupilLoss {
  long long rays = 0;   // sampled with a non-empty box
  long long lost = 0;   // of those, lost in the lens
  long long noBox = 0;  // film points with an empty box (outside the image circle)
  double lostFraction() const { return rays > 0 ? static_cast<double>(lost) / rays : 0.0; }
};
PupilLoss measurePupilLoss(const LensSystem& lens, const ExitPupilBounds& bounds,
                           glm::dvec2 sensorSize, int samples, double lambdaNm = kLambdaDNm);

}  // namespace camsim
