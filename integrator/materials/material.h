// Material: the BSDF at a surface point, in the local shading frame (z = shading normal,
// pointing to the surface's front, i.e. outside for closed shapes), following Nori's plain
// interface. Directions are unit vectors pointing away from the surface: wo towards the
// viewer, wi towards the light. Transmission means wi and wo on opposite sides (wi.z·wo.z < 0).
//   f(wo, wi, λ, ctx)     BSDF value, sr⁻¹ (0 for delta lobes: they are only sampled)
//   sample(...)           draws wi ∝ (approximately) f·|cos θi|, returns f, pdf
//   pdf(wo, wi, λ, ctx)   density of sample() producing wi (sr⁻¹; 0 for delta lobes)
// Radiance transport: a transmitted path's f carries the 1/η² factor of radiance
// crossing an interface (η = ηt/ηi), so L/n² is invariant along a refracted ray.
//
// Dispersive materials (η depends on λ) scatter each wavelength differently: before
// using them the integrator calls lambda.terminateSecondary(), and the material then
// evaluates η at the hero wavelength lambda[0] only.
#pragma once

#include <array>
#include <memory>
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/textures/normal_map.h"
#include "integrator/textures/texture.h"
#include "integrator/textures/vertex_colors.h"
#include "sensor/spectra/sampled_spectrum.h"

namespace camsim {

// What a material may look up besides the directions: texture coordinates, and a memo of
// its spectral texture there. At one shading point the path tracer asks f and pdf (light
// sample), sample and, at the first hit, aov — each needs the same reflectance (or F0); an
// image texture lookup (four texels' sigmoid spectra) is the costliest part of a textured
// bounce, so it is done once per point. The memo is keyed by texture, uv and wavelengths:
// a context reused elsewhere (tests, other wavelengths) looks the texture up again. A
// context lives at one point and must not outlive the materials it was used with.
// On a mesh with vertex colours (glTF COLOR_0) the looked-up value is the texture's times
// the colours at the point (integrator/textures/vertex_colors.h): the spectral texture is
// the material's reflectance (base colour, a conductor's F0), which the colours multiply.
struct BsdfContext {
  BsdfContext() = default;
  explicit BsdfContext(glm::vec2 uvAtPoint) : uv(uvAtPoint) {}
  // colors: the mesh's vertex colours (null: none); triangle and Embree's barycentrics
  // (b1, b2) locate the point on the mesh.
  BsdfContext(glm::vec2 uvAtPoint, const VertexColors* colors, int tri, float bary1, float bary2)
      : uv(uvAtPoint), vertexColors(colors), triangle(tri), b1(bary1), b2(bary2) {}

  glm::vec2 uv{0.0f};
  const VertexColors* vertexColors = nullptr;
  int triangle = 0;
  float b1 = 0.0f, b2 = 0.0f;

  SampledSpectrum lookup(const SpectrumTexture& texture, const SampledWavelengths& lambda) const {
    bool same = memo_.texture == &texture && memo_.uv == uv;
    for (int i = 0; i < kWavelengthSamples; ++i)
      same = same && memo_.lambda[static_cast<std::size_t>(i)] == lambda[i];
    if (!same) {
      memo_.value = texture.evaluate(uv, lambda);
      if (vertexColors) [[unlikely]]
        memo_.value *= vertexColors->evaluate(triangle, b1, b2, lambda);
      memo_.texture = &texture;
      memo_.uv = uv;
      for (int i = 0; i < kWavelengthSamples; ++i)
        memo_.lambda[static_cast<std::size_t>(i)] = lambda[i];
      ++memo_.misses;
    }
    return memo_.value;
  }
  // The texture (times the vertex colours) in bins (spectral_bins.h), for the spectral
  // control variate: a constant texture's stored bins (its averages), else `out` filled with
  // its values at the bins' centres — 16/N more evaluations of the texture per bounce (each
  // serves the N bins of one SampledWavelengths::binCentres group), a constant texture with
  // vertex colours included. Not memoised: a bounce asks once.
  const SpectralBins* lookupBins(const SpectrumTexture& texture, SpectralBins& out) const {
    if (const SpectralBins* c = texture.constantBins(); c && !vertexColors) return c;
    for (int k = 0; k < kSpectralBins / kWavelengthSamples; ++k) {
      const SampledWavelengths& centres = SampledWavelengths::binCentres(k);
      SampledSpectrum v = texture.evaluate(uv, centres);
      if (vertexColors) v *= vertexColors->evaluate(triangle, b1, b2, centres);
      for (int i = 0; i < kWavelengthSamples; ++i) out[k * kWavelengthSamples + i] = v[i];
    }
    return &out;
  }
  // How many lookups evaluated the texture (tests check that a bounce does it once).
  int textureEvaluations() const { return memo_.misses; }

