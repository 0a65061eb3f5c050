#include "integrator/render/path_tracer.h"

#include "integrator/geometry/math.h"
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
};

// One light sample, MIS-weighted against BSDF sampling: uLight chooses the light, the
// sampler's next 2D draw the point on it. Returns the contribution to L before multiplying
// by the path throughput.
template <typename SamplerT>
SampledSpectrum sampleLight(const Scene& scene, const ShadingPoint& sp,
                            const SampledWavelengths& lambda, float uLight, SamplerT& sampler) {
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
  if (f.isZero()) return SampledSpectrum(0.0f);
  const Ray shadow = ls->infinite ? escapeRay(sp.si, ls->wi) : shadowRay(sp.si, ls->point);
  countRay(RayKind::kShadow, shadow);
  if (scene.geometry().occluded(shadow)) return SampledSpectrum(0.0f);
  const float lightPdf = pmf * ls->pdf;
  const float weight =
      ls->delta ? 1.0f
                : powerHeuristic(lightPdf, sp.material.pdf(sp.woLocal, wiLocal, lambda, sp.ctx));
  return f * ls->L * (weight / lightPdf);
}

// The path loop, compiled once per sampler type: for the final samplers the ≈ 20 numbers
// a path draws are direct, inlined calls instead of virtual ones.
template <typename SamplerT>
SampledSpectrum trace(const Scene& scene, Ray ray, SampledWavelengths& lambda, SamplerT& sampler,
                      VisibleSurface* visible) {
  const RenderSettings& settings = scene.settings();
  const bool haveLights = scene.hasPoweredLights();
  SampledSpectrum L(0.0f), beta(1.0f);
  float etaScale = 1.0f;  // Π etap² of the transmissions so far: beta·etaScale has no η² factors
  float prevBsdfPdf = 0.0f;
  bool prevSpecular = true;  // the camera ray: emitters seen directly get full weight
  glm::vec3 prevP(0.0f);
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
        L += beta * Le * weight;
      }
      break;
    }
    const Shape& shape = scene.shape(hit.shape);
    const Material& material = scene.material(hit.shape);
    SurfaceInteraction si = shape.interaction(hit, ray);
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
      if (!Le.isZero()) {
        if (prevSpecular) {
          L += beta * Le;
        } else {
          const float lightPdf = scene.lightPmfOfShape(hit.shape) * light->pdf(prevP, si);
          L += beta * Le * powerHeuristic(prevBsdfPdf, lightPdf);
        }
      }
    }
    if (depth >= settings.maxDepth) break;
    if (!material.reflects()) break;
    if (material.dispersive()) lambda.terminateSecondary();

    const Frame frame = Frame::fromZ(si.ns);
    const ShadingPoint sp{si, frame, wo, frame.toLocal(wo), material, ctx};
    // The bounce's two 1D choices, which light and which BSDF lobe, share one 2D draw (one
    // sampler dimension instead of two).
    const glm::vec2 uChoice = sampler.get2D();
    if (haveLights && material.hasNonSpecular())
      L += beta * sampleLight(scene, sp, lambda, uChoice.x, sampler);

    const std::optional<BsdfSample> bs =
        material.sample(sp.woLocal, uChoice.y, sampler.get2D(), lambda, sp.ctx);
    if (!bs || !(bs->pdf > 0.0f) || bs->f.isZero()) break;
    const glm::vec3 wi = frame.toWorld(bs->wi);
    if (!sidesAgree(si.n, wo, wi, sp.woLocal, bs->wi)) break;
    beta *= bs->f * (std::abs(bs->wi.z) / bs->pdf);
    etaScale *= bs->etap * bs->etap;
    prevBsdfPdf = bs->pdf;
    prevSpecular = bs->specular;
    prevP = si.p;
    ray = Ray{si.spawnOrigin(wi), wi, std::numeric_limits<float>::infinity(), ray.time};
    countRay(RayKind::kBounce, ray);

    if (depth + 1 >= settings.rrDepth) {
      // Survival ∝ the throughput without the 1/η² of refraction: inside glass beta is
      // η² smaller although the path carries as much light out again.
      const float q = std::max(0.0f, 1.0f - beta.maxComponent() * etaScale);
      if (sampler.get1D() < q) break;
      beta /= 1.0f - q;
    }
  }
  return L;
}

}  // namespace

SampledSpectrum traceRadiance(const Scene& scene, Ray ray, SampledWavelengths& lambda,
                              SobolSampler& sampler, VisibleSurface* visible) {
  return trace(scene, ray, lambda, sampler, visible);
}

SampledSpectrum traceRadiance(const Scene& scene, Ray ray, SampledWavelengths& lambda,
                              IndependentSampler& sampler, VisibleSurface* visible) {
  return trace(scene, ray, lambda, sampler, visible);
}

}  // namespace camsim
