// The dielectric specular layer's albedo table (see dielectric_specular_albedo.h).
#include "integrator/materials/dielectric_specular_albedo.h"

#include <algorithm>
#include <cmath>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/materials/microfacet.h"

namespace camsim {
namespace {

constexpr double kTableMinAlpha = 9e-6;  // r = 0's row: the smooth limit
constexpr int kNodeSamples = 32;         // per axis, per node
constexpr int kAverageSteps = 256;       // midpoints in μ for E_avg
constexpr double kTableF0 = 0.04;

// x clamped to [0, 1]; NaN → 0 (a NaN must not reach the float → int cast of a lookup).
double unit(double x) {
  return x > 0.0 ? std::min(x, 1.0) : 0.0;
}

double tableAlpha(double r) {
  return std::max(r * r, kTableMinAlpha);
}

// Node coordinate x for cos θ under α (and back).
double xOf(double mu, double alpha) {
  const double u = mu / std::sqrt(mu * mu + alpha * alpha * (1.0 - mu * mu));
  return 1.0 - std::sqrt(std::max(0.0, 1.0 - u));
}
double muOf(double x, double alpha) {
  const double u = 1.0 - (1.0 - x) * (1.0 - x);
  return u * alpha / std::sqrt(std::max(1e-300, 1.0 - u * u + u * u * alpha * alpha));
}

}  // namespace

float DielectricSpecularAlbedo::fresnel(float cosTheta) {
  const float x = 1.0f - std::clamp(cosTheta, 0.0f, 1.0f);
  const float x2 = x * x;
  return static_cast<float>(kTableF0) + static_cast<float>(1.0 - kTableF0) * x2 * x2 * x;
}

double DielectricSpecularAlbedo::integrate(double cosTheta, double alpha, int n) {
  const double mu = std::clamp(cosTheta, 1e-6, 1.0);
  const MicrofacetModel model(MicrofacetDistribution::kGgx, MaskingModel::kSmith,
                              static_cast<float>(alpha), static_cast<float>(alpha));
  const glm::vec3 wo(static_cast<float>(std::sqrt(1.0 - mu * mu)), 0.0f, static_cast<float>(mu));
  double sum = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const glm::vec2 u(static_cast<float>((i + 0.5) / n), static_cast<float>((j + 0.5) / n));
      const auto s = model.sampleReflection(wo, u);
      if (!s) continue;
      const MicrofacetModel::Reflection r = model.reflection(wo, s->wi, s->wm);
      if (!(r.pdf > 0.0f)) continue;
      const double cosH = std::abs(static_cast<double>(glm::dot(wo, s->wm)));
      sum += static_cast<double>(fresnel(static_cast<float>(cosH))) * static_cast<double>(r.f) *
             static_cast<double>(s->wi.z) / static_cast<double>(r.pdf);
    }
  return sum / (static_cast<double>(n) * n);
}

DielectricSpecularAlbedo::DielectricSpecularAlbedo() {
  for (int j = 0; j < kNodes; ++j) {
    const double t = static_cast<double>(j) / (kNodes - 1);
    const double alpha = tableAlpha(t * t);
    for (int i = 0; i < kNodes; ++i) {
      const double mu = std::clamp(muOf(static_cast<double>(i) / (kNodes - 1), alpha), 1e-6, 1.0);
      const double e = integrate(mu, alpha, kNodeSamples);
      q_[static_cast<size_t>(j * kNodes + i)] =
          static_cast<float>(e / static_cast<double>(fresnel(static_cast<float>(mu))));
    }
  }
  // E_avg of the table itself, at each r node (lookups need average_ only afterwards).
  for (int j = 0; j < kNodes; ++j) {
    const float t = static_cast<float>(j) / (kNodes - 1), r = t * t;
    double sum = 0.0;
    for (int k = 0; k < kAverageSteps; ++k) {
      const double mu = (k + 0.5) / kAverageSteps;
      sum += static_cast<double>(albedo(static_cast<float>(mu), r)) * mu;
    }
    average_[static_cast<size_t>(j)] = static_cast<float>(2.0 * sum / kAverageSteps);
  }
}

const DielectricSpecularAlbedo& DielectricSpecularAlbedo::get() {
  static const DielectricSpecularAlbedo table;
  return table;
}

float DielectricSpecularAlbedo::albedo(float cosTheta, float roughness) const {
  const double mu = unit(static_cast<double>(cosTheta));
  const double r = unit(static_cast<double>(roughness));
  const double gx = xOf(mu, tableAlpha(r)) * (kNodes - 1), gr = std::sqrt(r) * (kNodes - 1);
  const int i = std::min(static_cast<int>(gx), kNodes - 2),
            j = std::min(static_cast<int>(gr), kNodes - 2);
  const double fx = gx - i, fr = gr - j;
  auto q = [&](int a, int b) {
    return static_cast<double>(q_[static_cast<size_t>(b * kNodes + a)]);
  };
  const double value = (1.0 - fr) * ((1.0 - fx) * q(i, j) + fx * q(i + 1, j)) +
                       fr * ((1.0 - fx) * q(i, j + 1) + fx * q(i + 1, j + 1));
  return static_cast<float>(value) * fresnel(static_cast<float>(mu));
}

float DielectricSpecularAlbedo::average(float roughness) const {
  const double gr = std::sqrt(unit(static_cast<double>(roughness))) * (kNodes - 1);
  const int j = std::min(static_cast<int>(gr), kNodes - 2);
  const double f = gr - j;
  return static_cast<float>((1.0 - f) * static_cast<double>(average_[static_cast<size_t>(j)]) +
                            f * static_cast<double>(average_[static_cast<size_t>(j) + 1]));
}

}  // namespace camsim
