// ReflectanceUplift (see reflectance_uplift.h): quadrature weights, start table, Newton.
#include "integrator/textures/reflectance_uplift.h"

#include <algorithm>
#include <cmath>

#include <glm/matrix.hpp>

#include "sensor/spectra/cie.h"

namespace camsim {
namespace {

constexpr int kNodeSpacingNm = 5;
constexpr double kTolerance = 1e-6;
constexpr int kMaxSteps = 6;
constexpr double kTrusted = 1e-4;
constexpr double kMaxCoefficient = 1e10;

double smoothstep(double x) {
  return x * x * (3.0 - 2.0 * x);
}

// S⁻¹(y), clamped so that black and white stay finite.
double inverseSigmoid(double y) {
  if (y <= 0.0) return -kMaxCoefficient;
  if (y >= 1.0) return kMaxCoefficient;
  return std::clamp((2.0 * y - 1.0) / (2.0 * std::sqrt(y * (1.0 - y))), -kMaxCoefficient,
                    kMaxCoefficient);
}

}  // namespace

const ReflectanceUplift& ReflectanceUplift::linearRec709() {
  static const ReflectanceUplift uplift(RgbColorSpace::linearRec709());
  return uplift;
}

ReflectanceUplift::ReflectanceUplift(const RgbColorSpace& space) {
  static_assert((kSpectrumSamples - 1) % kNodeSpacingNm == 0 &&
                (kSpectrumSamples - 1) / kNodeSpacingNm + 1 == kNodes);
  static_assert(kPaddedNodes % kLanes == 0 && kPaddedNodes >= kNodes);
  const Cie1931& cie = Cie1931::get();
  const double norm = innerProduct(space.illuminant(), cie.y);
  std::array<glm::dvec3, kNodes> w1{};  // W_j
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const glm::dvec3 xyz(cie.x.sample(i), cie.y.sample(i), cie.z.sample(i));
    const glm::dvec3 w =
        space.rgbFromXyz() * xyz * (static_cast<double>(space.illuminant().sample(i)) / norm);
    // Cubic Lagrange basis on the 4 nodes around sample i (shifted inwards at the ends).
    const double x = static_cast<double>(i) / kNodeSpacingNm;  // position in node units
    const int below = std::min(static_cast<int>(x), kNodes - 2);
    const int lo = std::clamp(below - 1, 0, kNodes - 4);
    for (int a = lo; a < lo + 4; ++a) {
      double basis = 1.0;
      for (int b = lo; b < lo + 4; ++b)
        if (b != a) basis *= (x - b) / static_cast<double>(a - b);
      w1[static_cast<size_t>(a)] += basis * w;
    }
  }
  for (size_t j = 0; j < static_cast<size_t>(kNodes); ++j) {
    const double t = static_cast<double>(j) * kNodeSpacingNm / (kSpectrumSamples - 1);
    t_[j] = static_cast<float>(t);
    for (size_t p = 0; p < 3; ++p)
      for (size_t k = 0; k < 3; ++k)
        weights_[p][k][j] =
            static_cast<float>(std::pow(t, static_cast<double>(p)) * w1[j][static_cast<int>(k)]);
  }
  for (size_t j = kNodes; j < static_cast<size_t>(kPaddedNodes); ++j) t_[j] = 1.0f;  // weights 0
  buildTable();
}

// 12 sums over the nodes: RGB = Σ S(x_j) W_j and ∂RGB/∂c_k = Σ S'(x_j) t_j^(2−k) W_j.
// kLanes independent partial sums per quantity, so the compiler can vectorise the loop
// without reordering any floating-point sum.
glm::dvec3 ReflectanceUplift::evaluate(const Coeffs& c, glm::dmat3* jacobian) const {
  constexpr size_t L = kLanes;
  float sums[4][3][L] = {};  // [RGB, ∂c₂, ∂c₁, ∂c₀][channel][lane]
  const float c0 = static_cast<float>(c[0]), c1 = static_cast<float>(c[1]),
              c2 = static_cast<float>(c[2]);
  for (size_t j0 = 0; j0 < static_cast<size_t>(kPaddedNodes); j0 += L) {
    float s[L], ds[L];
    for (size_t l = 0; l < L; ++l) {
      const float t = t_[j0 + l];
      const float x = (c0 * t + c1) * t + c2;
      const float q = 1.0f / std::sqrt(1.0f + x * x);
      s[l] = 0.5f + 0.5f * x * q;  // S(x)
      ds[l] = 0.5f * q * q * q;    // S'(x)
    }
    for (size_t k = 0; k < 3; ++k)
      for (size_t l = 0; l < L; ++l) {
        sums[0][k][l] += s[l] * weights_[0][k][j0 + l];
        sums[1][k][l] += ds[l] * weights_[0][k][j0 + l];
        sums[2][k][l] += ds[l] * weights_[1][k][j0 + l];
        sums[3][k][l] += ds[l] * weights_[2][k][j0 + l];
      }
  }
  glm::dvec3 total[4];
  for (size_t q = 0; q < 4; ++q)
    for (size_t k = 0; k < 3; ++k) {
      double sum = 0.0;
      for (size_t l = 0; l < L; ++l) sum += static_cast<double>(sums[q][k][l]);
      total[q][static_cast<int>(k)] = sum;
    }
  if (jacobian != nullptr)
    *jacobian = glm::dmat3(total[3], total[2], total[1]);  // columns ∂c₀, ∂c₁, ∂c₂
  return total[0];
}

glm::dvec3 ReflectanceUplift::rgbOf(const SigmoidPolynomial& p) const {
  return evaluate({p.c0, p.c1, p.c2}, nullptr);
}

