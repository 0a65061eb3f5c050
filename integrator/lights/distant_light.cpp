#include "integrator/lights/distant_light.h"

#include <cmath>

#include "sensor/base/check.h"

namespace camsim {

DistantLight::DistantLight(const Spectrum& irradiance, const glm::vec3& direction,
                           float angularDiameter)
    : irradiance_(irradiance),
      toLight_(-glm::normalize(direction)),
      frame_(Frame::fromZ(toLight_)),
      delta_(angularDiameter == 0.0f) {
  CAMSIM_CHECK(angularDiameter >= 0.0f && angularDiameter < kPi);
  CAMSIM_CHECK(std::isfinite(toLight_.x) && std::isfinite(toLight_.y) && std::isfinite(toLight_.z));
  if (!delta_) {
    const double alpha = 0.5 * static_cast<double>(angularDiameter);
    const double sinHalf = std::sin(0.5 * alpha);
    oneMinusCosAlpha_ = 2.0 * sinHalf * sinHalf;
    const double sinAlpha = std::sin(alpha);
    sin2Alpha_ = static_cast<float>(sinAlpha * sinAlpha);
    conePdf_ = static_cast<float>(1.0 / (2.0 * M_PI * oneMinusCosAlpha_));
    radiancePerIrradiance_ = 1.0 / (M_PI * sinAlpha * sinAlpha);
  }
}

void DistantLight::setSceneBounds(const glm::vec3& /*centre*/, float radius) {
  sceneRadius_ = radius;
}

bool DistantLight::inCone(const glm::vec3& d) const {
  // |d × toLight|² = sin²θ is accurate for the small angles of the sun, where cos θ ≈ 1
  // would lose the disc's edge in float.
  if (glm::dot(d, toLight_) <= 0.0f) return false;
  const glm::vec3 c = glm::cross(d, toLight_);
  return lengthSquared(c) <= sin2Alpha_ * lengthSquared(d);
}

std::optional<LightSample> DistantLight::sample(const glm::vec3& /*ref*/, double /*time*/,
                                                float /*u1*/, glm::vec2 u2,
                                                const SampledWavelengths& lambda) const {
  LightSample ls;
  ls.infinite = true;
  if (delta_) {
    ls.wi = toLight_;
    ls.L = sampleSpectrum(irradiance_, lambda);
    ls.pdf = 1.0f;
    ls.delta = true;
  } else {
    // Uniform in the cone: 1 − cos θ = u (1 − cos α), sin θ = √((1 − cos θ)(1 + cos θ)).
    const double oneMinusCos = static_cast<double>(u2.x) * oneMinusCosAlpha_;
    const double cosTheta = 1.0 - oneMinusCos;
    const double sinTheta = std::sqrt(std::max(0.0, oneMinusCos * (1.0 + cosTheta)));
    const double phi = 2.0 * M_PI * static_cast<double>(u2.y);
    const glm::vec3 local(static_cast<float>(sinTheta * std::cos(phi)),
                          static_cast<float>(sinTheta * std::sin(phi)),
                          static_cast<float>(cosTheta));
    ls.wi = glm::normalize(frame_.toWorld(local));
    ls.L = sampleSpectrum(irradiance_, lambda) * static_cast<float>(radiancePerIrradiance_);
    ls.pdf = conePdf_;
  }
  if (ls.L.isZero()) return std::nullopt;
  return ls;
}

SampledSpectrum DistantLight::Le(const glm::vec3& direction,
                                 const SampledWavelengths& lambda) const {
  if (delta_ || !inCone(direction)) return SampledSpectrum(0.0f);
  return sampleSpectrum(irradiance_, lambda) * static_cast<float>(radiancePerIrradiance_);
}

float DistantLight::pdfDirection(const glm::vec3& direction) const {
  if (delta_ || !inCone(direction)) return 0.0f;
  return conePdf_;
}

double DistantLight::power() const {
  const double r = static_cast<double>(sceneRadius_);
  return M_PI * r * r * irradiance_.sum();
}

}  // namespace camsim
