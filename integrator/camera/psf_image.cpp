// PSF images: the forward trace and the statistics of psf_image.h (which states the model).
#include "integrator/camera/psf_image.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "integrator/camera/secant.h"
#include "integrator/geometry/math.h"
#include "integrator/sampling/rng.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace {

// Numbers in messages with 10 significant digits (sensor/base/format.h).
std::string psfNumber(double v) {
  return formatNumber(v, 10);
}

[[noreturn]] void refusePsf(const std::string& key, const std::string& message) {
  throw InputError({}, key, message);
}

// A ray that reached the film: upright film point (m) and its weight.
struct PsfHit {
  glm::dvec2 s{0.0};
  double weight = 1.0;
};

// The lens with every clear aperture but the stop's widened (to 3× its diameter, within the
// sphere's own limit; aspheres keep theirs): what passes it passed the stop's opening.
LensSystem withoutRims(const LensSystem& lens) {
  LensPrescription p = lens.prescription();
  for (LensSurface& s : p.surfaces) {
    if (s.stop || s.aspheric()) continue;
    double wider = 3.0 * s.apertureDiameter;
    if (s.radius != 0.0) wider = std::min(wider, 1.998 * std::abs(s.radius));
    s.apertureDiameter = std::max(s.apertureDiameter, wider);
  }
  LensSystem out(std::move(p));
  const Aperture& stop = lens.stop();
  const double diameter = std::sqrt(4.0 * stop.area() / M_PI);
  out.setStop(std::min(diameter, out.maxStopDiameter()), stop.blades(), stop.rotation());
  return out;
}

// The real chief ray in object space (lens axes, heading +z) from the upright film point
// (h, 0) — lens space (−h, 0, −s) — through the stop's centre at λ_d, traced through `open`
// (rims widened: a vignetted chief ray still counts, as LensSystem::chiefRayAngle's). Aimed
// by the secant method on the stop's height, from the rear group alone (the surfaces behind
// the stop, whose front surface is then the stop's plane). None if the aim fails.
// Found by probing: aimed from 0 towards the far side of the axis and through the stop's own
// rim, the secant's iterates missed the stop at field points the render lights (the
// double-Gauss's corner, the fisheye beyond 12.5 mm), and psf refused them. Now aimed from
// the paraxial exit pupil's direction, at the stop's plane widened tenfold (aimed at, not a
// rim: the chief ray is then traced through `open`, the real stop included).
std::optional<LensRay> psfChiefRay(const LensSystem& open, double h, double sensor) {
  LensPrescription rearGroup = open.prescription();
  rearGroup.surfaces.erase(rearGroup.surfaces.begin(),
                           rearGroup.surfaces.begin() + rearGroup.stopIndex);
  rearGroup.stopIndex = 0;
  rearGroup.surfaces.front().apertureDiameter *= 10.0;
  const LensSystem rear(std::move(rearGroup));
  const LensSystem::Indices nRear = rear.indicesAt(kLambdaDNm);
  const glm::dvec3 film(-h, 0.0, -sensor);
  const auto aim = [&film](double x) {
    return LensRay{film, glm::normalize(glm::dvec3(x, 0.0, 0.0) - film)};
  };
  const auto stopHeight = [&](double x) -> std::optional<double> {
    const std::optional<LensRay> atStop = rear.traceFromFilm(aim(x), nRear);
    if (!atStop) return std::nullopt;
    return atStop->origin.x;
  };
  // The paraxial chief ray heads for the exit pupil's centre (lens-space z = exitPupilZ):
  // it crosses the rear vertex's plane at film.x · z_XP / (z_XP + s).
  const double exitPupilZ = open.paraxial().exitPupilZ;
  const double guess = film.x * exitPupilZ / (exitPupilZ + sensor);
  const double step = 0.01 * open.rearClearRadius() * (h >= 0.0 ? -1.0 : 1.0);
  const std::optional<double> x = secantRoot(stopHeight, guess, guess + step);
  if (!x) return std::nullopt;
  return open.traceFromFilm(aim(*x), kLambdaDNm);
}

