// PhysicalCamera: a thin-lens camera (a pinhole when it has no aperture) whose film
// records the energy arriving on each photosite — the pixel measurement equation
//
//   Q_c = ∫_shutter s(t) ∫_photosite ∫_aperture ∫_λ r_c(λ) T_lens(λ) L(x, ω, t, λ)
//                                         cosθ_film cosθ_lens / d²  dλ dA_lens dA_pixel dt
//
// For a sample (film point, lens point, time, wavelengths) drawn uniformly over the
// photosensitive area and the aperture and with density s(t)/T_eff in time, the weight is
//
//   W = A_pixel · T_eff · A_aperture · cos⁴θ / z_i² · T_lens(λ)   [m²·s·sr → radiance to energy]
//
// with z_i = f·z_o / (z_o − f) the image distance for focus distance z_o (z_i = f at
// infinity) and θ, by the lens's pupil model (docs/camera.md):
//   aplanatic (default): θ is the chief ray's angle (film point → lens centre), the same for
//     every lens point. The lens obeys Abbe's sine condition, sin θ' = h / z_i for a ray
//     through pupil height h, so the pupil seen from the film is a sphere and a uniform
//     stop fills equal projected solid angle per area: on axis E = π L T / (4 N_w²)
//     exactly (ISO 12232's camera equation, N_w = z_i / D), cos⁴θ off axis, and a
//     defocused point's blur disc is uniformly lit.
//   flat: θ is the angle of the film-point → lens-point segment, as for a flat pupil in
//     the lens plane: on axis E = π L T / (1 + 4 N_w²), 1.8 % darker at N_w = 3.7, 11 %
//     at 1.4, and a blur disc that darkens towards its rim as cos⁴θ.
// Both map lens points to rays the same way (through the film point's conjugate on the
// plane of focus); they differ only in the weight. Without an aperture (pinhole) the lens
// point is the centre: E = π L T / (4 N_w²) cos⁴θ, the limit of both.
//
// Any other camera model (a projection that distorts, a fisheye, omnidirectional or
// equirectangular model, or intrinsics given in pixels) maps the film point u through the
// model (projection.h: unproject) to the chief ray ω(u), and weighs a sample by the solid
// angle its film area maps to times the pupil's projected area:
//
//   W = T_eff · F · dΩ/dA(u) · A_aperture · c · T_lens(λ)     [dΩ/dA in sr per px², F the fill factor in px²]
//
// opencv (the pinhole with OpenCV's distortion): a fixed pupil in the lens plane, c = cos θ
//   of the chief ray (aplanatic; the flat pupil multiplies by (|v_chief|² / |v_lens|²)² as
//   above), rays through the film point's conjugate on the plane z = z_o. Without distortion
//   dΩ/dA = pitch² cos³θ / z_i² and W is the pinhole's weight above.
// every other model: the pupil turns with the field (a disc of area A at the centre,
//   perpendicular to the chief ray, as a fisheye's entrance pupil does to first order), c = 1,
//   so a uniform field gives each pixel E ∝ its solid angle; rays through the point at
//   distance z_o along the chief ray (a sphere of focus). Real fisheyes' pupils also move
//   forward off axis; that shift, a few mm, is neglected.
// A film point outside the model's image (past its field limit or image circle) has no ray.
//
// Diffraction at the stop (aperture.diffraction, on by default; a pinhole has none): the
// film point u is first moved by an offset δ drawn from the stop's PSF at one of the path's
// wavelengths, u' = u + (δ_x / pitch_x, −δ_y / pitch_y), and the ray's weight is multiplied
// by the MIS weights w_i — the PSF of each wavelength integrated over the photosite moved to
// u' (from the sample's pPhotosite and the photosite's √fill sides) over their mean: a
// convolution of the geometric image with the PSF per wavelength, with N_w = z_i / D
// (Diffraction, diffraction.h, states the model).
//
// | parameter        | unit | default   | meaning |
// |------------------|------|-----------|---------|
// | sensor size      | m    | 36×24 mm  | |
// | resolution       | px   | 640×480   | pitch = size / resolution |
// | fill factor      | —    | 1         | photosensitive fraction of the pixel area (centred, same aspect) |
// | focal length f   | m    | 50 mm     | |
// | f-number N       | —    | 8         | D = f/N |
// | focus distance   | m    | ∞         | z_o, measured from the lens |
// | aperture         | —    | none      | none: pinhole; else circular or N blades (see Aperture) |
// | diffraction      | —    | on        | with an aperture: the stop's Fraunhofer PSF (Diffraction) |
// | pupil            | —    | aplanatic | aplanatic (sine condition) or flat: the weight above |
// | lens transmittance | —  | 1         | T_lens(λ) |
// | projection       | —    | opencv, no distortion | the camera model (projection.h): OpenCV's full distortion, the fisheye, omnidirectional and equirectangular models |
// | intrinsics       | px   | from the lens | fx = z_i / pitch_x, fy = z_i / pitch_y, (cx, cy) the image centre; or the projection's own (a calibration's) |
// | shutter          | s    | 1/60 box  | see Shutter |
// | motion           | m, ° | static    | camera keyframes: translate adds to the position (world), rotate turns about the camera centre in camera axes |
#pragma once