double ReflectanceUplift::refine(const glm::dvec3& target, Coeffs& c, int maxSteps,
                                 double tolerance, double trusted) const {
  glm::dmat3 jacobian;
  glm::dvec3 r = evaluate(c, &jacobian) - target;
  double err = glm::dot(r, r);
  for (int step = 0; step < maxSteps && err > tolerance * tolerance; ++step) {
    if (!(std::abs(glm::determinant(jacobian)) > 0.0)) break;
    const glm::dvec3 delta = -(glm::inverse(jacobian) * r);
    if (err < trusted * trusted) {  // close enough for Newton's quadratic convergence
      for (size_t k = 0; k < 3; ++k)
        c[k] = std::clamp(c[k] + delta[static_cast<int>(k)], -kMaxCoefficient, kMaxCoefficient);
      return 0.0;
    }
    bool improved = false;
    for (double scale = 1.0; scale > 1e-4 && !improved; scale *= 0.5) {
      Coeffs q{c[0] + scale * delta[0], c[1] + scale * delta[1], c[2] + scale * delta[2]};
      for (double& v : q) v = std::clamp(v, -kMaxCoefficient, kMaxCoefficient);
      glm::dmat3 jq;
      const glm::dvec3 rq = evaluate(q, &jq) - target;
      const double eq = glm::dot(rq, rq);
      if (std::isfinite(eq) && eq < err) {
        c = q;
        r = rq;
        err = eq;
        jacobian = jq;
        improved = true;
      }
    }
    if (!improved) break;
  }
  return std::sqrt(err);
}

// Fitted along lines of constant (a, b), from z near 0.2 outwards, each fit starting from
// its neighbour's coefficients (Jakob & Hanika's continuation).
void ReflectanceUplift::buildTable() {
  table_.assign(3 * static_cast<size_t>(kTableRes) * kTableRes * kTableRes, {0.0f, 0.0f, 0.0f});
  for (int k = 0; k < kTableRes; ++k)
    zNodes_[static_cast<size_t>(k)] =
        smoothstep(smoothstep(static_cast<double>(k) / (kTableRes - 1)));
  const int first = kTableRes / 5;
  for (int m = 0; m < 3; ++m)
    for (int j = 0; j < kTableRes; ++j)
      for (int i = 0; i < kTableRes; ++i) {
        const double a = static_cast<double>(i) / (kTableRes - 1),
                     b = static_cast<double>(j) / (kTableRes - 1);
        auto fitAt = [&](int k, Coeffs& c) {
          const double z = zNodes_[static_cast<size_t>(k)];
          glm::dvec3 rgb;
          rgb[m] = z;
          rgb[(m + 1) % 3] = a * z;
          rgb[(m + 2) % 3] = b * z;
          refine(rgb, c, 30, 1e-7, 0.0);
          table_[index(m, k, j, i)] = {static_cast<float>(c[0]), static_cast<float>(c[1]),
                                       static_cast<float>(c[2])};
        };
        Coeffs c{0.0, 0.0, 0.0};
        for (int k = first; k < kTableRes; ++k) fitAt(k, c);
        c = {0.0, 0.0, 0.0};
        for (int k = first - 1; k >= 0; --k) fitAt(k, c);
      }
}

ReflectanceUplift::Coeffs ReflectanceUplift::start(const glm::dvec3& rgb) const {
  const int m = rgb.x >= rgb.y ? (rgb.x >= rgb.z ? 0 : 2) : (rgb.y >= rgb.z ? 1 : 2);
  const double z = rgb[m];
  const double a = rgb[(m + 1) % 3] / z * (kTableRes - 1),
               b = rgb[(m + 2) % 3] / z * (kTableRes - 1);
  const int k = std::clamp(
      static_cast<int>(std::upper_bound(zNodes_.begin(), zNodes_.end(), z) - zNodes_.begin()) - 1,
      0, kTableRes - 2);
  const double fz =
      std::clamp((z - zNodes_[static_cast<size_t>(k)]) /
                     (zNodes_[static_cast<size_t>(k) + 1] - zNodes_[static_cast<size_t>(k)]),
                 0.0, 1.0);
  const int i = std::clamp(static_cast<int>(a), 0, kTableRes - 2),
            j = std::clamp(static_cast<int>(b), 0, kTableRes - 2);
  const double fa = a - i, fb = b - j;
  Coeffs c{};
  for (size_t d = 0; d < 3; ++d) {
    auto at = [&](int kk, int jj, int ii) {
      return static_cast<double>(table_[index(m, kk, jj, ii)][d]);
    };
    auto bilinear = [&](int kk) {
      return (1.0 - fb) * ((1.0 - fa) * at(kk, j, i) + fa * at(kk, j, i + 1)) +
             fb * ((1.0 - fa) * at(kk, j + 1, i) + fa * at(kk, j + 1, i + 1));
    };
    c[d] = (1.0 - fz) * bilinear(k) + fz * bilinear(k + 1);
  }
  return c;
}

SigmoidPolynomial ReflectanceUplift::fit(glm::dvec3 rgb) const {
  for (int i = 0; i < 3; ++i) rgb[i] = rgb[i] > 0.0 ? std::min(rgb[i], 1.0) : 0.0;  // NaN → 0
  if (rgb.x == rgb.y && rgb.y == rgb.z) return {0.0, 0.0, inverseSigmoid(rgb.x)};
  Coeffs c = start(rgb);
  if (!std::isfinite(c[0] + c[1] + c[2])) c = {0.0, 0.0, 0.0};
  refine(rgb, c, kMaxSteps, kTolerance, kTrusted);
  return {c[0], c[1], c[2]};
}

}  // namespace camsim
