// AovFilm: ground-truth outputs (AOVs) from the first hit of the very camera samples that
// make the image (the same film point, lens point, time and wavelengths), averaged with the
// image's pixel filter — a box over the photosite — so they describe the same footprint.
// Each value is the mean over the pixel's samples whose camera ray hit a surface; a pixel
// that no sample hit holds 0. Ids are not averaged: they are coverages (id_film.h). Written
// as layers of NAME.exr (docs/output.md):
//
// | aov         | channels                     | unit | meaning |
// |-------------|------------------------------|------|---------|
// | (any)       | coverage.A                   | —    | fraction of the pixel's samples that hit a surface |
// | depth       | depth.Z                      | m    | camera-space z of the hit: distance along the optical axis from the lens plane, at the sample's time |
// | distance    | distance.Z                   | m    | distance from the ray's origin on the lens (the pinhole) to the hit |
// | position    | P.X, P.Y, P.Z                | m    | world position (the scene file's coordinates, in double before the float sum) |
// | normal      | N.*, Ng.*, N_cam.*, Ng_cam.* | —    | shading and geometric normal, world axes and camera axes (OpenCV: x right, y down, z forward); each on the shape's front side; the mean of unit vectors (shorter at edges), not renormalised |
// | albedo      | albedo.R, .G, .B             | —    | the material's reflectance (material.h SurfaceAov) as linear Rec.709 under D65: per XYZ channel the ratio of the pixel's sums Σ r_c ρ D65/p ÷ Σ r_c D65/p over its samples' wavelengths (CIE 1931 r_c), so a spectrally flat ρ reads exactly ρ |
// | roughness   | roughness.Y                  | —    | the material's α as the scene gives it (diffuse 1, mirror 0) |
// | instance_id, class_id, material_id | CryptoObject00.R … instance.id (id_film.h) | — | ID mattes: ranked (id, coverage) pairs, Cryptomatte, and the dominant id |
// | motion      | motion_fw.X/Y, motion_bw.X/Y | px   | where the hit point is imaged in the next / previous frame minus where it is in this one, all at the frames' reference times (shutter centres): OpenCV pixel axes (x right, y down) |
// | motion      | flow_fw.X/Y/Z, flow_bw.X/Y/Z | m    | 3-D scene flow: the hit point's world position at the next / previous frame's reference time minus at this frame's |
//
// The motion field follows the exact rigid motion of the hit point: the sample's hit, at
// the sample's time t, is taken back to object space through the shape's keyframed
// motion at t and moved to each reference time t_j; it is projected with the camera's pose
// at t_j (PhysicalCamera::project: intrinsics and distortion, as the exported metadata).
// Samples for which a projection falls behind the lens are left out of the motion mean.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "integrator/render/id_film.h"
#include "integrator/render/path_tracer.h"
#include "integrator/scene/scene.h"
#include "sensor/base/image.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

// One camera sample for the AOVs (as Nori's query records: one argument, not a list).
struct AovSample {
  glm::ivec2 pixel{0};
  const VisibleSurface& visible;     // its first hit (visible.hit false: a miss, or no ray)
  double time = 0.0;                 // the sample's time, s
  const SampledWavelengths& lambda;  // as the camera ray started (before a dispersive hit)
  const glm::dmat4* worldFromCamera = nullptr;  // the camera's pose at `time` when wantsCamera()
};

class AovFilm {
 public:
  // The scene's render.aovs, at its camera's resolution; the frame times from its camera's
  // shutter and frameInterval().
  explicit AovFilm(const Scene& scene);

  bool enabled() const { return !aovs_.empty(); }
  // Whether traceRadiance must evaluate the hit's material (albedo, roughness).
  bool wantsMaterial() const { return wantsMaterial_; }
  // Whether addSample needs the camera's pose at the sample's time (depth, normals).
  bool wantsCamera() const { return wantsCamera_; }
  void addSample(const AovSample& sample);
  // coverage.A, each averaged aov's channels in the scene's order (table above), then each
  // id aov's (id_film.h), in the scene's order.
  Image toImage(int samplesPerPixel) const;

 private:
  void addMotion(double* sums, const AovSample& s);

  const Scene& scene_;
  glm::ivec2 resolution_;
  std::vector<Aov> aovs_;
  std::vector<std::string> channels_;  // of the averaged aovs (all but the ids)
  std::size_t stride_ = 0;             // sums per pixel: hit count, then one per channel
  std::vector<double> sums_;
  std::size_t albedoChannel_ = 0;         // of albedo.R (0: no albedo)
  std::vector<double> albedoWhite_;       // per pixel: the D65 white's X, Y, Z sums
  std::array<Spectrum, 3> whiteXyz_;      // x̄·D65, ȳ·D65, z̄·D65
  std::size_t motionChannel_ = 0;         // of motion_fw.X (0: no motion)
  std::vector<double> motionCount_;       // per pixel: samples in the motion mean
  std::array<double, 3> frameTimes_{};    // previous, this, next frame's reference time, s
  std::array<glm::dmat4, 3> cameraAt_{};  // the camera's pose at each frame time
  std::vector<std::array<glm::dmat4, 3>> shapeAt_;  // per shape: its motion at each (moving)
  bool wantsMaterial_ = false;
  bool wantsCamera_ = false;  // depth or normals: the camera's pose at the sample's time
  std::vector<std::unique_ptr<IdFilm>> idFilms_;  // in the scene's order of the id aovs
  std::vector<IdKind> idKinds_;                   // of each IdFilm
  std::vector<std::uint32_t> idEntries_;          // per shape, per IdFilm: the shape's table entry
  bool cameraTurns_ = false;                      // the camera moves during the exposure
  glm::dmat4 worldFromCamera_{1.0};               // its pose when it does not
  std::size_t normalChannel_ = 0;                 // of N.X (0: no normals)
};

}  // namespace camsim
