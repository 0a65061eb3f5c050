#include "integrator/lights/area_light.h"

#include "integrator/geometry/math.h"

namespace camsim {

AreaLight::AreaLight(const Shape& shape, Spectrum radiance, bool twoSided)
    : shape_(shape),
      radiance_(radiance),
      twoSided_(twoSided),
      front_(twoSided ? std::nullopt : shape.frontPlane()) {}

std::optional<LightSample> AreaLight::sample(const glm::vec3& ref, double time, float u1,
                                             glm::vec2 u2, const SampledWavelengths& lambda) const {
  // Every return returns `out`, so it is built in the caller's slot (the light point is
  // copied once, from the shape's sample).
  std::optional<LightSample> out;
  if (front_ && front_->entirelyBehind(ref)) return out;  // L would be 0
  const std::optional<ShapeSample> ss = shape_.sample(ref, u1, u2, time);
  if (!ss) return out;
  if (!emitsTowards(ss->point, -ss->wi)) return out;
  const SampledSpectrum Le = sampleSpectrum(radiance_, lambda);
  // Black at these wavelengths: nothing to add, unless the control variate adds its term
  // (which must not depend on the wavelengths drawn).
  if (Le.isZero() && !cvBins_) return out;
  LightSample& ls = out.emplace();
  ls.L = Le;
  ls.wi = ss->wi;
  ls.pdf = ss->pdf;
  ls.point = ss->point;
  return out;
}

float AreaLight::pdf(const glm::vec3& ref, const SurfaceInteraction& onLight) const {
  return shape_.pdf(ref, onLight);
}

void AreaLight::setControlVariateReference(const SpectralBins& referenceAverages) {
  const SpectralBins mine = binAverages(radiance_);
  SpectralBins& bins = cvBins_.emplace();
  for (int b = 0; b < kSpectralBins; ++b)
    bins[b] = referenceAverages[b] > 0.0f ? mine[b] / referenceAverages[b] : 0.0f;
}

double AreaLight::power() const {
  return static_cast<double>(kPi * shape_.area()) * radiance_.sum() * (twoSided_ ? 2.0 : 1.0);
}

}  // namespace camsim
