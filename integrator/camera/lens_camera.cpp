#include "integrator/camera/lens_camera.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "sensor/base/check.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace {

// The lens with its stop set for the f-number (the file's stop when fNumber is 0).
LensSystem withStop(const LensSpec& spec) {
  LensSystem lens = LensSystem::forCamera(spec.prescription);
  const double diameter =
      spec.fNumber > 0.0 ? lens.stopDiameterForFNumber(spec.fNumber) : lens.maxStopDiameter();
  lens.setStop(diameter, spec.blades, spec.rotation);
  return lens;
}

}  // namespace

std::string realImageProblem(const LensSpec& spec) {
  const LensSystem lens = withStop(spec);
  const double sensor = lens.focusSensorDistance(objectDistanceFromVertex(lens, spec.focusDistance),
                                                 kLambdaDNm, FocusMethod::kBestRms);
  if (sensor > 0.0 && std::isfinite(sensor)) return "";
  const std::string object = spec.focusDistance > 0.0
                                 ? "a plane at " + formatShortest(spec.focusDistance) + " m"
                                 : "a distant object (focus_distance_m unset: focused at infinity)";
  return "the lens forms no real image of " + object +
         ": the real rays from there leave its rear surface diverging" +
         (std::isfinite(sensor)
              ? " (their best focus lies " + formatNumber(-sensor * 1e3, 4) + " mm in front of it)"
              : "");
}

double objectDistanceFromVertex(const LensSystem& lens, double focusDistance) {
  if (!(focusDistance > 0.0)) return kInfiniteDistance;
  const double entrancePupilZ = lens.paraxial().entrancePupilZ;
  return focusDistance + entrancePupilZ - lens.frontVertexZ();
}

LensCamera::LensCamera(const LensSpec& spec, glm::dvec2 sensorSize)
    : lens_(withStop(spec)),
      fNumber_(lens_.paraxial().fNumber),
      focusDistance_(spec.focusDistance),
      entrancePupilZ_(lens_.paraxial().entrancePupilZ),
      sensorDistance_(lens_.focusSensorDistance(objectDistanceFromVertex(lens_, focusDistance_),
                                                kLambdaDNm, FocusMethod::kBestRms)),
      bounds_(lens_, sensorDistance_, 0.5 * glm::length(sensorSize)),
      disperses_(lens_.disperses()),
      indicesD_(lens_.indicesAt(kLambdaDNm)),
      paraxial_(
          lens_.paraxial(kLambdaDNm, objectDistanceFromVertex(lens_, focusDistance_), sensorSize)) {
  CAMSIM_CHECK(sensorDistance_ > 0.0 && std::isfinite(sensorDistance_));
  // A lens no ray from the film gets through (an aspheric term that bends every ray out, a
  // clear aperture of 1e-300 mm) rendered black, exit 0: refused (the caller names the file).
  bool passes = false;
  for (int k = 0; k < bounds_.intervals() && !passes; ++k) passes = bounds_.area(k) > 0.0;
  if (!passes)
    throw InputError({}, "camera.lens",
                     "no ray from the film gets through this lens at its f-number (every exit "
                     "pupil bound is empty): check its clear apertures, thicknesses and "
                     "aspheric terms");
}

std::optional<LensCameraRay> LensCamera::generate(glm::dvec2 s, glm::dvec2 u,
                                                  double lambdaNm) const {
  const glm::dvec2 film(-s.x, -s.y);  // the lens inverts the image
  const std::optional<PupilSample> rear = bounds_.sample(film, u);
  if (!rear) return std::nullopt;
  const glm::dvec3 filmPoint(film, -sensorDistance_);
  const glm::dvec3 v = rear->point - filmPoint;
  const double d2 = glm::dot(v, v);
  LensRay in;
  in.origin = filmPoint;
  in.direction = v / std::sqrt(d2);
  const std::optional<LensRay> out =
      disperses_ ? lens_.traceFromFilm(in, lambdaNm) : lens_.traceFromFilm(in, indicesD_);
  if (!out) return std::nullopt;
  LensCameraRay r;
  r.origin = out->origin - glm::dvec3(0.0, 0.0, entrancePupilZ_);
  r.direction = out->direction;
  r.geometric = rear->area * v.z * v.z / (d2 * d2);  // area · cosθ_film · cosθ_rear / d²
  return r;
}

}  // namespace camsim
