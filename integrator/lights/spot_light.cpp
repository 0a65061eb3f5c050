#include "integrator/lights/spot_light.h"

#include <algorithm>
#include <cmath>

#include "sensor/base/check.h"

namespace camsim {

SpotLight::SpotLight(const glm::vec3& position, const glm::vec3& axis, const Spectrum& intensity,
                     float coneAngle, float falloffStart)
    : point_(position, intensity),
      axis_(glm::normalize(axis)),
      intensitySum_(intensity.sum()),
      cosEnd_(std::cos(coneAngle)),
      cosStart_(std::cos(falloffStart)),
      coneAngle_(static_cast<double>(coneAngle)),
      falloffStart_(static_cast<double>(falloffStart)) {
  CAMSIM_CHECK(falloffStart >= 0.0f && falloffStart <= coneAngle && coneAngle <= kPi);
  CAMSIM_CHECK(std::isfinite(axis_.x) && std::isfinite(axis_.y) && std::isfinite(axis_.z));
}

float SpotLight::falloff(const glm::vec3& w) const {
  const float c = glm::dot(axis_, w);
  if (c >= cosStart_) return 1.0f;
  if (c <= cosEnd_) return 0.0f;
  const float t = std::clamp((c - cosEnd_) / (cosStart_ - cosEnd_), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

std::optional<LightSample> SpotLight::sample(const glm::vec3& ref, double time, float u1,
                                             glm::vec2 u2, const SampledWavelengths& lambda) const {
  std::optional<LightSample> ls = point_.sample(ref, time, u1, u2, lambda);
  if (!ls) return std::nullopt;
  const float f = falloff(-ls->wi);
  if (f == 0.0f) return std::nullopt;
  ls->L *= f;
  return ls;
}

double SpotLight::effectiveSolidAngle(double coneAngle, double falloffStart) {
  // 2π[(1 − cos θ_s) + (cos θ_s − cos θ_e)/2] = π[(1 − cos θ_s) + (1 − cos θ_e)], in double
  // with 1 − cos θ = 2 sin²(θ/2) so that narrow spots keep their precision.
  const double oneMinusCosStart = 2.0 * std::pow(std::sin(0.5 * falloffStart), 2.0);
  const double oneMinusCosEnd = 2.0 * std::pow(std::sin(0.5 * coneAngle), 2.0);
  return M_PI * (oneMinusCosStart + oneMinusCosEnd);
}

double SpotLight::power() const {
  return effectiveSolidAngle(coneAngle_, falloffStart_) * intensitySum_;
}

}  // namespace camsim
