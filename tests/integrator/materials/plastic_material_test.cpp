// PlasticMaterial (integrator/materials/plastic_material.cpp) through the BSDF harness:
//  - χ² of the mixture sampler against the mixture pdf over the full sphere (rough GGX and
//    Beckmann, Smith and V-groove, wo on both sides), and for the smooth layer, where the
//    delta samples must make up exactly 1 − ∫ pdf dω;
//  - ∫ pdf dω: the smooth layer's equals the diffuse choice probability kd ρmax/(kd ρmax + ks);
//  - reciprocity;
//  - energy: ρ = 1, ks = 0.1: smooth layer gives path weight kd ρ + ks = 1 on every sample;
//    rough layer: albedo = kd ρ + ks · (specular albedo) ≤ 1, MC = quadrature + delta part;
//  - finite at grazing cos θ = 1e-6 and α = 1e-4.
#include "integrator/materials/plastic_material.h"

#include <gtest/gtest.h>

#include <cstdio>

#include <memory>
#include <string>

#include "tests/integrator/bsdf_check.h"

namespace camsim {
namespace {

using bsdfcheck::direction;

std::unique_ptr<PlasticMaterial> plastic(double rho, float alpha, float ks = 0.1f,
                                         MicrofacetDistribution d = MicrofacetDistribution::kGgx,
                                         MaskingModel mask = MaskingModel::kSmith) {
  PlasticParameters p;
  p.reflectance = std::make_unique<ConstantSpectrumTexture>(Spectrum::constant(rho));
  p.roughness = std::make_unique<ConstantFloatTexture>(alpha);
  p.specularWeight = ks;
  p.distribution = d;
  p.masking = mask;
  return std::make_unique<PlasticMaterial>(std::move(p));
}

const SampledWavelengths kPlasticLambda = SampledWavelengths::sampleUniform(0.61f);

TEST(PlasticMaterial, SamplesFollowPdfOverTheSphere) {
  struct Case {
    MicrofacetDistribution d;
    MaskingModel mask;
    float alpha, ks;
    double rho;
  };
  const Case cases[] = {
      {MicrofacetDistribution::kGgx, MaskingModel::kSmith, 0.05f, 0.1f, 0.5},
      {MicrofacetDistribution::kGgx, MaskingModel::kSmith, 0.3f, 0.5f, 0.8},
      {MicrofacetDistribution::kBeckmann, MaskingModel::kSmith, 0.1f, 0.3f, 0.2},
      {MicrofacetDistribution::kGgx, MaskingModel::kVGroove, 0.3f, 0.3f, 0.5},
      {MicrofacetDistribution::kBeckmann, MaskingModel::kVGroove, 0.5f, 0.1f, 1.0},
      {MicrofacetDistribution::kGgx, MaskingModel::kSmith, 0.0f, 0.2f, 0.6},  // smooth
  };
  const double zs[] = {1.0, 0.5, 0.1, -0.6};
  constexpr int tests = 6 * 4;
  for (const Case& c : cases)
    for (double z : zs) {
      const auto m = plastic(c.rho, c.alpha, c.ks, c.d, c.mask);
      bsdfcheck::ChiSquareOptions o;
      o.testCount = tests;
      o.sampleCount = 50000;
      const auto r = bsdfcheck::chiSquare(*m, direction(z, 0.8), kPlasticLambda, {}, o);
      const std::string what = "α " + std::to_string(c.alpha) + " ks " + std::to_string(c.ks) +
                               " z " + std::to_string(z);
      EXPECT_TRUE(r.accepted) << what << "\n" << r.report;
      EXPECT_EQ(r.pdfMismatch, 0) << what;
      EXPECT_EQ(r.fMismatch, 0) << what;
      const double ks = static_cast<double>(c.ks);
      const double pd = (1.0 - ks) * c.rho / ((1.0 - ks) * c.rho + ks);
      if (c.alpha == 0.0f) {
        EXPECT_NEAR(r.pdfIntegral, pd, 1e-5) << what;  // the diffuse lobe only
        EXPECT_GT(r.delta, 0) << what;
      } else {
        const double p = static_cast<double>(r.nonDelta) / o.sampleCount;
        const double sigma = std::sqrt(std::max(p * (1.0 - p), 1e-4) / o.sampleCount);
        EXPECT_NEAR(r.pdfIntegral, p, 5.0 * sigma + 1e-4) << what;
        EXPECT_GE(r.pdfIntegral, pd - 1e-5) << what;  // the diffuse part never fails
        EXPECT_EQ(r.delta, 0) << what;
      }
    }
}

TEST(PlasticMaterial, Reciprocal) {
  for (MicrofacetDistribution d : {MicrofacetDistribution::kGgx, MicrofacetDistribution::kBeckmann})
    for (MaskingModel mask : {MaskingModel::kSmith, MaskingModel::kVGroove})
      for (float alpha : {0.0f, 0.1f, 0.7f}) {
        const auto m = plastic(0.4, alpha, 0.3f, d, mask);
        const auto r = bsdfcheck::reciprocity(*m, kPlasticLambda, {});
        EXPECT_LT(r.maxRelError, 1e-5) << alpha;
        EXPECT_GT(r.nonZeroPairs, 1000);
        EXPECT_EQ(r.nonFinite, 0);
      }
}

// ρ = 1, ks = 0.1, smooth: diffuse samples weigh kd ρ/pd = kd ρ + ks, delta samples
// ks/(1 − pd) = kd ρ + ks: every sample carries exactly 1.
TEST(PlasticMaterial, SmoothWhiteFurnaceIsExactlyOne) {
  const auto m = plastic(1.0, 0.0f);
  for (double z : {1.0, 0.5, 1e-3, 1e-6, -0.3}) {
    bsdfcheck::AlbedoOptions o;
    o.sampleCount = 5000;
    const auto a = bsdfcheck::albedo(*m, direction(z, 0.2), kPlasticLambda, {}, o);
    EXPECT_EQ(a.nonFinite, 0) << z;
    for (std::size_t c = 0; c < a.mean.size(); ++c) {
      EXPECT_NEAR(a.mean[c], 1.0, 1e-5) << z;
      EXPECT_NEAR(a.quadrature[c], 0.9, 1e-4) << z;  // kd ρ: the non-delta part
    }
    EXPECT_LE(a.maxWeight, 1.0 + 1e-5);
  }
}

// Rough layer: albedo = kd ρ + ks E_spec, E_spec ≤ 1 the lobe's own single-scattering
// albedo, so the total stays ≤ 1; MC against quadrature within 5σ + 1e-3.
TEST(PlasticMaterial, RoughWhiteFurnaceConservesEnergy) {
  for (MicrofacetDistribution d : {MicrofacetDistribution::kGgx, MicrofacetDistribution::kBeckmann})
    for (float alpha : {0.05f, 0.3f, 1.0f})
      for (double z : {1.0, 0.5, 0.1}) {
        const auto m = plastic(1.0, alpha, 0.1f, d);
        bsdfcheck::AlbedoOptions o;
        o.sampleCount = 20000;
        o.cosThetaBins = 4;
        o.phiBins = 8;
        o.quadratureOptions.minDepth = 4;
        const auto a = bsdfcheck::albedo(*m, direction(z, 1.1), kPlasticLambda, {}, o);
        const std::string what = "α " + std::to_string(alpha) + " z " + std::to_string(z);
        std::printf(
            "[measured] plastic ρ 1, ks 0.1, %s α %.2f cosθo %.1f: albedo MC %.4f, quadrature "
            "%.4f\n",
            d == MicrofacetDistribution::kGgx ? "ggx" : "beckmann", static_cast<double>(alpha), z,
            a.mean[0], a.quadrature[0]);
        EXPECT_EQ(a.nonFinite, 0) << what;
        EXPECT_EQ(a.unresolvedCells, 0) << what;
        EXPECT_LE(a.mean[0], 1.0 + 5.0 * a.stdErr[0]) << what;
        EXPECT_LE(a.quadrature[0], 1.0 + 1e-4) << what;
        EXPECT_GE(a.quadrature[0], 0.9 - 1e-4) << what;  // at least the diffuse kd ρ
        EXPECT_NEAR(a.mean[0], a.quadrature[0], 5.0 * a.stdErr[0] + 1e-3) << what;
      }
}

TEST(PlasticMaterial, FiniteAtGrazingAndSharpestLobe) {
  for (float alpha : {MicrofacetModel::kSmoothAlpha, 0.5f})
    for (MaskingModel mask : {MaskingModel::kSmith, MaskingModel::kVGroove}) {
      const auto m = plastic(0.7, alpha, 0.3f, MicrofacetDistribution::kGgx, mask);
      for (double z : {1e-6, -1e-6, 1.0}) {
        bsdfcheck::AlbedoOptions o;
        o.sampleCount = 4000;
        o.quadrature = false;
        const auto a = bsdfcheck::albedo(*m, direction(z, 0.4), kPlasticLambda, {}, o);
        EXPECT_EQ(a.nonFinite, 0) << alpha << " " << z;
        EXPECT_LE(a.mean[0], 1.0 + 5.0 * a.stdErr[0]) << alpha << " " << z;
      }
    }
  const auto black = plastic(0.0, 0.2f, 0.0f);
  EXPECT_FALSE(black->reflects());
  EXPECT_FALSE(
      black->sample(direction(0.5, 0.0), 0.5f, {0.5f, 0.5f}, kPlasticLambda, {}).has_value());
}

}  // namespace
}  // namespace camsim
