#include "integrator/render/path_tracer.h"

#include "integrator/geometry/math.h"
#include "integrator/render/path_guide.h"
#include "integrator/render/spectral_control_variate.h"
#include "integrator/sampling/sobol_sampler.h"

namespace camsim {
namespace {

// Ray from a surface point to another, both offset; stops just short of the target.
Ray shadowRay(const SurfaceInteraction& from, const SurfaceInteraction& to) {
  const glm::vec3 o = from.spawnOrigin(to.p - from.p);
  const glm::vec3 target = to.spawnOrigin(o - to.p);
  Ray r;
  r.o = o;
  r.d = target - o;
  r.tMax = 1.0f - 1e-4f;
  r.time = from.time;
  return r;
}

// Ray from a surface point along w to infinity (sun, environment).
Ray escapeRay(const SurfaceInteraction& from, const glm::vec3& w) {
  return Ray{from.spawnOrigin(w), w, std::numeric_limits<float>::infinity(), from.time};
}

// The shading frame may disagree with the geometry about which side a direction is on
// (interpolated normals). Such directions would leak light through the surface: the
// scattering is rejected unless both frames agree on reflection vs transmission.
bool sidesAgree(const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi,
                const glm::vec3& woLocal, const glm::vec3& wiLocal) {
  const bool geometricReflection = glm::dot(wo, n) * glm::dot(wi, n) > 0.0f;
  const bool shadingReflection = woLocal.z * wiLocal.z > 0.0f;
  return geometricReflection == shadingReflection;
}

// The shading normal at a hit: the shape's, bent by the material's normal map if it has
// one (integrator/textures/normal_map.h), in the shape's tangent frame (none: unbent).
glm::vec3 shadingNormal(const Shape& shape, const Hit& hit, const SurfaceInteraction& si,
                        const Material& material) {
  const NormalMap* map = material.normalMap();
  if (!map) [[likely]]
    return si.ns;
  const std::optional<SurfaceTangents> t = shape.tangentFrame(hit, si);
  if (!t) return si.ns;
  return perturbShadingNormal(si.ns, si.n, t->tangent, t->bitangent,
                              map->tangentSpaceNormal(si.uv));
}

struct ShadingPoint {
  const SurfaceInteraction& si;
  const Frame& frame;
  const glm::vec3& wo;
  glm::vec3 woLocal;
  const Material& material;
  const BsdfContext& ctx;
  const GuideQuery& guide;  // the guide here; density null: unguided

