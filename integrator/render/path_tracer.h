// The spectral path tracer: estimates the radiance L(x, ω, λ) arriving along a camera ray
// at the path's sampled wavelengths, solving the rendering equation
//
//   L(x, ωo) = Le(x, ωo) + ∫ f(x, ωo, ωi) L(x', −ωi) |cos θi| dωi
//
// with next-event estimation (one light sample per bounce, lights chosen ∝ power) and
// BSDF sampling, combined by multiple importance sampling (power heuristic, β = 2), and
// Russian roulette after settings.rrDepth bounces (survival √ of the max throughput,
// Cycles' rule, without the 1/η² radiance scaling of refractions: pbrt-v4's etaScale).
#pragma once

#include <cstddef>
#include <cstdint>

#include "integrator/geometry/ray.h"
#include "integrator/render/ray_stats.h"
#include "integrator/sampling/sampler.h"
#include "integrator/scene/scene.h"
#include "sensor/spectra/sampled_spectrum.h"
#include "sensor/spectra/spectral_bins.h"

namespace camsim {

class SobolSampler;
class PathGuide;
struct GuideRecorder;

// The camera ray's first hit, for the ground-truth outputs (aov_film.h), as pbrt-v4's
// VisibleSurface: filled by traceRadiance when asked for, at no cost otherwise.
struct VisibleSurface {
  bool wantMaterial = false;  // in: also evaluate the material's albedo and roughness
  bool hit = false;
  glm::vec3 p{0.0f};       // render space, m
  glm::vec3 n{0.0f};       // geometric normal, unit, on the shape's front side
  glm::vec3 ns{0.0f};      // shading normal, unit
  float distance = 0.0f;   // from the ray's origin, m
  SampledSpectrum albedo;  // the material's SurfaceAov at the path's wavelengths (wantMaterial)
  float roughness = 0.0f;
  int shape = -1;  // the shape hit (Scene::shape)
};
// AovFilm loads p, n and ns 16 bytes at a time: each is followed by 4 more bytes of the struct.
static_assert(offsetof(VisibleSurface, p) + 16 <= sizeof(VisibleSurface) &&
              offsetof(VisibleSurface, n) + 16 <= sizeof(VisibleSurface) &&
              offsetof(VisibleSurface, ns) + 16 <= sizeof(VisibleSurface));

// Radiance (W·m⁻²·sr⁻¹·nm⁻¹) along `ray` at the wavelengths `lambda`. A dispersive
// material on the path terminates the secondary wavelengths (lambda is updated: the film
// must use it). Every bounce and shadow ray cast is counted (ray_stats.h). With `visible`,
// the first hit is recorded there (visible->hit stays false on a miss).
// With `guide`, non-specular bounces sample the BSDF/guide mixture (path_guide.h); with
// `recorder` (training), the path's vertices and the radiance they received are recorded.
// Compiled per concrete sampler (what the render loop uses): its numbers are drawn through
// inlined, not virtual, calls.
// With `cv` (unguided paths only; the scene has a spectral reference) the path also writes
// its spectral control variate's bins there (spectral_control_variate.h).
SampledSpectrum traceRadiance(const Scene& scene, Ray ray, SampledWavelengths& lambda,
                              SobolSampler& sampler, VisibleSurface* visible = nullptr,
                              const PathGuide* guide = nullptr, GuideRecorder* recorder = nullptr,
                              SpectralBins* cv = nullptr);
SampledSpectrum traceRadiance(const Scene& scene, Ray ray, SampledWavelengths& lambda,
                              IndependentSampler& sampler, VisibleSurface* visible = nullptr,
                              const PathGuide* guide = nullptr, GuideRecorder* recorder = nullptr,
                              SpectralBins* cv = nullptr);

}  // namespace camsim
