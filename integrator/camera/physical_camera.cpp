#include "integrator/camera/physical_camera.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "sensor/base/check.h"

namespace camsim {
namespace {

// The lens point (x, y, 0) of a pupil turned from facing +z to face the unit direction d:
// the rotation about z × d that takes z to d (d straight back: a half turn about x).
glm::dvec3 turnedLensPoint(const glm::dvec2& lens, const glm::dvec3& d) {
  const double onePlusC = 1.0 + d.z;
  if (!(onePlusC > 1e-12)) return {lens.x, -lens.y, 0.0};
  const double w = -(d.x * lens.x + d.y * lens.y);
  return {lens.x + d.x * w / onePlusC, lens.y + d.y * w / onePlusC, w};
}

}  // namespace

double PhysicalCamera::workingFNumber() const {
  // A traced lens: its exit pupil's, not the thin-lens stand-in's (pupil magnification and
  // close focus are in it).
  return lensCamera_ ? lensCamera_->paraxial().workingFNumber
                     : imageDistance_ / p_.apertureDiameter();
}

PhysicalCamera::PhysicalCamera(PhysicalCameraParams params) : p_(std::move(params)) {
  if (p_.lens) initLens();
  const double f = p_.focalLength;
  CAMSIM_CHECK(f > 0.0 && p_.fNumber > 0.0 && p_.fillFactor > 0.0 && p_.fillFactor <= 1.0);
  CAMSIM_CHECK(p_.focusDistance == 0.0 || p_.focusDistance > f);
  imageDistance_ = p_.focusDistance > 0.0 ? f * p_.focusDistance / (p_.focusDistance - f) : f;
  const glm::dvec2 pitch = p_.sensorSize / glm::dvec2(p_.resolution);
  pixelArea_ = pitch.x * pitch.y * p_.fillFactor;
  projection_ = p_.projection;
  if (p_.intrinsicsFromLens) {
    const bool equirect = projection_.model == ProjectionModel::kEquirectangular;
    projection_.fx = equirect ? p_.resolution.x / (2.0 * M_PI) : imageDistance_ / pitch.x;
    projection_.fy = equirect ? p_.resolution.y / M_PI : imageDistance_ / pitch.y;
    projection_.cx = 0.5 * p_.resolution.x - 0.5;
    projection_.cy = 0.5 * p_.resolution.y - 0.5;
  }
  intrinsics_ = {projection_.fx, projection_.fy, projection_.cx, projection_.cy};
  idealPinhole_ = p_.intrinsicsFromLens && isUndistortedOpenCv(projection_);
  turningPupil_ = projection_.model != ProjectionModel::kOpenCv;
  const double diameter = p_.apertureDiameter();
  if (p_.aperture) stop_.emplace(diameter, p_.aperture->blades, p_.aperture->rotation);
  if (p_.aperture && p_.aperture->diffraction) diffraction_.emplace(*p_.aperture, workingFNumber());
  pixelsPerMetre_ = glm::dvec2(1.0 / pitch.x, -1.0 / pitch.y);
  photositeHalfSide_ = 0.5 * std::sqrt(p_.fillFactor) * pitch;
  apertureArea_ = stop_ ? stop_->area() : M_PI * 0.25 * diameter * diameter;
  transmittanceIsOne_ =
      p_.lensTransmittance.minValue() == 1.0 && p_.lensTransmittance.maxValue() == 1.0;
  fastPinhole_ =
      !lensCamera_ && !p_.aperture && idealPinhole_ && p_.motion.empty() && transmittanceIsOne_;
  const glm::dmat4& m = p_.worldFromCamera;
  right_ = glm::vec3(m[0]);
  up_ = glm::vec3(m[1]);
  forward_ = glm::vec3(m[2]);
  origin_ = glm::vec3(m[3]);
  filmScale_ = glm::vec2(p_.sensorSize.x / p_.resolution.x, -p_.sensorSize.y / p_.resolution.y);
  filmOffset_ = glm::vec2(-0.5 * p_.sensorSize.x, 0.5 * p_.sensorSize.y);
  zi_ = static_cast<float>(imageDistance_);
  weightScale_ = static_cast<float>(pixelArea_ * p_.shutter.effectiveTime() * apertureArea_ *
                                    imageDistance_ * imageDistance_);
}

std::optional<CameraRay> PhysicalCamera::generatePinholeRay(const CameraSample& sample) const {
  const glm::vec2 s = sample.pFilm * filmScale_ + filmOffset_;
  const float d2 = s.x * s.x + s.y * s.y + zi_ * zi_;
  CameraRay cr;
  cr.ray.o = origin_;
  cr.ray.d = glm::normalize(s.x * right_ + s.y * up_ + zi_ * forward_);
  cr.ray.time = sample.time;
  cr.weight = SampledSpectrum(weightScale_ / (d2 * d2));
  return cr;
}

glm::dmat4 PhysicalCamera::worldFromCameraAt(double t) const {
  if (p_.motion.empty()) return p_.worldFromCamera;
  const glm::dmat4 local = p_.motion.at(t);  // rotation about the camera centre + offset
  glm::dmat4 m = p_.worldFromCamera * glm::dmat4(glm::dmat3(local));
  m[3] = p_.worldFromCamera[3] + glm::dvec4(glm::dvec3(local[3]), 0.0);
  return m;
}

std::optional<CameraRay> PhysicalCamera::generateRay(const CameraSample& sample,
                                                     const SampledWavelengths& lambda) const {
  if (fastPinhole_) return generatePinholeRay(sample);
  return generateRay(sample, lambda, worldFromCameraAt(sample.time));
}

std::optional<CameraRay> PhysicalCamera::generateRay(const CameraSample& sample,
                                                     const SampledWavelengths& lambda,
                                                     const glm::dmat4& m) const {
  if (fastPinhole_) return generatePinholeRay(sample);
  if (diffraction_) return generateDiffractedRay(sample, lambda, m);
  return generateLensRay(sample, lambda, m);
}

std::optional<CameraRay> PhysicalCamera::generateDiffractedRay(const CameraSample& sample,
                                                               const SampledWavelengths& lambda,
                                                               const glm::dmat4& m) const {
  const DiffractionSample d =
      diffraction_->sample(sample.pDiffraction, sample.uDiffractionWavelength, lambda,
                           {glm::dvec2(sample.pPhotosite) / pixelsPerMetre_, photositeHalfSide_});
  CameraSample moved = sample;
  moved.pFilm = glm::vec2(glm::dvec2(sample.pFilm) + d.offset * pixelsPerMetre_);
  std::optional<CameraRay> cr = generateLensRay(moved, lambda, m);
  if (cr) cr->weight *= d.weight;
  return cr;
}

std::optional<CameraRay> PhysicalCamera::generateLensRay(const CameraSample& sample,
                                                         const SampledWavelengths& lambda,
                                                         const glm::dmat4& m) const {
  if (lensCamera_) return generateTracedRay(sample, lambda, m);
  if (!idealPinhole_) return generateModelRay(sample, lambda, m);
  // Sensor point, upright image coordinates (m): x right, y up, origin at the centre.
  const glm::dvec2 ndc = glm::dvec2(sample.pFilm) / glm::dvec2(p_.resolution);
  const glm::dvec2 s((ndc.x - 0.5) * p_.sensorSize.x, (0.5 - ndc.y) * p_.sensorSize.y);
  const double zi = imageDistance_;

  // Chief-ray direction through the lens centre.
  const glm::dvec3 chief(s.x / zi, s.y / zi, 1.0);

  glm::dvec3 origin(0.0), direction = chief;
  glm::dvec2 lens(0.0);
  if (p_.aperture) {
    lens = glm::dvec2(stop_->sample(sample.pLens));
    origin = glm::dvec3(lens, 0.0);
    // Every ray from this film point meets the chief ray on the plane of focus.
    direction = p_.focusDistance > 0.0 ? chief * p_.focusDistance - origin : chief;
  }

  // Measurement weight: film point (−s, −z_i) to the lens centre (aplanatic) or to the
  // lens point (lens, 0) (flat pupil).
  const glm::dvec3 v = p_.pupil == LensPupil::kFlat ? glm::dvec3(lens.x + s.x, lens.y + s.y, zi)
                                                    : glm::dvec3(s.x, s.y, zi);
  const double d2 = glm::dot(v, v);
  const double geometric = apertureArea_ * zi * zi / (d2 * d2);  // A · cos⁴θ / z_i²
  const double scale = pixelArea_ * p_.shutter.effectiveTime() * geometric;
  return cameraRay(m, origin, direction, sample.time, scale, lambda);
}

std::optional<CameraRay> PhysicalCamera::generateModelRay(const CameraSample& sample,
                                                          const SampledWavelengths& lambda,
                                                          const glm::dmat4& m) const {
  // The film point in OpenCV pixels (centres at integers), its chief ray (unit, OpenCV axes)
  // and the solid angle per px² there.
  const glm::dvec2 pixel = glm::dvec2(sample.pFilm) - 0.5;
  const std::optional<ModelRay> model = unprojectWithDensity(projection_, pixel);
  if (!model) return std::nullopt;
  const glm::dvec3 chief(model->direction.x, -model->direction.y, model->direction.z);

  glm::dvec3 origin(0.0), direction = chief;
  double pupil = turningPupil_ ? 1.0 : chief.z;  // projected pupil area ÷ A
  if (p_.aperture) {
    const glm::dvec2 lens(stop_->sample(sample.pLens));
    const double zo = p_.focusDistance;
    if (turningPupil_) {
      origin = turnedLensPoint(lens, chief);
      if (zo > 0.0) direction = chief * zo - origin;  // through the chief ray's point at z_o
    } else {
      origin = glm::dvec3(lens, 0.0);
      if (zo > 0.0) direction = chief * (zo / chief.z) - origin;  // plane of focus z = z_o
      if (p_.pupil == LensPupil::kFlat) {
        // As the pinhole's flat pupil: film point (−s, −z_i) to the lens point, not its centre.
        const glm::dvec3 c = chief * (imageDistance_ / chief.z);
        const glm::dvec3 v(lens.x + c.x, lens.y + c.y, c.z);
        const double ratio = glm::dot(c, c) / glm::dot(v, v);
        pupil *= ratio * ratio;
      }
    }
  }
  const double scale =
      p_.shutter.effectiveTime() * p_.fillFactor * model->density * apertureArea_ * pupil;
  return cameraRay(m, origin, direction, sample.time, scale, lambda);
}

CameraRay PhysicalCamera::cameraRay(const glm::dmat4& m, const glm::dvec3& origin,
                                    const glm::dvec3& direction, double time, double scale,
                                    const SampledWavelengths& lambda) const {
  CameraRay cr;
  cr.ray.o = glm::vec3(m * glm::dvec4(origin, 1.0));
  cr.ray.d = glm::vec3(glm::normalize(glm::dvec3(m * glm::dvec4(direction, 0.0))));
  cr.ray.time = time;
  cr.weight = SampledSpectrum(static_cast<float>(scale));
  if (!transmittanceIsOne_) cr.weight *= sampleSpectrum(p_.lensTransmittance, lambda);
  return cr;
}

}  // namespace camsim