// Where the traced lens's rays land (upright film, m), and the vignetted share.
struct PsfTracedRays {
  std::vector<PsfHit> hits;
  double lostFraction = 0.0;
};

PsfTracedRays tracePsfLens(const LensCamera& camera, const PsfSettings& settings,
                           double imageHeight, double objectDistance, Pcg32& rng) {
  const LensSystem& lens = camera.lens();
  const LensSystem open = withoutRims(lens);
  const double sensor = camera.sensorDistance();
  const std::optional<LensRay> chief = psfChiefRay(open, imageHeight, sensor);
  if (!chief)
    refusePsf("field", psfNumber(settings.field) + ": the film point " +
                           psfNumber(imageHeight * 1e3) +
                           " mm off axis has no chief ray through the lens");
  const bool infinite = std::isinf(objectDistance);
  const double front = lens.frontVertexZ();
  const double discRadius = 1.5 * std::sqrt(lens.shape(0).clearRadius2);
  // The object point on the chief ray at objectDistance from the entrance pupil (the
  // object is on the +x side: the upright image); at infinity the rays come along it.
  const double reach =
      (camera.entrancePupilZ() + objectDistance - chief->origin.z) / chief->direction.z;
  const glm::dvec3 object = infinite ? glm::dvec3(0.0) : chief->origin + reach * chief->direction;
  const glm::dvec3 parallel = -chief->direction;
  const LensSystem::Indices n = lens.indicesAt(settings.wavelengthNm);

  PsfTracedRays out;
  out.hits.reserve(static_cast<size_t>(settings.rays));
  double through = 0.0, passed = 0.0;
  for (std::int64_t i = 0; i < settings.rays; ++i) {
    const glm::vec2 u(rng.uniform(), rng.uniform());
    const glm::dvec2 p = discRadius * glm::dvec2(sampleUniformDiskConcentric(u));
    const glm::dvec3 target(p, front);
    LensRay ray;
    double weight = 1.0;
    if (infinite) {  // start in front of any bulge of the front surface
      ray.direction = parallel;
      ray.origin = target - 4.0 * discRadius * parallel;
    } else {
      // Scaled to its largest component first: beyond about 1.3e154 m the squared length
      // overflowed and the direction was NaN (found by probing: "no ray reaches the film").
      const glm::dvec3 v = target - object;
      const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
      ray.direction = glm::normalize(v / largest);
      const double distance = glm::length(v / largest) * largest;
      // A far object's ray starts on its line as near the lens as the infinite case's: from
      // the object point itself, the front surface's intersection (terms ∝ distance²
      // against a clear radius² of 1e-3 m²) lost all precision beyond about 10 km (probing:
      // RMS 8× too large at 1e6 m, no ray at all from 1e8 m).
      ray.origin = distance > 4.0 * discRadius ? target - 4.0 * discRadius * ray.direction : object;
      const double c = -ray.direction.z;  // cos θ to the axis
      weight = c * c * c * c;
    }
    if (open.traceFromObject(ray, n)) through += weight;
    const std::optional<LensRay> leaving = lens.traceFromObject(ray, n);
    if (!leaving || !(leaving->direction.z < 0.0)) continue;
    passed += weight;
    const double t = (-sensor - leaving->origin.z) / leaving->direction.z;
    const glm::dvec3 hit = leaving->origin + t * leaving->direction;
    out.hits.push_back({glm::dvec2(-hit.x, -hit.y), weight});  // the lens inverts
  }
  out.lostFraction = through > 0.0 ? std::clamp(1.0 - passed / through, 0.0, 1.0) : 1.0;
  return out;
}

