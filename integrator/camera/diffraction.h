// Diffraction at the stop: the incoherent Fraunhofer PSF of the stop, per wavelength,
// applied as a jitter of the film point that is exact in distribution (issue 39, part 4).
//
// | parameter      | unit | meaning |
// |----------------|------|---------|
// | stop           | —    | the aperture's shape: circular, or N blades turned by `rotation` (Aperture) |
// | N_w            | —    | working f-number z_i / D (z_i the image distance, D = f/N the stop's diameter) |
// | λ_i            | nm   | the path's wavelengths (SampledWavelengths), i = 1 … n |
// | δ              | m    | offset on the film from the geometric image point, x right, y up (upright image) |
// | PSF_λ(δ)       | m⁻²  | p(R⁻¹δ / (λN_w)) / (λN_w)², p the stop's PSF in units of λN_w (StopPsf), R the stop's rotation |
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
// heuristic: choose j uniformly (probability 1/n, its own uniform number), draw δ from
// PSF_λj exactly (the table's distribution), and weight wavelength i by
//
//   w_i(δ) = PSF_λi(δ) / ((1/n) Σ_j PSF_λj(δ))    — δ's density is that mixture q(δ)
//
// so E[w_i · g(λ_i, δ)] = ∫ PSF_λi(δ) g(λ_i, δ) d²δ for every i and every g: unbiased per
// wavelength, also when only the hero survives a dispersive hit, and 0 ≤ w_i ≤ n. The
// camera multiplies its ray's weight by w (Diffraction::sample), and moves the film point by
// δ before it maps it to a ray.
#pragma once

#include <memory>

#include <glm/vec2.hpp>

#include "integrator/camera/aperture.h"
#include "integrator/camera/stop_psf.h"
#include "sensor/spectra/sampled_spectrum.h"

namespace camsim {

struct DiffractionSample {
  glm::dvec2 offset{0.0};        // δ, m, camera axes: x right, y up
  SampledSpectrum weight{1.0f};  // w_i, per wavelength
};

class Diffraction {
 public:
  // stop: its blades and rotation; workingFNumber: N_w = z_i / D (> 0).
  Diffraction(const ApertureShape& stop, double workingFNumber);

  double workingFNumber() const { return workingFNumber_; }
  const StopPsf& shape() const { return *psf_; }

  // δ and the weights from uniform numbers: u for the offset, uChoice for the wavelength.
  DiffractionSample sample(glm::vec2 u, float uChoice, const SampledWavelengths& lambda) const;
  // δ (m) drawn from PSF_λ alone (one wavelength, no weights: camsim psf), from u.
  glm::dvec2 sampleOffset(glm::vec2 u, double lambdaNm) const;
  // PSF_λ(δ) (m⁻²) for the offset δ (m) and wavelength λ (nm): the tabulated density.
  double psf(glm::dvec2 offset, double lambdaNm) const;

 private:
  // The table's offset t (units of λN_w, the stop unturned) turned by the stop's rotation
  // and scaled to metres.
  glm::dvec2 toFilm(glm::dvec2 t, double metresPerUnit) const {
    return metresPerUnit * glm::dvec2(cosRotation_ * t.x - sinRotation_ * t.y,
                                      sinRotation_ * t.x + cosRotation_ * t.y);
  }

  std::shared_ptr<const StopPsf> psf_;
  double workingFNumber_;
  double cosRotation_, sinRotation_;
};

}  // namespace camsim
