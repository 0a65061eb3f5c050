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
// | valid       | valid.A                      | —    | fraction of the pixel's samples whose film point lies inside the camera model's image (1 for the pinhole; 0 outside a fisheye's image circle, where the image is black) |
// | motion      | flow_fw.X/Y/Z, flow_bw.X/Y/Z | m    | 3-D scene flow: the hit point's world position at the next / previous frame's reference time minus at this frame's |
// | amodal      | amodal_<n>.A, visible_<n>.A  | —    | per labelled shape n: the fractions of the pixel's samples whose ray passes through it anywhere / first hits it (mask_film.h) |
// | occlusion   | occlusion_fw.A, occlusion_bw.A, outside_fw.A, outside_bw.A | — | fractions of the hitting samples whose point (the motion field's) is hidden in / outside the next / previous frame's image (occlusion_film.h) |
// | boundary    | boundary.A                   | —    | 1 on an occlusion boundary: several shapes, hits and misses, or a depth step among the pixel's samples (occlusion_film.h) |
//
// The motion field follows the exact rigid motion of the hit point: the sample's hit, at
// the sample's time t, is taken back to object space through the shape's keyframed
// motion at t and moved to each reference time t_j; it is projected with the camera's pose
// at t_j (PhysicalCamera::project: intrinsics and distortion, as the exported metadata).
// Samples for which a projection falls behind the lens are left out of the motion mean.
//
// A pixel's samples are consecutive in the render loop: they are summed in a small scratch
// record of the thread's (AovPixel, in double, in sample order) and the pixel's finished
// values are written into the film's image once (endPixel). The film's memory is touched
// once per pixel, there is no film-sized array of sums to clear or to convert at the end,
// and the result is the same whatever the thread count or tile split. A sample's vectors
// (position, normals, their camera axes) are summed as Double4 lanes, one lane per axis;
// the per-sample code (aov_film_add.cpp) is compiled twice, for the build's target and for
// AVX2 (used on CPUs that have it), the same operations in the same order: the same bits.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "integrator/camera/pose_projector.h"
#include "integrator/render/id_film.h"
#include "integrator/render/mask_film.h"
#include "integrator/render/occlusion_film.h"
#include "integrator/render/path_tracer.h"
#include "integrator/scene/scene.h"
#include "sensor/base/image.h"
#include "sensor/base/simd.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

// One camera sample for the AOVs (as Nori's query records: one argument, not a list). Its
// first hit is in the pixel's record that nextSurface handed out.
struct AovSample {
  double time = 0.0;                 // the sample's time, s
  const SampledWavelengths& lambda;  // as the camera ray started (before a dispersive hit)
  const glm::dmat4* worldFromCamera = nullptr;  // the camera's pose at `time` when wantsCamera()
  const Ray* cameraRay = nullptr;               // the camera ray (null: none), for the masks
};

// One camera sample's ground truth between addSample and its pixel's next summing: its first
// hit, as traceRadiance recorded it there, and what needed the sample's own camera pose and
// wavelengths, already worked out.
struct AovRecord {
  VisibleSurface visible;                 // visible.hit false: a miss (or no camera ray)
  double time;                            // s
  double depth;                           // camera-space z at the sample's time, m
  Double4 normalCam, geometricNormalCam;  // camera axes at the sample's time (camera turns)
  Float4 albedo, white;                   // Σ over its wavelengths of r_c ρ D65/p and r_c D65/p
};

