// MirrorMaterial (integrator/materials/mirror_material.cpp):
//  - the path weight f·|cos θi|/pdf equals the reflectance k(λ) (to one rounding) at every
//    angle, including grazing cos θ = 1e-6 and the back side;
//  - wi is the mirror image of wo, unit length, on wo's side; the sample is a delta lobe;
//  - f() and pdf() are 0; the harness's χ² sees only delta samples and ∫ pdf = 0;
//  - a black mirror reflects nothing; exactly grazing wo (cos θ = 0) gives no sample.
#include "integrator/materials/mirror_material.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/integrator/bsdf_check.h"

namespace camsim {
namespace {

using bsdfcheck::direction;

Spectrum ramp() {
  const double lambdaNm[] = {360.0, 830.0}, values[] = {0.1, 0.9};
  return Spectrum::fromSamples(lambdaNm, values, Extrapolation::kClamp);
}

TEST(MirrorMaterial, PathWeightIsTheReflectanceExactly) {
  const MirrorMaterial m(ramp());
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.21f);
  const SampledSpectrum k = sampleSpectrum(ramp(), lambda);
  for (double z : {1.0, 0.7, 0.2, 1e-3, 1e-6, -1e-6, -0.4, -1.0}) {
    const glm::vec3 wo = direction(z, 0.9);
    const auto s = m.sample(wo, 0.3f, {0.6f, 0.1f}, lambda, {});
    ASSERT_TRUE(s.has_value()) << z;
    EXPECT_TRUE(s->specular);
    EXPECT_FALSE(s->transmission);
    EXPECT_EQ(s->pdf, 1.0f);
    EXPECT_EQ(s->wi.x, -wo.x);
    EXPECT_EQ(s->wi.y, -wo.y);
    EXPECT_EQ(s->wi.z, wo.z);
    for (int c = 0; c < kWavelengthSamples; ++c) {
      ASSERT_TRUE(std::isfinite(s->f[c])) << z;
      const float weight = s->f[c] * std::abs(s->wi.z) / s->pdf;
      EXPECT_NEAR(weight, k[c], 2e-7f * k[c]) << z;  // k/c·c: at most one rounding each way
    }
    EXPECT_TRUE(m.f(wo, s->wi, lambda, {}).isZero());
    EXPECT_EQ(m.pdf(wo, s->wi, lambda, {}), 0.0f);
  }
  EXPECT_FALSE(m.hasNonSpecular());
  EXPECT_TRUE(m.reflects());
}

TEST(MirrorMaterial, HarnessSeesOnlyTheDeltaLobe) {
  const MirrorMaterial m(Spectrum::constant(0.8));
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.5f);
  bsdfcheck::ChiSquareOptions o;
  o.sampleCount = 2000;
  const auto chi = bsdfcheck::chiSquare(m, direction(0.6, 1.0), lambda, {}, o);
  EXPECT_EQ(chi.delta, o.sampleCount);
  EXPECT_EQ(chi.invalid, 0);
  EXPECT_EQ(chi.pdfIntegral, 0.0);
  EXPECT_TRUE(chi.accepted) << chi.report;
  bsdfcheck::AlbedoOptions a;
  a.sampleCount = 100;
  for (double z : {1.0, 1e-6}) {
    const auto albedo = bsdfcheck::albedo(m, direction(z, 0.0), lambda, {}, a);
    EXPECT_EQ(albedo.nonFinite, 0);
    EXPECT_NEAR(albedo.mean[0], 0.8, 1e-6);
    EXPECT_EQ(albedo.quadrature[0], 0.0);  // nothing outside the delta
  }
}

TEST(MirrorMaterial, BlackAndExactlyGrazing) {
  const MirrorMaterial black(Spectrum::constant(0.0));
  EXPECT_FALSE(black.reflects());
  const MirrorMaterial m(Spectrum::constant(0.5));
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.5f);
  EXPECT_FALSE(m.sample({1.0f, 0.0f, 0.0f}, 0.5f, {0.5f, 0.5f}, lambda, {}).has_value());
}

}  // namespace
}  // namespace camsim
