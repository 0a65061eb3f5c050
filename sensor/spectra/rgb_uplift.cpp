#include "sensor/spectra/rgb_uplift.h"

#include <algorithm>
#include <cmath>

#include <glm/matrix.hpp>

#include "sensor/base/check.h"
#include "sensor/spectra/cie.h"

namespace camsim {
namespace {

double sigmoid(double x) {
  if (std::isinf(x)) return x > 0.0 ? 1.0 : 0.0;
  return 0.5 + x / (2.0 * std::sqrt(1.0 + x * x));
}

glm::dvec3 rgbOf(const SigmoidPolynomial& p, const RgbColorSpace& space) {
  return reflectanceToRgb(p.toSpectrum(), space);
}

// One damped Gauss–Newton solve towards target, starting from p. Returns the residual norm.
double refine(SigmoidPolynomial& p, const glm::dvec3& target, const RgbColorSpace& space) {
  double lambda = 1e-3;  // Levenberg–Marquardt damping
  glm::dvec3 r = rgbOf(p, space) - target;
  double err = glm::dot(r, r);
  for (int iter = 0; iter < 50 && err > 1e-14; ++iter) {
    glm::dmat3 J;  // J[k] = ∂r/∂c_k (column k)
    double* c[3] = {&p.c0, &p.c1, &p.c2};
    for (int k = 0; k < 3; ++k) {
      const double h = 1e-4 * std::max(1.0, std::abs(*c[k]));
      const double saved = *c[k];
      *c[k] = saved + h;
      const glm::dvec3 plus = rgbOf(p, space);
      *c[k] = saved - h;
      const glm::dvec3 minus = rgbOf(p, space);
      *c[k] = saved;
      J[k] = (plus - minus) / (2.0 * h);
    }
    const glm::dmat3 JtJ = glm::transpose(J) * J;
    const glm::dvec3 Jtr = glm::transpose(J) * r;
    bool improved = false;
    for (int tries = 0; tries < 12 && !improved; ++tries) {
      glm::dmat3 A = JtJ;
      for (int k = 0; k < 3; ++k) A[k][k] += lambda * (JtJ[k][k] + 1e-12);
      const glm::dvec3 delta = -(glm::inverse(A) * Jtr);
      SigmoidPolynomial q{p.c0 + delta[0], p.c1 + delta[1], p.c2 + delta[2]};
      const glm::dvec3 rq = rgbOf(q, space) - target;
      const double eq = glm::dot(rq, rq);
      if (std::isfinite(eq) && eq < err) {
        p = q;
        r = rq;
        err = eq;
        lambda = std::max(lambda * 0.3, 1e-9);
        improved = true;
      } else {
        lambda *= 10.0;
      }
    }
    if (!improved) break;
  }
  return std::sqrt(err);
}

}  // namespace

double SigmoidPolynomial::operator()(double lambdaNm) const {
  const double t = (lambdaNm - kLambdaMinNm) / (kLambdaMaxNm - kLambdaMinNm);
  return sigmoid((c0 * t + c1) * t + c2);
}

Spectrum SigmoidPolynomial::toSpectrum() const {
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i)
    s.sample(i) = static_cast<float>((*this)(kLambdaMinNm + i));
  return s;
}

glm::dvec3 reflectanceToRgb(const Spectrum& reflectance, const RgbColorSpace& space) {
  return space.fromXyz(reflectanceToXyz(reflectance, space.illuminant()));
}

SigmoidPolynomial fitSigmoidPolynomial(const glm::dvec3& rgb, const RgbColorSpace& space) {
  // c = 0 is the constant ½, whose colour is the space's grey (½, ½, ½) up to the
  // tabulated illuminant's tiny chromaticity offset; walk from there to the target.
  SigmoidPolynomial p;
  const glm::dvec3 start = rgbOf(p, space);
  constexpr int kSteps = 32;
  for (int step = 1; step <= kSteps; ++step) {
    const double f = static_cast<double>(step) / kSteps;
    refine(p, start + f * (rgb - start), space);
  }
  refine(p, rgb, space);
  return p;
}

Spectrum rgbToReflectance(const glm::dvec3& rgb, const RgbColorSpace& space) {
  CAMSIM_CHECK(rgb.x >= 0.0 && rgb.y >= 0.0 && rgb.z >= 0.0 && rgb.x <= 1.0 && rgb.y <= 1.0 &&
               rgb.z <= 1.0);
  if (rgb.x == rgb.y && rgb.y == rgb.z) return Spectrum::constant(rgb.x);
  return fitSigmoidPolynomial(rgb, space).toSpectrum();
}

Spectrum rgbToEmissionShape(const glm::dvec3& rgb, const RgbColorSpace& space) {
  const double m = std::max({rgb.x, rgb.y, rgb.z});
  CAMSIM_CHECK(m > 0.0 && rgb.x >= 0.0 && rgb.y >= 0.0 && rgb.z >= 0.0);
  const double norm = innerProduct(space.illuminant(), Cie1931::get().y);
  return rgbToReflectance(rgb / (2.0 * m), space) * space.illuminant() * (2.0 * m / norm);
}

}  // namespace camsim