// One pixel's sums and bookkeeping while its samples are traced; all of it is cleared when
// the pixel starts (startPixel). Vectors are Double4s with x, y, z in lanes 0–2 (lane 3
// unused).
struct AovPixelState {
  glm::ivec2 pixel{0};
  int samples = 0;  // camera samples added, hits or not
  int noRay = 0;    // of them, film points outside the camera model's image (no camera ray)
  int pending = 0;  // records (AovPixel) not summed yet
  // Σ over the samples that hit: 1 (the hit count), depth (m), distance (m), roughness.
  Double4 scalars{};
  Double4 position{}, normal{}, geometricNormal{};  // world axes
  Double4 normalCam{}, geometricNormalCam{};        // camera axes, when the camera turns
  Double4 albedo{};       // albedo: Σ r_c ρ D65/p over the samples' wavelengths (X, Y, Z, −)
  Double4 white{};        // and Σ r_c D65/p, the ratio's denominators
  int motionPending = 0;  // motion samples staged (AovPixel::motion)
  std::array<bool, 4> motionMoves{};  // the lane's shape moves (else its scene flow is 0)
  // The motion vectors summed per lane (the pixel's motion samples k in lane k mod 4), added
  // up in endPixel; count: the samples in the mean (in front of the lens at all three times).
  MotionVectorSums motionLanes{};
  std::array<double, 6> flow{};  // Σ scene flow, forward then backward (m), moving hits only
  OcclusionSums occlusion;       // aov occlusion (occlusion_film.h)
  BoundarySums boundary;         // aov boundary
  std::array<IdFilm::Slots, kIdKindCount> ids{};  // one per id aov
  // The previous sample's shape (−1: a miss; kNoShape: none yet) and its slot in each id
  // aov: consecutive samples on the same shape add to those slots without a search.
  static constexpr int kNoShape = -2;
  int idShape = kNoShape;
  std::array<IdFilm::Slot*, kIdKindCount> idSlot{};
};

// A render thread's scratch for the pixel it is on: the state above, and the samples waiting
// to be summed, which are written before they are read and so are not cleared per pixel.
struct AovPixel : AovPixelState {
  // Samples are recorded (addSample) and summed kBatch at a time (and at the pixel's end):
  // the larger part of the AOV code then runs once per batch instead of between every two
  // paths, where it pushed the path tracer's code out of the instruction cache.
  static constexpr int kBatch = 16;
  std::array<AovRecord, kBatch> records;
  // The motion field's samples waiting for their projections, in sample order: each one's
  // hit at the three frame times, four at a time (PoseProjector).
  PosePoints motion;
  MaskFilm::Counts masks;  // the amodal aov's counts (cleared by startPixel)
};

class AovFilm {
 public:
  // The scene's render.aovs, at its camera's resolution; the frame times from its camera's
  // shutter and frameInterval(). allowAvx2 false: the build target's copy of the per-sample
  // code even on a CPU with AVX2 (tests compare the two).
  explicit AovFilm(const Scene& scene, bool allowAvx2 = true);

  bool enabled() const { return !aovs_.empty(); }
  // Whether addSample needs the camera's pose at the sample's time (depth, normals).
  bool wantsCamera() const { return wantsCamera_; }

  // Starts summing pixel `pixel` in `px` (a render thread's scratch record).
  void startPixel(AovPixel& px, glm::ivec2 pixel) const;
  // Whether addSample runs the AVX2 copy.
  bool usesAvx2() const { return avx2_; }
  // Where the pixel's next camera sample records its first hit (traceRadiance's `visible`):
  // a record of the pixel's batch, cleared (hit false), wantMaterial set. The path tracer
  // writes it in place; addSample then completes the record.
  VisibleSurface& nextSurface(AovPixel& px) const {
    if (px.pending == AovPixel::kBatch) sumRecords(px);
    VisibleSurface& v = px.records[static_cast<std::size_t>(px.pending)].visible;
    v.hit = false;
    v.wantMaterial = wantsMaterial_;
    return v;
  }
  // The sample whose surface nextSurface handed out (call them in pairs).
  void addSample(AovPixel& px, const AovSample& sample) const {
    if (masks_) {
      const VisibleSurface& v = px.records[static_cast<std::size_t>(px.pending)].visible;
      masks_->add(px.masks, sample.cameraRay, v.hit ? v.shape : -1);
    }
    if (avx2_)
      addSampleAvx2(px, sample);
    else
      addSamplePortable(px, sample);
  }
  // A sample whose film point has no camera ray (outside the model's image): a miss that
  // also counts against the pixel's valid fraction.
  void addNoRaySample(AovPixel& px, const AovSample& sample) const {
    nextSurface(px);  // left empty: no hit
    addSample(px, sample);
    ++px.noRay;
  }
  // Writes the pixel's finished values (means, coverages, id ranks) into the image. Each
  // pixel is ended by one thread only, so no locking is needed.
  void endPixel(AovPixel& px);
  // coverage.A, each averaged aov's channels in the scene's order (table above), then each
  // id aov's (id_film.h), in the scene's order. Pixels never ended hold 0.
  Image takeImage() { return std::move(image_); }

