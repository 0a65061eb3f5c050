#include "integrator/render/source_lobe.h"

#include <algorithm>
#include <cmath>

#include "integrator/geometry/math.h"

namespace camsim {
namespace {
constexpr float kTwoPi = 6.28318530717958647692f;
}  // namespace

void SourceMoments::add(const glm::vec3& source, float weight) {
  if (!(weight > 0.0f) || !std::isfinite(weight)) return;
  const double wd = static_cast<double>(weight);
  w += wd;
  for (int a = 0; a < 3; ++a) q[a] += wd * static_cast<double>(source[a]);
  const glm::dvec3 qd(source);
  q2 += wd * glm::dot(qd, qd);
}

float VmfLobe::pdf(const glm::vec3& w) const {
  if (kappa <= 0.0f) return 0.0f;
  // κ/(2π(1 − e^(−2κ))) e^(κ(μ·ω − 1)): the form without overflow for large κ, and
  // μ·ω − 1 = −½|ω − μ|² without the cancellation (at κ = 10⁵ one ulp of μ·ω moved the pdf
  // by 0.6 %).
  const glm::vec3 d = w - mu;
  return kappa / (kTwoPi * -std::expm1(-2.0f * kappa)) * std::exp(-0.5f * kappa * glm::dot(d, d));
}

glm::vec3 VmfLobe::sample(glm::vec2 u, float* density) const {
  // Inverse CDF of cos θ = 1 + ln(u + (1 − u) e^(−2κ))/κ; φ uniform.
  const float e = std::exp(-2.0f * kappa);
  const float cosTheta =
      std::clamp(1.0f + std::log(std::max(u.x + (1.0f - u.x) * e, 1e-30f)) / kappa, -1.0f, 1.0f);
  const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
  const float phi = kTwoPi * u.y;
  const Frame frame = Frame::fromZ(mu);
  const glm::vec3 w =
      glm::normalize(frame.toWorld({sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta}));
  *density = pdf(w);
  return w;
}

SourceLobe SourceLobe::fit(const SourceMoments& m) {
  SourceLobe lobe;
  if (!(m.w > 0.0)) return lobe;
  const glm::dvec3 c(m.q[0] / m.w, m.q[1] / m.w, m.q[2] / m.w);
  const double s2 = m.q2 / m.w - glm::dot(c, c);
  if (!std::isfinite(s2)) return lobe;
  lobe.centre = glm::vec3(c);
  lobe.spread2 = std::max(static_cast<float>(s2), kMinSpread);
  return lobe;
}

VmfLobe SourceLobe::at(const glm::vec3& x) const {
  VmfLobe v;
  if (spread2 <= 0.0f) return v;
  const glm::vec3 toC = centre - x;
  const float d2 = glm::dot(toC, toC);
  const float kappa = kSharpness * d2 / spread2;
  if (!(kappa >= kMinKappa) || !std::isfinite(d2)) return v;
  v.mu = toC / std::sqrt(d2);
  v.kappa = std::min(kappa, kMaxKappa);
  return v;
}

}  // namespace camsim
