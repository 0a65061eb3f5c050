#include "integrator/lights/point_light.h"

#include <cmath>

#include "integrator/geometry/math.h"

namespace camsim {

SurfaceInteraction deltaLightPoint(const glm::vec3& p, double time) {
  SurfaceInteraction si;
  si.p = p;
  si.time = time;
  return si;
}

PointLight::PointLight(const glm::vec3& position, const Spectrum& intensity)
    : position_(position), intensity_(intensity) {}

std::optional<LightSample> PointLight::sample(const glm::vec3& ref, double time, float /*u1*/,
                                              glm::vec2 /*u2*/,
                                              const SampledWavelengths& lambda) const {
  const glm::vec3 toLight = position_ - ref;
  const float dist2 = lengthSquared(toLight);
  if (!(dist2 > 0.0f) || !std::isfinite(dist2)) return std::nullopt;
  LightSample ls;
  ls.wi = toLight / std::sqrt(dist2);
  ls.L = sampleSpectrum(intensity_, lambda) / dist2;
  if (ls.L.isZero()) return std::nullopt;
  ls.pdf = 1.0f;
  ls.delta = true;
  ls.point = deltaLightPoint(position_, time);
  return ls;
}

double PointLight::power() const {
  return 4.0 * M_PI * intensity_.sum();
}

}  // namespace camsim
