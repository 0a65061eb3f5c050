// PSF images (issue 39): the point-spread function on the film of one object point, at a
// chosen field height and wavelength, for a scene's camera — the thin lens (camera.aperture)
// or the traced lens (camera.lens) — by forward-tracing rays from the point over the pupil
// and histogramming where they land. `camsim psf` (cli/psf_command.h) writes it; docs/mtf.md,
// "PSF images".
//
// | parameter      | unit | range        | meaning |
// |----------------|------|--------------|---------|
// | field F        | —    | [0, 1.5]     | relative field height along +x: h = F · D/2, D the sensor's diagonal (camsim mtf's and ISO 12233's convention: 1 a corner's height) |
// | wavelength λ   | nm   | [360, 830]   | the one wavelength traced (and diffracted) |
// | size           | px   | [4, 512]     | the grid's side in film pixels (photosites) |
// | oversample K   | —    | [1, 16]      | cells per photosite per axis (size·K ≤ 2048) |
// | rays           | —    | [1e3, 1e8]   | rays traced from the object point |
// | seed           | —    | any          | the random stream (PCG32, rng.h) |
// | objectDistance | m    | ≥ 0          | 0: the camera's focus distance (itself 0 = infinity); else from the lens (thin) or the entrance pupil (traced) |
//
// Geometry (film coordinates upright, as camera.h: x right, y up, origin at the sensor's
// centre): the reference point is s_ref = (h, 0). The object point is the one whose chief
// ray lands there: the thin lens's chief ray goes straight through the lens centre, so the
// point is at slope h / z_i (z_i the camera's image distance); the traced lens's is the real
// chief ray from s_ref through the stop's centre at λ_d (aimed as LensSystem::chiefRayAngle
// aims it), the object point on it at distance d from the entrance pupil (the plane
// z = z_EP + d, lens space). At infinity (d = ∞) the rays are parallel to it.
//   thin lens: a ray from the object through the stop point L (Aperture::sample: uniform
//     over the stop's shape, blades included) goes to the conjugate O' = −t·z_i' (t the
//     object's slope, z_i' = f·d/(d − f), f at infinity) and meets the film at z_i:
//     P = L + (O' − L)·z_i/z_i' (inverted; upright −P). A pinhole: L = 0.
//   traced lens: rays from the object aimed uniformly over a disc of 1.5× the front
//     surface's clear radius on its vertex plane (weight cos⁴θ of the ray to the axis: the
//     solid angle of the disc element times a Lambertian patch facing the lens; parallel
//     rays at infinity, weight 1), traced in at λ (LensSystem::traceFromObject), met with
//     the sensor plane z = −s.
//   diffraction (camera.aperture.diffraction, default on; not for a pinhole): each ray that
//     lands is moved by δ drawn from the stop's Fraunhofer PSF at λ: the PhysicalCamera's
//     own Diffraction (its PsfGrid table, its N_w = z_i / D as the renderer builds it),
//     in the film's axes (the stop turned) and scaled by λN_w, as Diffraction::sample does.
// Vignetting: lostFraction = 1 − W(lens)/W(stop only), the weight of the rays that pass the
// real lens over that of the rays that pass the same lens with every clear aperture but the
// stop's widened (traced lens only; the thin lens has no rims: 0) — the share of the light
// through the stop's opening that a rim blocks (mechanical vignetting).
//
// The grid: n = size·K cells per side of pitch/K (the photosite pitch per axis), s_ref at
// the centre of cell (n/2, n/2) (so a point image fills one cell), row 0 at the top (+y).
// The image holds the weight per cell over the weight landed in the grid (sum 1). The
// statistics use every ray that landed on the film, inside the grid or not: centroid
// (from s_ref), RMS radius about the centroid, and the radii about the centroid enclosing
// 50 % and 80 % of the weight. (With diffraction the RMS radius holds the Airy wings out
// to the table's 256 λN_w, ≈ 7 λN_w for the circle alone: the EE radii are the robust ones.)
#pragma once

#include <cstdint>
#include <vector>

#include "integrator/camera/physical_camera.h"

namespace camsim {

struct PsfSettings {
  double field = 0.0;           // F, relative to the sensor's half diagonal
  double wavelengthNm = 550.0;  // nm
  int size = 32;                // px
  int oversample = 4;           // cells per px per axis
  std::int64_t rays = 1000000;  // traced
  std::uint64_t seed = 0;       // stream
  double objectDistance = 0.0;  // m; 0: the camera's focus distance
};

// The ranges of the table above, named once (InputError keys "field", "wavelength",
// "size", "oversample", "rays", "object_distance"; the CLI's options carry the same names).
namespace psf_ranges {
inline constexpr double kFieldMax = 1.5;
inline constexpr double kLambdaMinNm = 360.0, kLambdaMaxNm = 830.0;
inline constexpr int kSizeMin = 4, kSizeMax = 512;
inline constexpr int kOversampleMin = 1, kOversampleMax = 16;
inline constexpr int kCellsMax = 2048;
inline constexpr std::int64_t kRaysMin = 1000, kRaysMax = 100000000;
}  // namespace psf_ranges

// Throws InputError (key the setting's name, the value and its range) for a bad value.
void checkPsfSettings(const PsfSettings& settings);

struct PsfImage {
  PsfSettings settings;
  double imageHeight = 0.0;      // m, h: s_ref's x
  double objectDistance = 0.0;   // m, the object point's distance used (∞ at infinity)
  double workingFNumber = 0.0;   // N_w of the diffraction used (0: none)
  int cells = 0;                 // n per side
  double cellWidth = 0.0;        // m
  double cellHeight = 0.0;       // m
  std::vector<double> energy;    // n·n, row-major, row 0 at the top; sums to 1 (or all 0)
  double centroidX = 0.0;        // m, from s_ref
  double centroidY = 0.0;        // m
  double rmsRadius = 0.0;        // m, about the centroid
  double encircled50 = 0.0;      // m, radius about the centroid
  double encircled80 = 0.0;      // m
  double lostFraction = 0.0;     // of the weight through the stop, blocked by a rim
  double outsideFraction = 0.0;  // of the weight landed, outside the grid
  std::int64_t landed = 0;       // rays that reached the film
};

// The PSF of `camera` (a PhysicalCamera as the renderer builds it from the scene) at the
// settings; checkPsfSettings first. InputError ("field") when no ray reaches the film or the
// object point has no chief ray or real image (object distance ≤ f).
PsfImage computePsf(const PhysicalCamera& camera, const PsfSettings& settings);

}  // namespace camsim
