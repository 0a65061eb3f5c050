// Tests of the BSDF test harness itself (tests/integrator/bsdf_check.h): the p-value
// function against closed forms, and the χ²/pdf/albedo/reciprocity checks on the
// Lambertian material (must pass) and on deliberately broken materials (must be caught).
#include "tests/integrator/bsdf_check.h"

#include <gtest/gtest.h>

#include <cmath>

#include "integrator/geometry/math.h"
#include "integrator/materials/diffuse_material.h"

namespace camsim {
namespace {

using bsdfcheck::direction;

// A Lambertian whose sampler is cosine-weighted but whose pdf claims uniform hemisphere
// sampling: a sample()/pdf() mismatch that the χ² test must reject.
class WrongPdfMaterial final : public Material {
 public:
  SampledSpectrum f(const glm::vec3& wo, const glm::vec3& wi, const SampledWavelengths&,
                    const BsdfContext&) const override {
    return SampledSpectrum(wo.z * wi.z > 0.0f ? kInvPi : 0.0f);
  }
  std::optional<BsdfSample> sample(const glm::vec3& wo, float, glm::vec2 u,
                                   const SampledWavelengths& lambda,
                                   const BsdfContext& ctx) const override {
    glm::vec3 wi = sampleCosineHemisphere(u);
    if (wo.z < 0.0f) wi.z = -wi.z;
    BsdfSample s;
    s.wi = wi;
    s.f = f(wo, wi, lambda, ctx);
    s.pdf = pdf(wo, wi, lambda, ctx);
    return s;
  }
  float pdf(const glm::vec3& wo, const glm::vec3& wi, const SampledWavelengths&,
            const BsdfContext&) const override {
    return wo.z * wi.z > 0.0f ? 0.5f * kInvPi : 0.0f;
  }
  SurfaceAov aov(const SampledWavelengths&, const BsdfContext&) const override { return {}; }
};

TEST(BsdfCheck, PValueMatchesClosedForms) {
  // dof 2: Q(1, x/2) = exp(−x/2); dof 1: Q(1/2, x/2) = erfc(√(x/2)).
  for (double x : {0.1, 1.0, 3.0, 10.0, 40.0}) {
    EXPECT_NEAR(bsdfcheck::chiSquarePValue(x, 2), std::exp(-0.5 * x), 1e-12);
    EXPECT_NEAR(bsdfcheck::chiSquarePValue(x, 1), std::erfc(std::sqrt(0.5 * x)), 1e-12);
  }
  // χ² with 199 dof: median ≈ 198.3 (p ≈ 0.5); 99th percentile ≈ 248.3.
  EXPECT_NEAR(bsdfcheck::chiSquarePValue(198.33, 199), 0.5, 2e-3);
  EXPECT_NEAR(bsdfcheck::chiSquarePValue(248.33, 199), 0.01, 1e-3);
}

TEST(BsdfCheck, QuadratureIntegratesTheSphere) {
  const double area = bsdfcheck::integrateSphere([](const glm::vec3&) { return 1.0; }, 10, 20, {});
  EXPECT_NEAR(area, 4.0 * M_PI, 1e-6);
  const double cosine = bsdfcheck::integrateSphere(
      [](const glm::vec3& w) { return std::max(0.0, static_cast<double>(w.z)); }, 10, 20, {});
  EXPECT_NEAR(cosine, M_PI, 1e-6);
}

TEST(BsdfCheck, LambertianPassesEveryCheck) {
  const DiffuseMaterial m(Spectrum::constant(0.8));
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.3f);
  const BsdfContext ctx;
  for (double z : {1.0, 0.5, -0.3, 1e-6}) {
    const glm::vec3 wo = direction(z, 0.7);
    bsdfcheck::ChiSquareOptions o;
    o.testCount = 4;
    const auto chi = bsdfcheck::chiSquare(m, wo, lambda, ctx, o);
    EXPECT_TRUE(chi.accepted) << chi.report;
    EXPECT_EQ(chi.pdfMismatch, 0);
    EXPECT_EQ(chi.fMismatch, 0);
    EXPECT_NEAR(chi.pdfIntegral, 1.0, 1e-5);
    const auto a = bsdfcheck::albedo(m, wo, lambda, ctx);
    EXPECT_EQ(a.nonFinite, 0);
    for (int c = 0; c < kWavelengthSamples; ++c) {
      EXPECT_NEAR(a.mean[static_cast<std::size_t>(c)], 0.8, 1e-5);  // f cos/pdf = ρ exactly
      EXPECT_NEAR(a.quadrature[static_cast<std::size_t>(c)], 0.8, 1e-5);
    }
  }
  const auto rec = bsdfcheck::reciprocity(m, SampledWavelengths::sampleUniform(0.3f), {});
  EXPECT_EQ(rec.maxRelError, 0.0);
  EXPECT_GT(rec.nonZeroPairs, 1000);
}

TEST(BsdfCheck, ChiSquareRejectsAWrongPdf) {
  const WrongPdfMaterial m;
  const auto chi =
      bsdfcheck::chiSquare(m, direction(0.8, 0.0), SampledWavelengths::sampleUniform(0.5f), {});
  EXPECT_FALSE(chi.accepted) << chi.report;
  EXPECT_LT(chi.pValue, 1e-10);
  EXPECT_EQ(chi.pdfMismatch, 0);  // sample() reports the (wrong) pdf() consistently
}

}  // namespace
}  // namespace camsim