 private:
  struct Memo {
    const SpectrumTexture* texture = nullptr;
    glm::vec2 uv{0.0f};
    std::array<float, kWavelengthSamples> lambda{};
    SampledSpectrum value;
    int misses = 0;
  };
  mutable Memo memo_;
};

struct BsdfSample {
  SampledSpectrum f;  // BSDF value, sr⁻¹; for a delta lobe: the lobe's weight / |cos θi|
  glm::vec3 wi{0.0f};
  float pdf = 0.0f;       // sr⁻¹; for a delta lobe: the probability of choosing the lobe
  bool specular = false;  // delta lobe (mirror, smooth glass): no MIS with light sampling
  bool transmission = false;
  // Relative index of refraction η_t/η_i crossed by a transmission (1 for a reflection):
  // radiance along the path scales by 1/etap² there, which the path's Russian roulette
  // undoes (pbrt-v4's etaScale) so that paths inside glass are not killed for it.
  float etap = 1.0f;
};

// What a first hit reports as ground truth (integrator/render/aov_film.h): the reflectance
// the surface shows at λ — a diffuse or plastic surface's ρ, a mirror's ρ, a metal's
// normal-incidence Fresnel reflectance F(0), 1 for (lossless) glass — and its roughness α
// as the scene gives it (diffuse 1; a mirror 0).
struct SurfaceAov {
  SampledSpectrum albedo;
  float roughness = 0.0f;
};

class Material {
 public:
  virtual ~Material() = default;
  virtual SampledSpectrum f(const glm::vec3& wo, const glm::vec3& wi,
                            const SampledWavelengths& lambda, const BsdfContext& ctx) const = 0;
  virtual std::optional<BsdfSample> sample(const glm::vec3& wo, float uc, glm::vec2 u,
                                           const SampledWavelengths& lambda,
                                           const BsdfContext& ctx) const = 0;
  virtual float pdf(const glm::vec3& wo, const glm::vec3& wi, const SampledWavelengths& lambda,
                    const BsdfContext& ctx) const = 0;
  virtual SurfaceAov aov(const SampledWavelengths& lambda, const BsdfContext& ctx) const = 0;
  // For a Lambertian reflector — f(wo, wi, λ) = R(λ)/π where wo and wi are on the same
  // side, else 0, and sample() draws wi ∝ |cos θi| — R in bins (BsdfContext::lookupBins; the
  // spectral control variate, integrator/render/spectral_control_variate.h): stored bins or
  // `scratch` filled; null for any other BSDF.
  const SpectralBins* lambertianBins(const BsdfContext& ctx, SpectralBins& scratch) const {
    const SpectrumTexture* r = traits_.lambertianReflectance;
    return r ? ctx.lookupBins(*r, scratch) : nullptr;
  }
  // What the path loop asks at every bounce, fixed when the material is made (plain
  // members, not virtual calls).
  // False for a material that reflects nothing (lets the integrator stop a path).
  bool reflects() const { return traits_.reflects; }
  // False when every lobe is a delta (mirror, smooth glass): light sampling is skipped.
  bool hasNonSpecular() const { return traits_.nonSpecular; }
  // True when η depends on wavelength (see above).
  bool dispersive() const { return traits_.dispersive; }
  // The tangent-space normal map that bends the shading normal before the integrator
  // builds the shading frame (integrator/textures/normal_map.h), or null. Any material may
  // have one: it changes the frame, not the BSDF. Set by the factory.
  const NormalMap* normalMap() const { return normalMap_.get(); }
  void setNormalMap(std::unique_ptr<const NormalMap> map) { normalMap_ = std::move(map); }

 protected:
  struct Traits {
    bool reflects = true;
    bool nonSpecular = true;
    bool dispersive = false;
    // A Lambertian reflector's reflectance R (lambertianBins); null for any other BSDF.
    const SpectrumTexture* lambertianReflectance = nullptr;
  };
  Traits traits_;  // set by the constructors of the materials

 private:
  std::unique_ptr<const NormalMap> normalMap_;
};

}  // namespace camsim