// The thin lens (or pinhole): every ray through the stop lands (psf_image.h's equations).
std::vector<PsfHit> tracePsfThinLens(const PhysicalCamera& camera, const PsfSettings& settings,
                                     double imageHeight, double objectDistance, Pcg32& rng) {
  const PhysicalCameraParams& p = camera.params();
  const double f = p.focalLength, zi = camera.imageDistance();
  const bool infinite = std::isinf(objectDistance);
  const double conjugate = infinite ? f : f * objectDistance / (objectDistance - f);  // z_i'
  const glm::dvec2 slope(imageHeight / zi, 0.0);
  const glm::dvec2 image = -slope * conjugate;  // O', inverted
  std::optional<Aperture> stop;
  if (p.aperture) stop.emplace(p.apertureDiameter(), p.aperture->blades, p.aperture->rotation);
  std::vector<PsfHit> hits;
  hits.reserve(static_cast<size_t>(settings.rays));
  for (std::int64_t i = 0; i < settings.rays; ++i) {
    const glm::vec2 u(rng.uniform(), rng.uniform());
    const glm::dvec2 lens = stop ? glm::dvec2(stop->sample(u)) : glm::dvec2(0.0);
    const glm::dvec2 film = lens + (image - lens) * (zi / conjugate);
    hits.push_back({-film, 1.0});
  }
  return hits;
}

// The radius about c enclosing `fraction` of the weight (hits sorted by radius).
double psfEncircledRadius(const std::vector<std::pair<double, double>>& byRadius, double total,
                          double fraction) {
  double sum = 0.0;
  for (const auto& [r, w] : byRadius) {
    sum += w;
    if (sum >= fraction * total) return r;
  }
  return byRadius.empty() ? 0.0 : byRadius.back().first;
}

}  // namespace

void checkPsfSettings(const PsfSettings& s) {
  if (!(s.field >= 0.0 && s.field <= psf_ranges::kFieldMax))
    refusePsf("field", psfNumber(s.field) + " is outside " +
                           formatRange(0.0, psf_ranges::kFieldMax) +
                           " (the image height over the sensor's half diagonal)");
  if (!(s.wavelengthNm >= psf_ranges::kLambdaMinNm && s.wavelengthNm <= psf_ranges::kLambdaMaxNm))
    refusePsf("wavelength", psfNumber(s.wavelengthNm) + " nm is outside " +
                                formatRange(psf_ranges::kLambdaMinNm, psf_ranges::kLambdaMaxNm) +
                                " nm");
  if (s.size < psf_ranges::kSizeMin || s.size > psf_ranges::kSizeMax)
    refusePsf("size", std::to_string(s.size) + " px is outside [" +
                          std::to_string(psf_ranges::kSizeMin) + ", " +
                          std::to_string(psf_ranges::kSizeMax) + "]");
  if (s.oversample < psf_ranges::kOversampleMin || s.oversample > psf_ranges::kOversampleMax)
    refusePsf("oversample", std::to_string(s.oversample) + " is outside [" +
                                std::to_string(psf_ranges::kOversampleMin) + ", " +
                                std::to_string(psf_ranges::kOversampleMax) + "]");
  if (static_cast<std::int64_t>(s.size) * s.oversample > psf_ranges::kCellsMax)
    refusePsf("oversample", "size × oversample = " + std::to_string(s.size * s.oversample) +
                                " cells per side is over " + std::to_string(psf_ranges::kCellsMax));
  if (s.rays < psf_ranges::kRaysMin || s.rays > psf_ranges::kRaysMax)
    refusePsf("rays", std::to_string(s.rays) + " is outside [" +
                          std::to_string(psf_ranges::kRaysMin) + ", " +
                          std::to_string(psf_ranges::kRaysMax) + "]");
  if (!(s.objectDistance >= 0.0 && std::isfinite(s.objectDistance)))
    refusePsf("object_distance",
              psfNumber(s.objectDistance) + " m: expected ≥ 0 (0: the focus distance)");
}

