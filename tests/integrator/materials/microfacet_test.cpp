// MicrofacetModel (integrator/materials/microfacet.cpp):
//  - hand values of D at the pole and of V-groove G;
//  - normalisation ∫ D(m) cos θm dωm = 1 and, for visible normals, ∫ D_ω(m) dωm = 1
//    (which holds only with the exact Smith Λ), by adaptive quadrature;
//  - sampleWm distributed as pdf(w, m) (χ² over the sphere of m), its normals facing w and
//    Smith reflection weights ≤ 1 (visible normals, both distributions);
//  - robustness: α from kSmoothAlpha to 1, directions at the pole and at cos θ ∈ {1e-6, 0}
//    give finite, non-negative values and unit normals.
#include "integrator/materials/microfacet.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include <glm/vec3.hpp>

#include "integrator/geometry/math.h"
#include "integrator/materials/fresnel.h"  // camsim::reflect (glm::reflect has the opposite sign)
#include "integrator/sampling/rng.h"
#include "tests/integrator/bsdf_check.h"

namespace camsim {
namespace {

using bsdfcheck::direction;

constexpr MicrofacetDistribution kMicrofacetDistributions[] = {MicrofacetDistribution::kGgx,
                                                               MicrofacetDistribution::kBeckmann};

std::string distributionName(MicrofacetDistribution d) {
  return d == MicrofacetDistribution::kGgx ? "ggx" : "beckmann";
}

bsdfcheck::QuadratureOptions fineQuadrature() {
  bsdfcheck::QuadratureOptions q;
  q.minDepth = 4;
  return q;
}

// Exposes sampleWm/pdf as a "material" so that the χ² harness can test the sampler.
class NormalSampler final : public Material {
 public:
  explicit NormalSampler(const MicrofacetModel& m) : m_(m) {}
  SampledSpectrum f(const glm::vec3&, const glm::vec3&, const SampledWavelengths&,
                    const BsdfContext&) const override {
    return SampledSpectrum(1.0f);
  }
  std::optional<BsdfSample> sample(const glm::vec3& w, float, glm::vec2 u,
                                   const SampledWavelengths&, const BsdfContext&) const override {
    BsdfSample s;
    s.wi = m_.sampleWm(w, u);
    s.f = SampledSpectrum(1.0f);
    s.pdf = m_.pdf(w, s.wi);
    return s;
  }
  float pdf(const glm::vec3& w, const glm::vec3& wm, const SampledWavelengths&,
            const BsdfContext&) const override {
    return m_.pdf(w, wm);
  }
  SurfaceAov aov(const SampledWavelengths&, const BsdfContext&) const override { return {}; }

