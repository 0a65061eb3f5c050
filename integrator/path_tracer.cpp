#include "integrator/path_tracer.h"

#include "integrator/math.h"

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

// One light sample, MIS-weighted against BSDF sampling. Returns the contribution to L
// before multiplying by the path throughput.
SampledSpectrum sampleLight(const Scene& scene, const SurfaceInteraction& si, const Frame& frame,
                            const glm::vec3& woLocal, const Material& material,
                            const SampledWavelengths& lambda, Sampler& sampler, RayCounts& counts) {
  const float uLight = sampler.get1D();
  const glm::vec2 uPoint = sampler.get2D();
  float uRemapped = 0.0f;
  const size_t index = scene.lightDistribution().sample(uLight, &uRemapped);
  const float pmf = scene.lightDistribution().pmf(index);
  const std::optional<LightSample> ls = scene.light(index).sample(si.p, si.time, uRemapped, uPoint, lambda);
  if (!ls || pmf == 0.0f) return SampledSpectrum(0.0f);
  const glm::vec3 wiLocal = frame.toLocal(ls->wi);
  const SampledSpectrum f = material.f(woLocal, wiLocal, lambda) * std::abs(wiLocal.z);
  if (f.isZero()) return SampledSpectrum(0.0f);
  ++counts.shadow;
  if (scene.geometry().occluded(shadowRay(si, ls->point))) return SampledSpectrum(0.0f);
  const float lightPdf = pmf * ls->pdf;
  const float weight = powerHeuristic(lightPdf, material.pdf(woLocal, wiLocal));
  return f * ls->L * (weight / lightPdf);
}

}  // namespace

SampledSpectrum traceRadiance(const Scene& scene, Ray ray, const SampledWavelengths& lambda,
                              Sampler& sampler, RayCounts& counts) {
  const RenderSettings& settings = scene.settings();
  const bool haveLights = scene.lightCount() > 0;
  SampledSpectrum L(0.0f), beta(1.0f);
  float prevBsdfPdf = 0.0f;
  glm::vec3 prevP(0.0f);
  for (int depth = 0;; ++depth) {
    Hit hit;
    if (!scene.geometry().intersect(ray, hit)) break;
    const SurfaceInteraction si = scene.shape(hit.shape).interaction(hit, ray);
    const glm::vec3 wo = -glm::normalize(ray.d);

    if (const AreaLight* light = scene.areaLight(hit.shape)) {
      const SampledSpectrum Le = light->L(si, wo, lambda);
      if (!Le.isZero()) {
        if (depth == 0) {
          L += beta * Le;
        } else {
          const float lightPdf = scene.lightPmfOfShape(hit.shape) * light->pdf(prevP, si);
          L += beta * Le * powerHeuristic(prevBsdfPdf, lightPdf);
        }
      }
    }
    if (depth >= settings.maxDepth) break;
    const Material& material = scene.material(hit.shape);
    if (!material.reflects()) break;

    const Frame frame = Frame::fromZ(si.ns);
    const glm::vec3 woLocal = frame.toLocal(wo);
    if (haveLights) L += beta * sampleLight(scene, si, frame, woLocal, material, lambda, sampler, counts);

    const float uc = sampler.get1D();
    const std::optional<BsdfSample> bs = material.sample(woLocal, uc, sampler.get2D(), lambda);
    if (!bs || bs->pdf == 0.0f || bs->f.isZero()) break;
    beta *= bs->f * (std::abs(bs->wi.z) / bs->pdf);
    prevBsdfPdf = bs->pdf;
    prevP = si.p;
    const glm::vec3 wi = frame.toWorld(bs->wi);
    ray = Ray{si.spawnOrigin(wi), wi, std::numeric_limits<float>::infinity(), ray.time};
    ++counts.bounce;

    if (depth + 1 >= settings.rrDepth) {
      const float q = std::max(0.0f, 1.0f - beta.maxComponent());
      if (sampler.get1D() < q) break;
      beta /= 1.0f - q;
    }
  }
  return L;
}

}  // namespace camsim
