// The spectral path tracer: estimates the radiance L(x, ω, λ) arriving along a camera ray
// at the path's sampled wavelengths, solving the rendering equation
//
//   L(x, ωo) = Le(x, ωo) + ∫ f(x, ωo, ωi) L(x', −ωi) |cos θi| dωi
//
// with next-event estimation (one light sample per bounce, lights chosen ∝ power) and
// BSDF sampling, combined by multiple importance sampling (power heuristic, β = 2), and
// Russian roulette after settings.rrDepth bounces (survival ∝ max throughput, without the
// 1/η² radiance scaling of refractions: pbrt-v4's etaScale).
#pragma once

#include <cstdint>

#include "integrator/geometry/ray.h"
#include "integrator/render/ray_stats.h"
#include "integrator/sampling/sampler.h"
#include "integrator/scene/scene.h"
#include "sensor/spectra/sampled_spectrum.h"

namespace camsim {

class SobolSampler;

// Radiance (W·m⁻²·sr⁻¹·nm⁻¹) along `ray` at the wavelengths `lambda`. A dispersive
// material on the path terminates the secondary wavelengths (lambda is updated: the film
// must use it). Every bounce and shadow ray cast is counted (ray_stats.h).
// Compiled per concrete sampler (what the render loop uses): its numbers are drawn through
// inlined, not virtual, calls.
SampledSpectrum traceRadiance(const Scene& scene, Ray ray, SampledWavelengths& lambda,
                              SobolSampler& sampler);
SampledSpectrum traceRadiance(const Scene& scene, Ray ray, SampledWavelengths& lambda,
                              IndependentSampler& sampler);

}  // namespace camsim