 private:
  MicrofacetModel m_;
};

TEST(Microfacet, DistributionAtThePoleIsOneOverPiAlphaXAlphaY) {
  for (MicrofacetDistribution d : kMicrofacetDistributions) {
    const MicrofacetModel iso(d, MaskingModel::kSmith, 0.3f, 0.3f);
    EXPECT_NEAR(iso.D({0.0f, 0.0f, 1.0f}), 1.0f / (kPi * 0.09f), 1e-5f) << distributionName(d);
    const MicrofacetModel aniso(d, MaskingModel::kSmith, 0.2f, 0.5f);
    EXPECT_NEAR(aniso.D({0.0f, 0.0f, 1.0f}), 1.0f / (kPi * 0.1f), 1e-5f) << distributionName(d);
    EXPECT_EQ(iso.D({0.0f, 0.6f, -0.8f}), 0.0f);  // no normals below the surface
    EXPECT_EQ(iso.lambda({0.0f, 0.0f, 1.0f}), 0.0f);
  }
  // GGX at tan θ = α (θ = atan 0.3): D = 1/(π α² cos⁴θ · 4).
  const MicrofacetModel ggx(MicrofacetDistribution::kGgx, MaskingModel::kSmith, 0.3f, 0.3f);
  const float c = std::cos(std::atan(0.3f));
  const glm::vec3 m(std::sqrt(1.0f - c * c), 0.0f, c);
  EXPECT_NEAR(ggx.D(m) / (1.0f / (kPi * 0.09f * c * c * c * c * 4.0f)), 1.0f, 1e-5f);
}

TEST(Microfacet, LambdaMatchesTheTanThetaFormulas) {
  const float theta = 1.2f, alpha = 0.4f;
  const glm::vec3 w(std::sin(theta), 0.0f, std::cos(theta));
  const double a2t2 = 0.16 * std::pow(std::tan(1.2), 2.0);
  const MicrofacetModel ggx(MicrofacetDistribution::kGgx, MaskingModel::kSmith, alpha, alpha);
  EXPECT_NEAR(ggx.lambda(w), (-1.0 + std::sqrt(1.0 + a2t2)) / 2.0, 1e-5);
  const MicrofacetModel beckmann(MicrofacetDistribution::kBeckmann, MaskingModel::kSmith, alpha,
                                 alpha);
  const double a = 1.0 / (0.4 * std::tan(1.2));
  EXPECT_NEAR(beckmann.lambda(w), (std::exp(-a * a) / (a * std::sqrt(M_PI)) - std::erfc(a)) / 2.0,
              1e-5);
}

TEST(Microfacet, VGrooveHandValues) {
  const MicrofacetModel m(MicrofacetDistribution::kGgx, MaskingModel::kVGroove, 0.3f, 0.3f);
  const glm::vec3 z(0.0f, 0.0f, 1.0f);
  EXPECT_FLOAT_EQ(m.G(z, z, z), 1.0f);
  // wm at 30°, wo at 80° on the same side (50° from wm), wi its mirror image (at −20°):
  // G = min(1, 2 cos30° cos80°/cos50°, 2 cos30° cos20°/cos50°) = 2·0.866025·0.173648/0.642788.
  const glm::vec3 wm(0.5f, 0.0f, std::sqrt(0.75f));
  const float t = 80.0f * kPi / 180.0f;
  const glm::vec3 wo(std::sin(t), 0.0f, std::cos(t));
  const glm::vec3 wi = glm::normalize(reflect(wo, wm));
  EXPECT_NEAR(wi.x, -std::sin(20.0f * kPi / 180.0f), 1e-6f);
  EXPECT_NEAR(m.G(wo, wi, wm), 0.467911f, 1e-5f);
  EXPECT_FLOAT_EQ(m.G(wo, wi, wm), m.G(wi, wo, wm));
}

// ∫ D(m) cos θm dωm = 1, down to α = kSmoothAlpha = 1e-4: the peak sits at the pole,
// where the quadrature's θ panels are graded down to 1/4096 of the cell (measured
// |error| ≤ 4e-7 at α = 1e-4 and 1e-3). A narrow lobe away from the pole could not be
// integrated this way; D's peak is always at the pole.
TEST(Microfacet, ProjectedAreaIsNormalised) {
  const std::pair<float, float> alphas[] = {{1e-4f, 1e-4f}, {1e-3f, 1e-3f}, {0.01f, 0.01f},
                                            {0.1f, 0.1f},   {0.5f, 0.5f},   {1.0f, 1.0f},
                                            {0.1f, 0.4f},   {0.03f, 0.6f},  {2e-3f, 1e-3f}};
  for (MicrofacetDistribution d : kMicrofacetDistributions)
    for (auto [ax, ay] : alphas) {
      const MicrofacetModel m(d, MaskingModel::kSmith, ax, ay);
      const double integral = bsdfcheck::integrateSphere(
          [&](const glm::vec3& wm) {
            return static_cast<double>(m.D(wm)) * std::max(0.0, static_cast<double>(wm.z));
          },
          10, 20, fineQuadrature());
      EXPECT_NEAR(integral, 1.0, 1e-6) << distributionName(d) << " α = " << ax << ", " << ay;
    }
}

// ∫ G1(ω) max(0, ω·m) D(m) / cos θ dωm = 1 for every ω: the defining property of Smith's
// Λ, so this checks the exact Λ (GGX closed form, Beckmann erfc) and pdf().
TEST(Microfacet, VisibleNormalsAreNormalised) {
  const std::pair<float, float> alphas[] = {
      {0.05f, 0.05f}, {0.3f, 0.3f}, {1.0f, 1.0f}, {0.1f, 0.5f}};
  for (MicrofacetDistribution d : kMicrofacetDistributions)
    for (auto [ax, ay] : alphas)
      for (double z : {1.0, 0.5, 0.1, 1e-3}) {
        const MicrofacetModel m(d, MaskingModel::kSmith, ax, ay);
        const glm::vec3 w = direction(z, 0.4);
        const double visible = bsdfcheck::integrateSphere(
            [&](const glm::vec3& wm) {
              // (w·m in double)
              const glm::dvec3 wd(w), md(wm);
              const double dot = std::max(0.0, glm::dot(wd, md));
              return static_cast<double>(m.G1(w)) * dot * static_cast<double>(m.D(wm)) / z;
            },
            10, 20, fineQuadrature());
        // Measured |error| ≤ 4e-7 for z ≥ 0.1; at z = 1e-3 the quadrature misses part of the
        // 1e-3-wide region around the pole where the kink w·m = 0 meets the peak (1e-5).
        EXPECT_NEAR(visible, 1.0, z < 0.01 ? 5e-5 : 2e-6)
            << distributionName(d) << " α = " << ax << ", " << ay << " z = " << z;
      }
}

TEST(Microfacet, SampledNormalsFollowPdf) {
  const std::pair<float, float> alphas[] = {
      {0.05f, 0.05f}, {0.3f, 0.3f}, {1.0f, 1.0f}, {0.1f, 0.4f}};
  const double zs[] = {1.0, 0.5, 0.05, -0.7};
  constexpr int tests = 2 * 4 * 4;
  for (MicrofacetDistribution d : kMicrofacetDistributions)
    for (auto [ax, ay] : alphas)
      for (double z : zs) {
        const NormalSampler s(MicrofacetModel(d, MaskingModel::kSmith, ax, ay));
        bsdfcheck::ChiSquareOptions o;
        o.testCount = tests;
        o.sampleCount = 100000;
        const auto r = bsdfcheck::chiSquare(s, direction(z, 1.0),
                                            SampledWavelengths::sampleUniform(0.5f), {}, o);
        EXPECT_TRUE(r.accepted) << distributionName(d) << " α = " << ax << ", " << ay << "\n"
                                << r.report;
        EXPECT_EQ(r.pdfMismatch, 0);
        EXPECT_NEAR(r.pdfIntegral, 1.0, 1e-3);
      }
}

TEST(Microfacet, FiniteFromSmoothToRoughAndAtGrazing) {
  const float alphas[] = {MicrofacetModel::kSmoothAlpha, 1e-3f, 0.05f, 1.0f, 3.0f};
  const glm::vec3 dirs[] = {{0.0f, 0.0f, 1.0f},
                            {1.0f, 0.0f, 1e-6f},
                            {0.6f, 0.8f, 0.0f},
                            {0.0f, -1.0f, -1e-6f},
                            glm::normalize(glm::vec3(0.3f, -0.2f, 0.9f))};
  const glm::vec2 us[] = {
      {0.0f, 0.0f}, {1.0f - 0x1p-24f, 0.5f}, {0.5f, 1.0f - 0x1p-24f}, {0.3f, 0.7f}};
  for (MicrofacetDistribution d : kMicrofacetDistributions)
    for (MaskingModel mask : {MaskingModel::kSmith, MaskingModel::kVGroove})
      for (float a : alphas)
        for (const glm::vec3& w : dirs) {
          const MicrofacetModel m(d, mask, a, 0.5f * a);
          const float l = m.lambda(w);
          EXPECT_FALSE(std::isnan(l));
          EXPECT_GE(l, 0.0f);
          EXPECT_GE(m.G1(w), 0.0f);
          EXPECT_LE(m.G1(w), 1.0f);
          for (glm::vec2 u : us) {
            const glm::vec3 wm = m.sampleWm(w, u);
            EXPECT_NEAR(glm::length(wm), 1.0f, 1e-5f) << distributionName(d) << " α " << a;
            EXPECT_GT(wm.z, 0.0f);
            const float dv = m.D(wm), pv = m.pdf(w, wm);
            EXPECT_TRUE(std::isfinite(dv) && dv >= 0.0f) << distributionName(d) << " α " << a;
            EXPECT_TRUE(std::isfinite(pv) && pv >= 0.0f) << distributionName(d) << " α " << a;
            for (const glm::vec3& wi : dirs) {
              const float g = m.G(w, wi, wm);
              EXPECT_TRUE(g >= 0.0f && g <= 1.0f) << g;
            }
          }
        }
  // Smooth threshold.
  EXPECT_TRUE(MicrofacetModel(kMicrofacetDistributions[0], MaskingModel::kSmith, 0.0f, 0.0f)
                  .effectivelySmooth());
  EXPECT_FALSE(MicrofacetModel(kMicrofacetDistributions[0], MaskingModel::kSmith, 1e-3f, 0.0f)
                   .effectivelySmooth());
}

// From below, the lobe is the one seen from the other side: w with w.z < 0 is sampled and
// weighted as −w (point reflection, what the dielectric's inside needs), not as w mirrored in
// the plane; the two differ for an anisotropic α and a direction off the principal planes.
TEST(Microfacet, DirectionsBelowAreTakenAsTheirOpposite) {
  const glm::vec3 below = glm::normalize(glm::vec3(0.5f, 0.3f, -0.4f));
  for (MicrofacetDistribution d : kMicrofacetDistributions) {
    const MicrofacetModel m(d, MaskingModel::kSmith, 0.6f, 0.1f);
    for (const glm::vec2 u : {glm::vec2(0.2f, 0.3f), glm::vec2(0.7f, 0.9f)}) {
      const glm::vec3 wm = m.sampleWm(below, u);
      EXPECT_EQ(wm, m.sampleWm(-below, u)) << distributionName(d);
      EXPECT_EQ(m.pdf(below, wm), m.pdf(-below, wm)) << distributionName(d);
    }
    const glm::vec3 mirrored(below.x, below.y, -below.z);
    EXPECT_NE(m.sampleWm(below, glm::vec2(0.2f, 0.3f)), m.sampleWm(mirrored, glm::vec2(0.2f, 0.3f)))
        << distributionName(d);
  }
}

// Visible normals: every sampled normal faces w, and a Smith reflection's weight
// f cosθi / pdf = G(wo, wi)/G1(wo) is at most 1 — down to grazing wo, where sampling D cos θm
// (Beckmann's sampler before) gives back-facing normals and weights far above 1.
TEST(Microfacet, SampledNormalsFaceWAndSmithWeightsStayAtMostOne) {
  const std::pair<float, float> alphas[] = {
      {0.05f, 0.05f}, {0.3f, 0.3f}, {1.0f, 1.0f}, {0.2f, 0.6f}};
  for (MicrofacetDistribution d : kMicrofacetDistributions)
    for (auto [ax, ay] : alphas)
      for (double z : {1.0, 0.5, 0.1, 0.01, 1e-4}) {
        const MicrofacetModel m(d, MaskingModel::kSmith, ax, ay);
        const glm::vec3 wo = direction(z, 0.7);
        int backFacing = 0, overweight = 0, failed = 0;
        double largest = 0.0;
        constexpr int n = 64;
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j) {
            const glm::vec2 u((i + 0.5f) / n, (j + 0.5f) / n);
            const glm::vec3 wm = m.sampleWm(wo, u);
            if (!(glm::dot(wo, wm) > 0.0f)) ++backFacing;
            const auto s = m.sampleReflection(wo, u);
            if (!s) continue;
            const MicrofacetModel::Reflection r = m.reflection(wo, s->wi, s->wm);
            if (!(r.pdf > 0.0f)) {
              ++failed;
              continue;
            }
            const double weight = static_cast<double>(r.f * s->wi.z / r.pdf);
            largest = std::max(largest, weight);
            if (weight > 1.0 + 1e-4) ++overweight;
          }
        const std::string what = distributionName(d) + " α " + std::to_string(ax) + "," +
                                 std::to_string(ay) + " cos " + std::to_string(z);
        EXPECT_EQ(backFacing, 0) << what;
        EXPECT_EQ(overweight, 0) << what << " largest weight " << largest;
        EXPECT_EQ(failed, 0) << what;
      }
}

// Random roughness (log-uniform 1e-4 … 3, anisotropic), directions down to 1e-7 from
// grazing and numbers including the ends of [0, 1): every sampled normal is a finite unit
// vector facing up with a finite pdf (the visible-slope inversion must not reach erf⁻¹(±1)).
TEST(Microfacet, SamplingStaysFiniteOverRandomHardCases) {
  Pcg32 rng(2024, 7);
  const float ends[] = {0.0f, 1e-7f, 0.5f, 1.0f - 0x1p-24f};
  for (MicrofacetDistribution d : kMicrofacetDistributions)
    for (int i = 0; i < 50000; ++i) {
      const float ax = std::pow(10.0f, -4.0f + 4.5f * rng.uniform());
      const float ay = std::pow(10.0f, -4.0f + 4.5f * rng.uniform());
      const float z = (rng.uniform() < 0.3f ? 1e-7f * rng.uniform() : rng.uniform()) *
                      (rng.uniform() < 0.5f ? 1.0f : -1.0f);
      const glm::vec3 w = direction(z, 2.0 * M_PI * static_cast<double>(rng.uniform()));
      const glm::vec2 u(i % 5 == 0 ? ends[i / 5 % 4] : rng.uniform(),
                        i % 7 == 0 ? ends[i / 7 % 4] : rng.uniform());
      const MicrofacetModel m(d, MaskingModel::kSmith, ax, ay);
      const glm::vec3 wm = m.sampleWm(w, u);
      ASSERT_TRUE(std::isfinite(wm.x) && std::isfinite(wm.y) && std::isfinite(wm.z))
          << distributionName(d) << " α " << ax << "," << ay << " z " << z << " u " << u.x << ","
          << u.y;
      ASSERT_NEAR(glm::length(wm), 1.0f, 1e-5f);
      ASSERT_GT(wm.z, 0.0f);
      const float p = m.pdf(w, wm);
      ASSERT_TRUE(std::isfinite(p) && p >= 0.0f)
          << distributionName(d) << " α " << ax << " z " << z;
    }
}

// The half-vector reflection shared by the conductor and the plastic's specular lobe:
// f = D G / (4 cosθo cosθi) and pdf = pdf(wo, wm) / (4 wo·wm) at a hand-checked configuration;
// nothing for a back-facing normal; sampleReflection's wi is wo mirrored about its wm.
TEST(Microfacet, ReflectionIsTheHalfVectorFormula) {
  const MicrofacetModel m(MicrofacetDistribution::kGgx, MaskingModel::kSmith, 0.3f, 0.3f);
  const glm::vec3 wo = glm::normalize(glm::vec3(0.3f, 0.1f, 0.9f));
  const glm::vec3 wi = glm::normalize(glm::vec3(-0.5f, 0.2f, 0.7f));
  const glm::vec3 wm = halfVector(wo, wi);
  const MicrofacetModel::Reflection r = m.reflection(wo, wi, wm);
  EXPECT_FLOAT_EQ(r.f, m.D(wm) * m.G(wo, wi, wm) / (4.0f * wo.z * wi.z));
  EXPECT_FLOAT_EQ(r.pdf, m.pdf(wo, wm) / (4.0f * glm::dot(wo, wm)));
  EXPECT_GT(r.f, 0.0f);
  const MicrofacetModel::Reflection none = m.reflection(wo, wi, -wm);
  EXPECT_EQ(none.f, 0.0f);
  EXPECT_EQ(none.pdf, 0.0f);
  const std::optional<MicrofacetModel::ReflectionSample> s =
      m.sampleReflection(wo, glm::vec2(0.4f, 0.6f));
  ASSERT_TRUE(s);
  EXPECT_GT(s->wi.z, 0.0f);
  EXPECT_NEAR(glm::dot(s->wi + wo, s->wm) / glm::length(s->wi + wo), 1.0f, 1e-5f);
  EXPECT_TRUE(upperHemisphere(glm::vec3(0.1f, 0.2f, -0.3f)) == glm::vec3(0.1f, 0.2f, 0.3f));
}

}  // namespace
}  // namespace camsim