#include <memory>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "integrator/camera/aperture.h"
#include "integrator/camera/camera.h"
#include "integrator/camera/diffraction.h"
#include "integrator/camera/lens_camera.h"
#include "integrator/camera/projection.h"
#include "integrator/camera/shutter.h"
#include "integrator/geometry/motion.h"
#include "sensor/base/enum_names.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

enum class LensPupil { kAplanatic, kFlat };
// The scene's `camera.aperture.pupil` names (sensor/base/enum_names.h).
template <>
struct EnumNames<LensPupil> {
  static constexpr EnumName<LensPupil> kTable[] = {{LensPupil::kAplanatic, "aplanatic"},
                                                   {LensPupil::kFlat, "flat"}};
};

struct PhysicalCameraParams {
  glm::dmat4 worldFromCamera{1.0};  // at rest; columns right, up, forward, position
  RigidMotion motion;               // camera-relative keyframes (may be empty)
  glm::dvec2 sensorSize{0.036, 0.024};
  glm::ivec2 resolution{640, 480};
  double fillFactor = 1.0;
  double focalLength = 0.050;
  double fNumber = 8.0;
  double focusDistance = 0.0;             // 0 = infinity
  std::optional<ApertureShape> aperture;  // none: pinhole
  LensPupil pupil = LensPupil::kAplanatic;
  Spectrum lensTransmittance = Spectrum::constant(1.0);
  // The camera model and its coefficients (integrator/camera/projection.h). With
  // intrinsicsFromLens, its fx, fy, cx, cy are replaced when the camera is made: fx = z_i /
  // pitch_x, fy = z_i / pitch_y (equirectangular: fx = W/2π, fy = H/π px per radian) and
  // (cx, cy) = (W/2 − ½, H/2 − ½); otherwise they are used as given (a calibration's pixels).
  Projection projection;
  bool intrinsicsFromLens = true;
  Shutter shutter = Shutter::box(0.0, 1.0 / 60.0);
  // A traced lens (lens_camera.h) instead of the thin lens: when set, the camera's rays and
  // weights come from it, and focalLength, fNumber become the lens's paraxial EFL and
  // f-number at λ_d (the thin-lens stand-in the intrinsics and project() use).
  std::optional<LensSpec> lens;

  // D = f/N (m): the entrance pupil's diameter — the one place it is derived.
  double apertureDiameter() const { return focalLength / fNumber; }
};

// A world-axes vector in the camera's OpenCV axes (x right, y down, z forward) — the axes of
// the exported metadata, the camera-space normals and project().
inline glm::dvec3 cameraCvFromWorld(const glm::dmat4& worldFromCamera, const glm::dvec3& v) {
  return {glm::dot(v, glm::dvec3(worldFromCamera[0])), -glm::dot(v, glm::dvec3(worldFromCamera[1])),
          glm::dot(v, glm::dvec3(worldFromCamera[2]))};
}

class PhysicalCamera final : public Camera {
 public:
  explicit PhysicalCamera(PhysicalCameraParams params);

  std::optional<CameraRay> generateRay(const CameraSample& sample,
                                       const SampledWavelengths& lambda) const override;
  // The same with the camera's pose at sample.time already computed (worldFromCameraAt):
  // the render loop shares it with the ground-truth outputs.
  std::optional<CameraRay> generateRay(const CameraSample& sample, const SampledWavelengths& lambda,
                                       const glm::dmat4& worldFromCamera) const;
  glm::ivec2 resolution() const override { return p_.resolution; }
  bool hasAperture() const override { return p_.aperture.has_value(); }
  bool moves(double t0, double t1) const override { return !p_.motion.isStaticDuring(t0, t1); }
  const Shutter& shutter() const override { return p_.shutter; }

