// The spectral control variate: colour without the noise of four wavelengths per path.
//
// A path carries N wavelengths λᵢ (hero and rotations, sampled_spectrum.h), and the film
// estimates each channel as (1/N) Σᵢ r_c(λᵢ) q(λᵢ)/p(λᵢ). Where the spectra along the path
// vary (a red wall under D65) the N values disagree from draw to draw: colour noise that an
// RGB renderer does not have. The path also carries its throughput in 16 bins of equal
// probability (spectral_bins.h) and writes each contribution it can as
//
//   S(λ) = B[bin(λ)] · E(λ),   E the scene's reference emission (Scene::spectralReference),
//
// whose film response ∫ r_c S dλ = Σ_b B_b ∫_bin b r_c E dλ is known exactly. The film adds
//
//   v_c = (1/N) Σᵢ r_c(λᵢ) (q(λᵢ) − S(λᵢ)) / p(λᵢ)  +  Σ_b B_b ∫_bin b r_c E dλ   (Film)
//
// which has the same expectation as the plain estimate for any S that does not depend on
// the wavelengths drawn, and almost no spectral variance when S follows q: a path of white
// walls lit by the reference light has q = S exactly, its colour is then exact per sample.
//
// | quantity   | unit                       | meaning                                        |
// |------------|----------------------------|------------------------------------------------|
// | beta       | —                          | the throughput's bins: Π R_k[b] × the scalar    |
// |            |                            | factors (|cos|/(π p), roulette) of β            |
// | R_k[b]     | —                          | a Lambertian vertex's reflectance in bin b: a   |
// |            |                            | constant one's average over the bin, a textured |
// |            |                            | one's value at its centre (lambertianBins)      |
// | light[b]   | —                          | the light's ∫_bin L_e / ∫_bin E (area_light.h)  |
// | L          | —                          | Σ over contributions of beta·(R)·light·weight:  |
// |            |                            | the bins B of S = B·E (the render loop scales   |
// |            |                            | them by the camera's weight, as q)              |
//
// S must not depend on the wavelengths drawn, and neither may any decision of the path
// while the variate is on: it is on from the camera (which must treat every wavelength
// alike, PhysicalCamera::wavelengthIndependent) through Lambertian vertices only — the
// first other material turns it off for the rest of the path (its later contributions are
// the plain estimate), as does a bounce that leaves beta's bins all 0 — and Russian roulette
// then reads beta's bins, not the wavelengths' throughput. Only emitting shapes (area lights) contribute to L; other lights' light is
// the plain estimate. Guided paths do not use it.
#pragma once

#include "integrator/geometry/math.h"
#include "integrator/materials/material.h"
#include "sensor/spectra/spectral_bins.h"

namespace camsim {

// One path's state (path_tracer.cpp).
struct SpectralControlVariate {
  bool on = false;
  SpectralBins beta{1.0f};
  SpectralBins L{0.0f};
  const SpectralBins* reflectance = nullptr;  // R at the current vertex (while on)
  SpectralBins scratch;                       // a textured R's bins

  // At a scattering vertex: stays on only at a Lambertian reflector.
  void enter(const Material& material, const BsdfContext& ctx) {
    if (!on) return;
    reflectance = material.lambertianBins(ctx, scratch);
    on = reflectance != nullptr;
  }
  // Emission hit with MIS weight w; light: the light's bins (null: not written so).
  void addEmission(const SpectralBins* light, float w) {
    if (on && light) L.addScaled(beta * *light, w);
  }
  // A light sample at the current vertex: f = R/π, scale = |cos θ| · MIS weight / pdf.
  void addLightSample(const SpectralBins& light, float scale) {
    L.addScaled(beta * *reflectance * light, scale * kInvPi);
  }
  // A cosine-sampled bounce: β gains R·|cos θ|/(π p). Bins all 0 (R 0 at every bin's value)
  // carry no more terms: the variate stops, and the path goes on as the plain estimate
  // (its drawn wavelengths may still carry light; roulette then reads them).
  void scatter(float cosOverPdf) {
    beta *= *reflectance;
    beta *= cosOverPdf * kInvPi;
    on = !beta.isZero();
  }
};

}  // namespace camsim