  // The pdf the bounce samples wi with (sr⁻¹): the BSDF's, or the mixture (path_guide.h).
  float scatterPdf(const glm::vec3& wiLocal, const glm::vec3& wi,
                   const SampledWavelengths& lambda) const {
    return mixturePdf(material.pdf(woLocal, wiLocal, lambda, ctx), wi);
  }
  float lobeFraction() const { return guide.lobe.kappa > 0.0f ? PathGuide::kLobeFraction : 0.0f; }
  float mixturePdf(float bsdfPdf, const glm::vec3& wi) const {
    if (!guide.density) return bsdfPdf;
    constexpr float a = PathGuide::kBsdfFraction;
    const float g = lobeFraction();
    float p = a * bsdfPdf + (1.0f - a - g) * PathGuide::pdf(*guide.density, wi);
    if (g > 0.0f) p += g * guide.lobe.pdf(wi);
    return p;
  }
};

// A bounce's sampled direction: what the path loop needs of a BsdfSample.
struct Scatter {
  SampledSpectrum f;  // BSDF, sr⁻¹
  glm::vec3 wiLocal{0.0f};
  float pdf = 0.0f;  // of the scheme that sampled it (for a delta lobe: its probability)
  bool specular = false;
  float etap = 1.0f;
  float bsdfPdf = 0.0f;  // the BSDF's own pdf of wiLocal (sampled as pdf if unguided)
};

// One-sample MIS of the mixture (path_guide.h): uc < α picks the BSDF (uc/α its lobe
// choice), else the guide's density or its source lobe; either way the pdf is the
// mixture's, except for a delta lobe, which only the BSDF samples: its probability is α
// times the lobe's.
template <typename SamplerT>
std::optional<Scatter> scatter(const ShadingPoint& sp, float uc, SamplerT& sampler,
                               const SampledWavelengths& lambda) {
  const glm::vec2 u = sampler.get2D();
  if (!sp.guide.density) {
    const std::optional<BsdfSample> bs = sp.material.sample(sp.woLocal, uc, u, lambda, sp.ctx);
    if (!bs) return std::nullopt;
    return Scatter{bs->f, bs->wi, bs->pdf, bs->specular, bs->etap, bs->pdf};
  }
  constexpr float a = PathGuide::kBsdfFraction;
  if (uc < a) {
    const std::optional<BsdfSample> bs = sp.material.sample(sp.woLocal, uc / a, u, lambda, sp.ctx);
    if (!bs) return std::nullopt;
    if (bs->specular) return Scatter{bs->f, bs->wi, a * bs->pdf, true, bs->etap, bs->pdf};
    // f and pdf evaluated, not the sample's: with several lobes the sample's are the chosen
    // lobe's only, and the mixture needs the same functions of wi for both techniques.
    const float bsdfPdf = sp.material.pdf(sp.woLocal, bs->wi, lambda, sp.ctx);
    return Scatter{sp.material.f(sp.woLocal, bs->wi, lambda, sp.ctx),
                   bs->wi,
                   sp.mixturePdf(bsdfPdf, sp.frame.toWorld(bs->wi)),
                   false,
                   bs->etap,
                   bsdfPdf};
  }
  // The technique that drew wi gives its own density on the way (no second quadtree
  // descent): for the tree, the cell it drew from. Mapping wi back (as the other branches
  // and NEE do) can land in the neighbouring cell within ~10⁻⁷ of a cell's edge: the same
  // rounding the map itself has.
  const float g = sp.lobeFraction();
  float treePdf = 0.0f, lobePdf = 0.0f;
  glm::vec3 wi;
  if (uc < 1.0f - g) {
    wi = PathGuide::sample(*sp.guide.density, u, &treePdf);
    if (g > 0.0f) lobePdf = sp.guide.lobe.pdf(wi);
  } else {
    wi = sp.guide.lobe.sample(u, &lobePdf);
    treePdf = PathGuide::pdf(*sp.guide.density, wi);
  }
  const glm::vec3 wiLocal = sp.frame.toLocal(wi);
  const float bsdfPdf = sp.material.pdf(sp.woLocal, wiLocal, lambda, sp.ctx);
  // etap stays 1: it only steers Russian roulette, which is unbiased for any survival rate.
  return Scatter{sp.material.f(sp.woLocal, wiLocal, lambda, sp.ctx),
                 wiLocal,
                 a * bsdfPdf + (1.0f - a - g) * treePdf + g * lobePdf,
                 false,
                 1.0f,
                 bsdfPdf};
}

// One light sample, MIS-weighted against BSDF sampling: uLight chooses the light, the
// sampler's next 2D draw the point on it. Returns the contribution to L before multiplying
// by the path throughput; adds the control variate's (cv on: Lambertian, its R set).
template <typename SamplerT>
SampledSpectrum sampleLight(const Scene& scene, const ShadingPoint& sp,
                            const SampledWavelengths& lambda, float uLight, SamplerT& sampler,
                            SpectralControlVariate& cv) {
  const glm::vec2 uPoint = sampler.get2D();
  float uRemapped = 0.0f;
  const size_t index = scene.lightDistribution().sample(uLight, &uRemapped);
  const float pmf = scene.lightDistribution().pmf(index);
  const std::optional<LightSample> ls =
      scene.light(index).sample(sp.si.p, sp.si.time, uRemapped, uPoint, lambda);
  if (!ls || pmf == 0.0f || !(ls->pdf > 0.0f)) return SampledSpectrum(0.0f);
  const glm::vec3 wiLocal = sp.frame.toLocal(ls->wi);
  if (!sidesAgree(sp.si.n, sp.wo, ls->wi, sp.woLocal, wiLocal)) return SampledSpectrum(0.0f);
  const SampledSpectrum f =
      sp.material.f(sp.woLocal, wiLocal, lambda, sp.ctx) * std::abs(wiLocal.z);
  // The variate's term does not depend on f being 0 at the drawn wavelengths: only on the
  // sides (where a Lambertian f is 0 at every wavelength).
  const SpectralBins* cvLight =
      cv.on && sp.woLocal.z * wiLocal.z > 0.0f ? scene.light(index).controlVariateBins() : nullptr;
  // (An area light's sample may be black at the drawn wavelengths: it is kept for the term.)
  if ((f.isZero() || ls->L.isZero()) && !cvLight) return SampledSpectrum(0.0f);
  const Ray shadow = ls->infinite ? escapeRay(sp.si, ls->wi) : shadowRay(sp.si, ls->point);
  countRay(RayKind::kShadow, shadow);
  if (scene.geometry().occluded(shadow)) return SampledSpectrum(0.0f);
  const float lightPdf = pmf * ls->pdf;
  const float weight =
      ls->delta ? 1.0f : powerHeuristic(lightPdf, sp.scatterPdf(wiLocal, ls->wi, lambda));
  if (cvLight) cv.addLightSample(*cvLight, std::abs(wiLocal.z) * (weight / lightPdf));
  return f * ls->L * (weight / lightPdf);
}

// The path loop, compiled once per sampler type: for the final samplers the ≈ 20 numbers
// a path draws are direct, inlined calls instead of virtual ones. Guided (a guide or a
// training recorder) is a second instantiation, so that the unguided loop carries none of
// guiding's bookkeeping (the recorder's additions, the roulette throughput, the mixture).
template <bool Guided, typename SamplerT>
SampledSpectrum trace(const Scene& scene, Ray ray, SampledWavelengths& lambda, SamplerT& sampler,
                      VisibleSurface* visible, const PathGuide* guide, GuideRecorder* recorder,
                      SpectralBins* cvOut) {
  const RenderSettings& settings = scene.settings();
  SpectralControlVariate cv;  // spectral_control_variate.h
  cv.on = !Guided && cvOut;
  const bool haveLights = scene.hasPoweredLights();
  SampledSpectrum L(0.0f), beta(1.0f);
  // Russian roulette's throughput: beta, except that guided bounces multiply by the BSDF
  // sampling weight f·cos/p_bsdf instead of f·cos/p_mixture. A guided direction towards
  // bright light has a high p and so a small weight; roulette on beta would kill most of
  // the very paths guiding found (any survival rate keeps the estimator unbiased).
  SampledSpectrum rrBeta(1.0f);
  float etaScale = 1.0f;  // Π etap² of the transmissions so far: beta·etaScale has no η² factors
  float prevBsdfPdf = 0.0f;
  bool prevSpecular = true;  // the camera ray: emitters seen directly get full weight
  glm::vec3 prevP(0.0f);
  if (Guided && recorder) recorder->path.clear();
  // Adds a contribution to L and, in training, to the radiance each earlier vertex received.
  auto add = [&](const SampledSpectrum& c) {
    L += c;
    if constexpr (!Guided) return;
    if (!recorder) return;
    for (GuideRecorder::Vertex& v : recorder->path) {
      // The latest vertex's next vertex is this one: c left it directly (source_lobe.h).
      const bool direct = v.direct && &v == &recorder->path.back();
      for (int i = 0; i < kWavelengthSamples; ++i) {
        if (!(v.beta[i] > 0.0f)) continue;
        const float x = c[i] / v.beta[i];
        v.L[i] += x;
        if (direct) v.Ld[i] += x;
      }
    }
  };
  for (int depth = 0;; ++depth) {
    Hit hit;
    if (!scene.geometry().intersect(ray, hit)) {
      const glm::vec3 d = glm::normalize(ray.d);
      for (size_t index : scene.infiniteLights()) {
        const Light& light = scene.light(index);
        const SampledSpectrum Le = light.Le(d, lambda);
        if (Le.isZero()) continue;
        const float weight =
            prevSpecular ? 1.0f
                         : powerHeuristic(prevBsdfPdf, scene.lightDistribution().pmf(index) *
                                                           light.pdfDirection(d));
        add(beta * Le * weight);
      }
      break;
    }
    const Shape& shape = scene.shape(hit.shape);
    const Material& material = scene.material(hit.shape);
    SurfaceInteraction si = shape.interaction(hit, ray);
    if (Guided && recorder && !recorder->path.empty() && !recorder->path.back().hasNext) {
      recorder->path.back().next = si.p;  // the light a vertex receives leaves from here
      recorder->path.back().hasNext = true;
    }
    si.ns = shadingNormal(shape, hit, si, material);
    const glm::vec3 wo = -glm::normalize(ray.d);
    // One per point: its texture memo serves aov, f, pdf, sample (and vertex colours).
    const BsdfContext ctx = scene.bsdfContext(hit, si);
    if (depth == 0 && visible) [[unlikely]] {
      visible->hit = true;
      visible->p = si.p;
      visible->n = si.n;
      visible->ns = si.ns;
      visible->distance = glm::length(si.p - ray.o);
      visible->shape = hit.shape;
      if (visible->wantMaterial) {
        const SurfaceAov aov = material.aov(lambda, ctx);
        visible->albedo = aov.albedo;
        visible->roughness = aov.roughness;
      }
    }

    if (const AreaLight* light = scene.areaLight(hit.shape)) {
      const SampledSpectrum Le = light->L(si, wo, lambda);
      const SpectralBins* cvLight =
          cv.on && light->emitsTowards(si, wo) ? light->controlVariateBins() : nullptr;
      if (!Le.isZero() || cvLight) {
        float weight = 1.0f;
        if (!prevSpecular) {
          const float lightPdf = scene.lightPmfOfShape(hit.shape) * light->pdf(prevP, si);
          weight = powerHeuristic(prevBsdfPdf, lightPdf);
        }
        if (!Le.isZero()) add(beta * Le * weight);
        cv.addEmission(cvLight, weight);
      }
    }
    if (depth >= settings.maxDepth) break;
    if (!material.reflects()) break;
    if (material.dispersive()) lambda.terminateSecondary();
    cv.enter(material, ctx);

    const Frame frame = Frame::fromZ(si.ns);
    const GuideQuery here =
        Guided && guide && material.hasNonSpecular() ? guide->at(si.p) : GuideQuery{};
    const ShadingPoint sp{si, frame, wo, frame.toLocal(wo), material, ctx, here};
    // The bounce's two 1D choices, which light and which BSDF lobe, share one 2D draw (one
    // sampler dimension instead of two).
    const glm::vec2 uChoice = sampler.get2D();
    if (haveLights && material.hasNonSpecular())
      add(beta * sampleLight(scene, sp, lambda, uChoice.x, sampler, cv));

    const std::optional<Scatter> bs = scatter(sp, uChoice.y, sampler, lambda);
    if (!bs || !(bs->pdf > 0.0f)) break;
    // f = 0 at the drawn wavelengths ends the path unless the variate still carries it.
    if (bs->f.isZero() && !(cv.on && !cv.reflectance->isZero())) break;
    const glm::vec3 wi = frame.toWorld(bs->wiLocal);
    if (!sidesAgree(si.n, wo, wi, sp.woLocal, bs->wiLocal)) break;
    const SampledSpectrum weight = bs->f * (std::abs(bs->wiLocal.z) / bs->pdf);
    beta *= weight;
    if (cv.on) cv.scatter(std::abs(bs->wiLocal.z) / bs->pdf);
    if constexpr (Guided)
      rrBeta *= sp.guide.density && bs->bsdfPdf > 0.0f
                    ? bs->f * (std::abs(bs->wiLocal.z) / bs->bsdfPdf)
                    : weight;
    if (Guided && recorder) {
      if (!bs->specular)
        recorder->path.push_back({si.p, directionToSquare(wi), bs->pdf, beta, SampledSpectrum(0.0f),
                                  SampledSpectrum(0.0f), true, glm::vec3(0.0f), false});
      else if (!recorder->path.empty())  // light past here did not leave `next` directly
        recorder->path.back().direct = false;
    }
    etaScale *= bs->etap * bs->etap;
    prevBsdfPdf = bs->pdf;
    prevSpecular = bs->specular;
    prevP = si.p;
    ray = Ray{si.spawnOrigin(wi), wi, std::numeric_limits<float>::infinity(), ray.time};

    if (depth + 1 >= settings.rrDepth) {
      // Survival √(max β), at most 1 (Cycles' rule; docs/performance.md, "Russian roulette:
      // survival √β"): after a survival β is √ of what it was, so the first roulette ends
      // fewer paths than pbrt's survival ∝ β (after three white walls β = 0.73³ = 0.39:
      // 38 % against 61 %); far on, both survive with the albedo. β without the 1/η² of
      // refraction: inside glass beta is η² smaller although the path carries as much
      // light out again.
      // With the spectral control variate on, its bins: no decision may depend on the
      // wavelengths drawn (spectral_control_variate.h; they are not all 0 while it is on).
      const float rrMax = cv.on ? cv.beta.maxComponent() : (Guided ? rrBeta : beta).maxComponent();
      const float q = std::max(0.0f, 1.0f - std::sqrt(rrMax * etaScale));
      if (sampler.get1D() < q) break;
      beta /= 1.0f - q;
      if (cv.on) cv.beta *= 1.0f / (1.0f - q);
      if constexpr (Guided) rrBeta /= 1.0f - q;
    }
    countRay(RayKind::kBounce, ray);  // after roulette: a path it ends never traces the ray
  }
  if (Guided && recorder && recorder->out)
    for (const GuideRecorder::Vertex& v : recorder->path) {
      const float Ld = v.Ld.average();
      recorder->out->push_back(
          {v.p, v.square, v.L.average() / v.pdf, v.next, v.hasNext ? Ld * Ld / v.pdf : 0.0f});
    }
  if (cvOut) *cvOut = cv.L;
  return L;
}

}  // namespace

SampledSpectrum traceRadiance(const Scene& scene, Ray ray, SampledWavelengths& lambda,
                              SobolSampler& sampler, VisibleSurface* visible,
                              const PathGuide* guide, GuideRecorder* recorder, SpectralBins* cv) {
  if (guide || recorder)
    return trace<true>(scene, ray, lambda, sampler, visible, guide, recorder, cv);
  return trace<false>(scene, ray, lambda, sampler, visible, nullptr, nullptr, cv);
}

SampledSpectrum traceRadiance(const Scene& scene, Ray ray, SampledWavelengths& lambda,
                              IndependentSampler& sampler, VisibleSurface* visible,
                              const PathGuide* guide, GuideRecorder* recorder, SpectralBins* cv) {
  if (guide || recorder)
    return trace<true>(scene, ray, lambda, sampler, visible, guide, recorder, cv);
  return trace<false>(scene, ray, lambda, sampler, visible, nullptr, nullptr, cv);
}

}  // namespace camsim
