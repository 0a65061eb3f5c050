// PhysicalCamera's traced-lens path (lens_camera.h): the pixel measurement equation with the
// rear-plane sample of ExitPupilBounds,
//
//   W = A_pixel · T_eff · area · cosθ_film · cosθ_rear / d² · T_lens(λ)
//
// (LensCamera::generate gives the geometric factor); the ray leaves the front surface in
// camera space (origin at the entrance pupil) and is moved to the world by the pose.
#include <memory>

#include "integrator/camera/physical_camera.h"

namespace camsim {

void PhysicalCamera::initLens() {
  lensCamera_ = std::make_shared<const LensCamera>(*p_.lens, p_.sensorSize);
  p_.focalLength = lensCamera_->lens().paraxial().effectiveFocalLength;
  p_.fNumber = lensCamera_->fNumber();
  // The lens is sampled as an aperture is (a 2D lens sample per camera sample).
  if (!p_.aperture) p_.aperture = ApertureShape{p_.lens->blades, p_.lens->rotation};
}

std::optional<CameraRay> PhysicalCamera::generateTracedRay(const CameraSample& sample,
                                                           const SampledWavelengths& lambda,
                                                           const glm::dmat4& m) const {
  // Sensor point, upright image coordinates (m): x right, y up, origin at the centre.
  const glm::dvec2 ndc = glm::dvec2(sample.pFilm) / glm::dvec2(p_.resolution);
  const glm::dvec2 s((ndc.x - 0.5) * p_.sensorSize.x, (0.5 - ndc.y) * p_.sensorSize.y);
  const std::optional<LensCameraRay> r =
      lensCamera_->generate(s, glm::dvec2(sample.pLens), static_cast<double>(lambda[0]));
  if (!r) return std::nullopt;
  const double scale = pixelArea_ * p_.shutter.effectiveTime() * r->geometric;
  return cameraRay(m, r->origin, r->direction, sample.time, scale, lambda);
}

}  // namespace camsim
