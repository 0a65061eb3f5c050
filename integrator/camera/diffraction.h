// Diffraction at the stop: the incoherent Fraunhofer PSF of the stop, per wavelength,
// applied as a jitter of the film point that is exact in distribution (issue 39, part 4).
//
// | parameter      | unit | meaning |
// |----------------|------|---------|
// | stop           | —    | the aperture's shape: circular, or N blades turned by `rotation` (Aperture) |
// | N_w            | —    | working f-number z_i / D (z_i the image distance, D = f/N the stop's diameter) |
// | λ_i            | nm   | the path's wavelengths (SampledWavelengths), i = 1 … n |
// | δ              | m    | offset on the film from the geometric image point, x right, y up (upright image) |
// | PSF_λ(δ)       | m⁻²  | p(δ / (λN_w)) / (λN_w)², p the turned stop's PSF in units of λN_w (PsfGrid) |
// | B, c           | m    | the photosite (the pixel's photosensitive square, √fill of its sides) and its centre |
//
// Model: scalar Fraunhofer diffraction at the exit pupil and an isoplanatic PSF (the same
// PSF over the whole field, the on-axis one: the pupil's foreshortening off axis and the
// aberrations are left out). Then the irradiance on the film is the geometric image
// convolved with the PSF, E_λ(x) = ∫ E_geo,λ(x − δ) PSF_λ(δ) d²δ, and a pixel's measurement
// ∫_pixel E_λ(x) dx is estimated without bias by taking the film point x uniform over the
// photosite as before, δ from a density q, and evaluating the geometric camera at x − δ
// (its ray, its weight) with the extra weight PSF_λ(δ)/q(δ). (The PSF of a real pupil is
// centrosymmetric, |P̂(−k)| = |P̂(k)|, so x + δ is the same: δ is added.)
//
// The path carries n wavelengths, each with its own PSF. One-sample MIS with the balance
// heuristic over the film point y = x + δ that the camera is evaluated at: choose j uniformly
// (probability 1/n, its own uniform number), draw δ from PSF_λj exactly (the grid's
// distribution, PsfGrid), so y's density given j is
//
//   q_j(y) = M_λj(B_y) / |B|,   B_y = the photosite moved to centre y − c (c its centre),
//
// M_λ the PSF's probability inside a box (PsfGrid::boxMass, exact for the grid), and weight
// wavelength i by
//
//   w_i = M_λi(B_y) / ((1/n) Σ_j M_λj(B_y))     (y's density is the mixture (1/n) Σ_j q_j)
//
// so E[w_i · g(λ_i, y)] = ∫ g(λ_i, y) q_i(y) dy = (1/|B|) ∫_B ∫ PSF_λi(δ) g(λ_i, x + δ) dδ dx
// for every i and every g: unbiased per wavelength, also when only the hero survives a
// dispersive hit, and 0 ≤ w_i ≤ n. The box's probability is the PSF integrated over the
// photosite — a Rao–Blackwellisation over the film point x: w_i varies far less between
// wavelengths than the point densities' ratio PSF_λi(δ) / mean_j PSF_λj(δ) (the estimator
// a point photosite falls back to), so the wavelengths' colour noise drops (docs/camera.md,
// "Diffraction at the stop"). The camera multiplies its ray's weight by w
// (Diffraction::sample) and moves the film point by δ before it maps it to a ray.
#pragma once

#include <memory>

#include <glm/vec2.hpp>

#include "integrator/camera/aperture.h"
#include "integrator/camera/psf_grid.h"
#include "sensor/spectra/sampled_spectrum.h"

namespace camsim {

// The photosite the film point x was drawn in, uniformly: x's offset from its centre and the
// half-sides (m, camera axes: x right, y up). Half-sides 0: a point photosite.
struct Photosite {
  glm::dvec2 offset{0.0};
  glm::dvec2 halfSide{0.0};
};

struct DiffractionSample {
  glm::dvec2 offset{0.0};        // δ, m, camera axes: x right, y up
  SampledSpectrum weight{1.0f};  // w_i, per wavelength
};

class Diffraction {
 public:
  // stop: its blades and rotation; workingFNumber: N_w = z_i / D (> 0).
  Diffraction(const ApertureShape& stop, double workingFNumber);

  double workingFNumber() const { return workingFNumber_; }
  const PsfGrid& grid() const { return *grid_; }

  // δ and the weights from uniform numbers: u for the offset, uChoice for the wavelength;
  // site: the photosite the film point was drawn in.
  DiffractionSample sample(glm::vec2 u, float uChoice, const SampledWavelengths& lambda,
                           const Photosite& site) const;
  // δ (m) drawn from PSF_λ alone (one wavelength, no weights: camsim psf), from u.
  glm::dvec2 sampleOffset(glm::vec2 u, double lambdaNm) const;
  // PSF_λ(δ) (m⁻²) for the offset δ (m) and wavelength λ (nm): the tabulated density.
  double psf(glm::dvec2 offset, double lambdaNm) const;

 private:
  // m per λN_w for wavelength λ (nm).
  double metresPerUnit(double lambdaNm) const { return lambdaNm * 1e-9 * workingFNumber_; }

  std::shared_ptr<const PsfGrid> grid_;
  double workingFNumber_;
};

}  // namespace camsim