  const PhysicalCameraParams& params() const { return p_; }
  // The traced lens, or null for the thin lens.
  const LensCamera* lensCamera() const { return lensCamera_.get(); }
  // Whether the camera ray depends on the wavelength (a traced lens that disperses): the
  // caller terminates the secondary wavelengths before generateRay (it traces λ[0] only).
  bool lensDisperses() const { return lensCamera_ && lensCamera_->disperses(); }
  // Whether every ray's path and weight are the same at every wavelength (no diffraction,
  // no dispersing lens, no spectral lens transmittance).
  bool wavelengthIndependent() const {
    return !diffraction_ && !lensDisperses() && transmittanceIsOne_;
  }
  double imageDistance() const { return imageDistance_; }  // z_i, m
  // N_w, the scale of diffraction's PSF: z_i / D for the thin lens; a traced lens's
  // paraxial working f-number 1/(2|u'|) at the scene's object distance.
  double workingFNumber() const;
  double pixelArea() const { return pixelArea_; }        // photosensitive area, m²
  double apertureArea() const { return apertureArea_; }  // m²
  // The stop's diffraction, or null (a pinhole, or aperture.diffraction off).
  const Diffraction* diffraction() const { return diffraction_ ? &*diffraction_ : nullptr; }
  glm::dmat4 worldFromCameraAt(double t) const;
  // OpenCV intrinsics (pixels): fx, fy, cx, cy (fixed when the camera is made).
  const glm::dvec4& intrinsics() const { return intrinsics_; }
  // The camera model with the intrinsics it renders with (fx … cy filled in).
  const Projection& projection() const { return projection_; }
  // Whether the camera is the ideal pinhole / thin lens: the opencv model without distortion
  // and with the lens's intrinsics (the fast paths: PoseProjector's vector kernel).
  bool idealPinhole() const { return idealPinhole_; }
  // Where the chief ray images the render-space point p at time t: OpenCV pixel
  // coordinates (x right, y down, pixel centres at integers) through the camera model; none
  // outside the model's domain (on or behind the lens plane for the pinhole).
  std::optional<glm::dvec2> project(const glm::dvec3& p, double t) const {
    return projectFrom(worldFromCameraAt(t), p);
  }
  // The same from a pose worldFromCameraAt(t) already computed (inline: the motion field
  // projects three times per camera sample).
  std::optional<glm::dvec2> projectFrom(const glm::dmat4& worldFromCamera,
                                        const glm::dvec3& p) const {
    const glm::dvec3 c = cameraCvFromWorld(worldFromCamera, p - glm::dvec3(worldFromCamera[3]));
    if (!idealPinhole_) return camsim::project(projection_, c);
    if (!(c.z > 0.0)) return std::nullopt;
    const glm::dvec2 xn(c.x / c.z, c.y / c.z);
    const glm::dvec4& k = intrinsics_;
    return glm::dvec2(k.x * xn.x + k.z, k.y * xn.y + k.w);
  }

 private:
  std::optional<CameraRay> generatePinholeRay(const CameraSample& sample) const;
  // The geometric camera's ray for the sample's film point (no diffraction).
  std::optional<CameraRay> generateLensRay(const CameraSample& sample,
                                           const SampledWavelengths& lambda,
                                           const glm::dmat4& worldFromCamera) const;
  // The film point moved by the PSF's offset, its ray weighted per wavelength.
  std::optional<CameraRay> generateDiffractedRay(const CameraSample& sample,
                                                 const SampledWavelengths& lambda,
                                                 const glm::dmat4& worldFromCamera) const;
  std::optional<CameraRay> generateModelRay(const CameraSample& sample,
                                            const SampledWavelengths& lambda,
                                            const glm::dmat4& worldFromCamera) const;
  // The ray from camera-space origin along direction (world through m) with weight scale
  // (× T_lens(λ)): the last step of both general paths.
  // Through the traced lens (physical_camera_lens.cpp): builds lensCamera_ and sets the
  // thin-lens stand-in's focal length, f-number and stop shape from it.
  void initLens();
  std::optional<CameraRay> generateTracedRay(const CameraSample& sample,
                                             const SampledWavelengths& lambda,
                                             const glm::dmat4& worldFromCamera) const;
  CameraRay cameraRay(const glm::dmat4& m, const glm::dvec3& origin, const glm::dvec3& direction,
                      double time, double scale, const SampledWavelengths& lambda) const;

  PhysicalCameraParams p_;
  std::optional<Aperture> stop_;            // from p_.aperture and p_.apertureDiameter()
  std::optional<Diffraction> diffraction_;  // with an aperture whose diffraction is on
  glm::dvec2 pixelsPerMetre_{0.0};          // film offset (m, y up) → pixels (y down)
  glm::dvec2 photositeHalfSide_{0.0};       // m: half the photosensitive square's sides (√fill)
  double imageDistance_;
  double pixelArea_;
  double apertureArea_;
  glm::dvec4 intrinsics_;
  Projection projection_;      // p_.projection with the intrinsics filled in
  bool idealPinhole_ = true;   // the opencv model, no distortion, the lens's intrinsics
  bool turningPupil_ = false;  // every model but opencv: the pupil faces the chief ray
  bool transmittanceIsOne_;
  // The static pinhole without distortion (the common case) generates its rays in float
  // from constants fixed here, instead of the double matrix and weight math per sample:
  // s = pFilm·filmScale + filmOffset (sensor point, m), d = normalize(s.x·right + s.y·up
  // + z_i·forward), W = weightScale / (s² + z_i²)² with weightScale = A_pixel·T_eff·A·z_i².
  bool fastPinhole_ = false;
  glm::vec3 origin_{0.0f}, right_{0.0f}, up_{0.0f}, forward_{0.0f};
  glm::vec2 filmScale_{0.0f}, filmOffset_{0.0f};
  float zi_ = 0.0f, weightScale_ = 0.0f;
  // The traced lens (p_.lens), built once; shared by copies of the camera.
  std::shared_ptr<const LensCamera> lensCamera_;
};

}  // namespace camsim
