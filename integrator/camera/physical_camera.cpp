#include "integrator/camera/physical_camera.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "sensor/base/check.h"

namespace camsim {

PhysicalCamera::PhysicalCamera(PhysicalCameraParams params) : p_(std::move(params)) {
  const double f = p_.focalLength;
  CAMSIM_CHECK(f > 0.0 && p_.fNumber > 0.0 && p_.fillFactor > 0.0 && p_.fillFactor <= 1.0);
  CAMSIM_CHECK(p_.focusDistance == 0.0 || p_.focusDistance > f);
  imageDistance_ = p_.focusDistance > 0.0 ? f * p_.focusDistance / (p_.focusDistance - f) : f;
  const glm::dvec2 pitch = p_.sensorSize / glm::dvec2(p_.resolution);
  pixelArea_ = pitch.x * pitch.y * p_.fillFactor;
  intrinsics_ = {imageDistance_ / pitch.x, imageDistance_ / pitch.y, 0.5 * p_.resolution.x - 0.5,
                 0.5 * p_.resolution.y - 0.5};
  const double diameter = p_.apertureDiameter();
  if (p_.aperture) stop_.emplace(diameter, p_.aperture->blades, p_.aperture->rotation);
  apertureArea_ = stop_ ? stop_->area() : M_PI * 0.25 * diameter * diameter;
  distorted_ = !p_.distortion.isIdentity();
  transmittanceIsOne_ =
      p_.lensTransmittance.minValue() == 1.0 && p_.lensTransmittance.maxValue() == 1.0;
  fastPinhole_ =
      !p_.aperture && p_.distortion.isIdentity() && p_.motion.empty() && transmittanceIsOne_;
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
  // Sensor point, upright image coordinates (m): x right, y up, origin at the centre.
  const glm::dvec2 ndc = glm::dvec2(sample.pFilm) / glm::dvec2(p_.resolution);
  const glm::dvec2 s((ndc.x - 0.5) * p_.sensorSize.x, (0.5 - ndc.y) * p_.sensorSize.y);
  const double zi = imageDistance_;

  // Chief-ray direction through the lens centre, distorted as OpenCV models it.
  glm::dvec3 chief(s.x / zi, s.y / zi, 1.0);
  if (!p_.distortion.isIdentity()) {
    glm::dvec2 undistorted;
    if (!p_.distortion.undistort({chief.x, -chief.y}, undistorted)) return std::nullopt;
    chief = {undistorted.x, -undistorted.y, 1.0};
  }

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

  CameraRay cr;
  cr.ray.o = glm::vec3(m * glm::dvec4(origin, 1.0));
  cr.ray.d = glm::vec3(glm::normalize(glm::dvec3(m * glm::dvec4(direction, 0.0))));
  cr.ray.time = sample.time;
  cr.weight = SampledSpectrum(static_cast<float>(scale));
  if (!transmittanceIsOne_) cr.weight *= sampleSpectrum(p_.lensTransmittance, lambda);
  return cr;
}

}  // namespace camsim