PsfImage computePsf(const PhysicalCamera& camera, const PsfSettings& settings) {
  checkPsfSettings(settings);
  const PhysicalCameraParams& p = camera.params();
  const LensCamera* traced = camera.lensCamera();
  PsfImage out;
  out.settings = settings;
  out.imageHeight = settings.field * 0.5 * std::hypot(p.sensorSize.x, p.sensorSize.y);
  const double focus = traced ? traced->focusDistance() : p.focusDistance;
  const double distance = settings.objectDistance > 0.0 ? settings.objectDistance : focus;
  out.objectDistance = distance > 0.0 ? distance : kInfiniteDistance;
  if (!traced && !(out.objectDistance > p.focalLength))
    refusePsf("object_distance", psfNumber(distance) + " m is not beyond the focal length " +
                                     psfNumber(p.focalLength * 1e3) + " mm: no real image");
  if (traced && std::isfinite(out.objectDistance)) {
    const double fromVertex = objectDistanceFromVertex(traced->lens(), out.objectDistance);
    if (!(fromVertex > traced->lens().paraxial().frontFocalLength))
      refusePsf("object_distance",
                psfNumber(distance) + " m is inside the lens's front focal length");
  }

  Pcg32 rng(settings.seed, 0x9f5b1c3d7e2a4u);  // the PSF's own stream of the seed
  std::vector<PsfHit> hits;
  if (traced) {
    PsfTracedRays r = tracePsfLens(*traced, settings, out.imageHeight, out.objectDistance, rng);
    hits = std::move(r.hits);
    out.lostFraction = r.lostFraction;
  } else {
    hits = tracePsfThinLens(camera, settings, out.imageHeight, out.objectDistance, rng);
  }
  if (hits.empty())
    refusePsf("field",
              psfNumber(settings.field) + ": no ray from the object point reaches the film");
  if (const Diffraction* d = camera.diffraction()) {
    out.workingFNumber = d->workingFNumber();
    // δ drawn from the renderer's own PSF at this one wavelength.
    for (PsfHit& h : hits) {
      const glm::vec2 u{rng.uniform(), rng.uniform()};
      h.s += d->sampleOffset(u, settings.wavelengthNm);
    }
  }
  out.landed = static_cast<std::int64_t>(hits.size());

  // The grid: s_ref at the centre of cell (n/2, n/2); row 0 at the top.
  const int n = settings.size * settings.oversample;
  out.cells = n;
  out.cellWidth = p.sensorSize.x / p.resolution.x / settings.oversample;
  out.cellHeight = p.sensorSize.y / p.resolution.y / settings.oversample;
  out.energy.assign(static_cast<size_t>(n) * static_cast<size_t>(n), 0.0);
  double total = 0.0, inside = 0.0, cx = 0.0, cy = 0.0;
  for (const PsfHit& h : hits) {
    const double dx = h.s.x - out.imageHeight, dy = h.s.y;
    total += h.weight;
    cx += h.weight * dx;
    cy += h.weight * dy;
    const double col = std::floor(dx / out.cellWidth + 0.5) + n / 2;
    const double row = n / 2 - std::floor(dy / out.cellHeight + 0.5);
    if (col < 0 || row < 0 || col >= n || row >= n) continue;
    out.energy[static_cast<size_t>(row) * static_cast<size_t>(n) + static_cast<size_t>(col)] +=
        h.weight;
    inside += h.weight;
  }
  // No ray in the grid: an all-zero image is no PSF (its sum is promised to be 1).
  if (!(inside > 0.0))
    refusePsf("size", std::to_string(settings.size) + " px: no ray lands in the grid (the PSF's " +
                          "centroid is " + std::to_string(std::lround(cx / total * 1e6)) + ", " +
                          std::to_string(std::lround(cy / total * 1e6)) +
                          " µm from the chief ray's image point): raise --size");
  for (double& e : out.energy) e /= inside;
  out.outsideFraction = total > 0.0 ? 1.0 - inside / total : 1.0;
  out.centroidX = cx / total;
  out.centroidY = cy / total;

  std::vector<std::pair<double, double>> byRadius;
  byRadius.reserve(hits.size());
  double second = 0.0;
  for (const PsfHit& h : hits) {
    const double r = std::hypot(h.s.x - out.imageHeight - out.centroidX, h.s.y - out.centroidY);
    second += h.weight * r * r;
    byRadius.emplace_back(r, h.weight);
  }
  out.rmsRadius = std::sqrt(second / total);
  std::sort(byRadius.begin(), byRadius.end());
  out.encircled50 = psfEncircledRadius(byRadius, total, 0.5);
  out.encircled80 = psfEncircledRadius(byRadius, total, 0.8);
  return out;
}

}  // namespace camsim