 private:
  // addSample records a sample; sumRecords adds the pending records to the pixel's sums.
  // Their bodies (aov_film_add.cpp) are inlined into a copy for the build's target and one
  // for AVX2 (the portable build: the same code twice; avx2_ is false there).
  void addSampleBody(AovPixel& px, const AovSample& sample) const;
  void addSamplePortable(AovPixel& px, const AovSample& sample) const;
  void addSampleAvx2(AovPixel& px, const AovSample& sample) const;
  void sumRecordsBody(AovPixel& px) const;
  void sumRecordsPortable(AovPixel& px) const;
  void sumRecordsAvx2(AovPixel& px) const;
  void sumRecords(AovPixel& px) const {
    if (avx2_)
      sumRecordsAvx2(px);
    else
      sumRecordsPortable(px);
  }
  void flushMotion(AovPixel& px) const;  // projects and sums the pending motion samples
  void writePixel(const AovPixel& px, float* o) const;  // its channels (o: zeros)
  void writeMotion(const AovPixel& px, float* o) const;

  const Scene& scene_;
  std::vector<Aov> aovs_;
  Image image_;                // the finished values (endPixel)
  std::size_t idChannel_ = 0;  // the first id aov's first channel (after the averaged ones)
  // Each averaged aov's first channel in the image (0: not asked for). The channels are in
  // the scene's order; addSample fills its sums in a fixed order, one test per aov.
  std::size_t depthChannel_ = 0, distanceChannel_ = 0, positionChannel_ = 0;
  std::size_t normalChannel_ = 0;     // of N.X
  std::size_t albedoChannel_ = 0;     // of albedo.R
  std::size_t roughnessChannel_ = 0;  // of roughness.Y
  std::size_t motionChannel_ = 0;     // of motion_fw.X
  std::size_t validChannel_ = 0;      // of valid.A
  std::size_t occlusionChannel_ = 0;  // of occlusion_fw.A
  std::size_t boundaryChannel_ = 0;   // of boundary.A
  bool stagesMotion_ = false;         // motion or occlusion: each hit is moved to the frame times
  // x̄·D65, ȳ·D65, z̄·D65 interleaved on Spectrum's 1 nm grid (lane 3: 0): one 16-byte pair
  // per wavelength gives all three (a sample touches 4–8 cache lines of it, not 12–24).
  std::vector<Float4> whiteXyz_;
  glm::dvec3 rec709WhiteXyz_{0.0};  // linear Rec.709's white (1, 1, 1) in XYZ
  glm::dmat3 rec709FromXyz_{1.0};
  std::optional<PoseProjector> projector_;          // the camera at the three frame times
  std::vector<std::array<glm::dmat4, 3>> shapeAt_;  // per shape: its motion at each (moving)
  std::vector<char> shapeMoves_;                    // per shape: it has keyframed motion
  std::unique_ptr<OcclusionFilm> occlusion_;        // aov occlusion: the visibility tests
  bool wantsMaterial_ = false;     // traceRadiance evaluates the hit's material (albedo, roughness)
  bool wantsCamera_ = false;       // depth or normals: the camera's pose at the sample's time
  std::vector<IdFilm> idFilms_;    // in the scene's order of the id aovs
  std::optional<MaskFilm> masks_;  // the amodal aov
  std::size_t maskChannel_ = 0;    // its first channel (after the id aovs')
  std::vector<std::uint32_t> idEntries_;  // per shape, per IdFilm: the shape's table entry
  bool cameraTurns_ = false;              // the camera moves during the exposure
  glm::dmat4 worldFromCamera_{1.0};       // its pose when it does not
  bool avx2_ = false;                     // simd::cpuHasAvx2(): addSampleAvx2
};

}  // namespace camsim
