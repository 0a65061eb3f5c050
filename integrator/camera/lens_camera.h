// LensCamera: camera rays through a traced lens (LensSystem) — the part of PhysicalCamera
// that replaces the thin lens when the scene gives `camera.lens` (docs/camera.md, "A traced
// lens in the camera").
//
// Per camera sample: the film point s (m, upright image coordinates: x right, y up, origin
// at the sensor's centre) is, in lens space (lens_system.h: +z towards the object, z = 0 at
// the rear vertex), the point (−s.x, −s.y, −z_s) — the lens inverts the image, camera.h
// stores it upright. A rear-plane point p (z = 0) comes from ExitPupilBounds::sample with
// density 1/area; the ray film → p is traced out of the front at the hero wavelength. The
// measurement equation's geometric factor for that sample is
//
//   G = area · cosθ_film · cosθ_rear / d² = area · v_z² / |v|⁴      [sr·m² / m² = sr·… ]
//
// with v = p − film (both planes are perpendicular to the axis, so the two cosines are
// equal), d = |v|; the pixel weight is W = A_pixel · T_eff · G · T_lens(λ) (pbrt-v4's
// realistic camera). A lost ray has no ray (the film gets nothing for that sample): the
// estimate stays unbiased, and relative illumination (natural and mechanical vignetting)
// and the working f-number's exposure come out of the trace.
//
// Camera space (camera.h: x right, y up, z forward) has its origin at the entrance pupil's
// centre at λ_d: camera = lens − (0, 0, z_EP). The focus distance is measured from there.
//
// | parameter       | unit | default         | meaning |
// |-----------------|------|-----------------|---------|
// | fNumber         | —    | the file's stop | EFL / EPD at λ_d, ≥ LensSystem::minFNumber() |
// | focusDistance   | m    | 0 = infinity    | object distance from the entrance pupil; sensor placed by kBestRms at λ_d |
// | blades, rotation| —, rad | 0, 0          | the stop's shape (Aperture) |
// | sensorSize      | m    | —               | the film; ExitPupilBounds cover its half diagonal |
#pragma once

#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/camera/lens_pupil.h"
#include "integrator/camera/lens_system.h"

namespace camsim {

// What the scene gives for `camera.lens` (checked by the loader).
struct LensSpec {
  LensPrescription prescription;
  double fNumber = 0.0;        // 0: the file's stop
  double focusDistance = 0.0;  // m from the entrance pupil; 0 = infinity
  int blades = 0;              // the stop's shape (0: circular)
  double rotation = 0.0;       // rad
};

// A camera-space ray (origin on the front surface, unit direction) and its geometric factor.
struct LensCameraRay {
  glm::dvec3 origin{0.0};     // m, camera space
  glm::dvec3 direction{0.0};  // unit, camera space
  double geometric = 0.0;     // G above (m²·sr / m² … the factor multiplying A_pixel·T_eff)
};

class LensCamera {
 public:
  LensCamera(const LensSpec& spec, glm::dvec2 sensorSize);

  // The ray for the upright film point s (m) and pupil sample u ∈ [0,1)², traced at
  // lambdaNm; none if the point has no pupil (outside the image circle) or the ray is lost.
  std::optional<LensCameraRay> generate(glm::dvec2 s, glm::dvec2 u, double lambdaNm) const;

  const LensSystem& lens() const { return lens_; }
  const ExitPupilBounds& pupil() const { return bounds_; }
  double sensorDistance() const { return sensorDistance_; }  // m, rear vertex → sensor
  double entrancePupilZ() const { return entrancePupilZ_; }  // m, lens space at λ_d
  double fNumber() const { return fNumber_; }
  double focusDistance() const { return focusDistance_; }  // m from the entrance pupil, 0 = ∞
  // Whether rays at different wavelengths leave differently (any glass disperses): the
  // render loop then terminates the secondary wavelengths before generating the ray.
  bool disperses() const { return disperses_; }
  // Paraxial data at λ_d for the scene's object distance and sensor.
  const ParaxialData& paraxial() const { return paraxial_; }

 private:
  LensSystem lens_;
  double fNumber_;
  double focusDistance_;
  double entrancePupilZ_;
  double sensorDistance_;
  ExitPupilBounds bounds_;
  bool disperses_;
  LensSystem::Indices indicesD_;  // at λ_d: the lens's indices when it does not disperse
  ParaxialData paraxial_;
};

// The object distance from the front vertex (m, +∞ at infinity) of an object at
// focusDistance (m from the entrance pupil, 0 = infinity): what LensSystem's focus takes.
double objectDistanceFromVertex(const LensSystem& lens, double focusDistance);

// Why the lens with spec's stop forms no real image of its focus plane (its real rays leave
// the rear surface diverging: LensCamera would have no sensor distance), or "". The scene
// loader and an f-number override ask it (the best focus depends on the stop).
std::string realImageProblem(const LensSpec& spec);

}  // namespace camsim
