// Fresnel reflectance and refraction (integrator/materials/fresnel.cpp) against hand-computed values:
//  - glass η = 1.5: R(normal) = ((η − 1)/(η + 1))² = 0.04 from either side;
//  - Brewster angle tan θB = η: r∥ = 0, so R = r⊥²/2 with r⊥ = (1 − η²)/(1 + η²);
//  - total internal reflection beyond sin θc = 1/η from the inside, R → 1 at grazing;
//  - conductor at normal incidence ((η − 1)² + k²)/((η + 1)² + k²), and = dielectric at k = 0;
//  - Schlick endpoints R(1) = R0, R(0) = 1, R(0.5) = R0 + (1 − R0)/32;
//  - refract: Snell's law, unit length, TIR, the relative index crossed, reversibility.
#include "integrator/materials/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>

namespace camsim {
namespace {

TEST(Fresnel, GlassAtNormalIncidenceReflectsFourPercent) {
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.5f), 0.04f, 1e-6f);
  EXPECT_NEAR(fresnelDielectric(-1.0f, 1.5f), 0.04f, 1e-6f);  // from inside: same
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f / 1.5f), 0.04f, 1e-6f);
  EXPECT_NEAR(fresnelDielectric(0.7f, 1.0f), 0.0f, 1e-7f);  // no interface
}

TEST(Fresnel, BrewsterAngleHasNoParallelReflection) {
  const float eta = 1.5f;
  const float cosB = 1.0f / std::sqrt(1.0f + eta * eta);                   // θB = atan η
  const float rPerp = (1.0f - eta * eta) / (1.0f + eta * eta);             // −0.384615
  EXPECT_NEAR(fresnelDielectric(cosB, eta), 0.5f * rPerp * rPerp, 1e-6f);  // 0.0739645
  EXPECT_NEAR(fresnelDielectric(cosB, eta), 0.0739645f, 1e-6f);
  // From the inside, Brewster is at tan θ = 1/η.
  const float cosBInside = eta / std::sqrt(1.0f + eta * eta);
  EXPECT_NEAR(fresnelDielectric(-cosBInside, eta), 0.0739645f, 1e-6f);
}

TEST(Fresnel, TotalInternalReflectionAndGrazing) {
  const float eta = 1.5f;
  const float cosCritical = std::sqrt(1.0f - 1.0f / (eta * eta));  // 0.745356
  EXPECT_EQ(fresnelDielectric(-(cosCritical - 1e-3f), eta), 1.0f);
  EXPECT_EQ(fresnelDielectric(-0.3f, eta), 1.0f);
  EXPECT_LT(fresnelDielectric(-(cosCritical + 1e-2f), eta), 1.0f);
  EXPECT_NEAR(fresnelDielectric(0.0f, eta), 1.0f, 1e-6f);
  EXPECT_NEAR(fresnelDielectric(1e-6f, eta), 1.0f, 1e-5f);
  // Index-matched (η = 1): no interface at any angle, although 1 − cos² rounds to 1 at
  // cos 1e-6 (the TIR branch would return 1); refraction goes straight through.
  for (float c : {1e-6f, -1e-6f, 0.0f, 0.5f, -1.0f})
    EXPECT_EQ(fresnelDielectric(c, 1.0f), 0.0f) << c;
  for (const glm::vec3 wi : {glm::vec3(1.0f, 0.0f, 1e-6f), glm::vec3(0.6f, 0.0f, -0.8f)}) {
    const std::optional<Refraction> r = refract(wi, glm::vec3(0.0f, 0.0f, 1.0f), 1.0f);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->wt, -wi);
    EXPECT_EQ(r->etap, 1.0f);
  }
  // Monotonic between normal and grazing from outside.
  float previous = 0.0f;
  for (float c = 1.0f; c >= 0.0f; c -= 0.01f) {
    const float r = fresnelDielectric(c, eta);
    EXPECT_GE(r, previous - 1e-6f) << c;
    previous = r;
  }
}

TEST(Fresnel, ConductorAtNormalIncidence) {
  struct Metal {
    float eta, k;
  };
  // Gold and aluminium near 550 nm, silver near 450 nm (rounded handbook values).
  for (Metal m : {Metal{0.43f, 2.46f}, Metal{0.96f, 6.69f}, Metal{0.14f, 2.47f}}) {
    const float expected = ((m.eta - 1.0f) * (m.eta - 1.0f) + m.k * m.k) /
                           ((m.eta + 1.0f) * (m.eta + 1.0f) + m.k * m.k);
    EXPECT_NEAR(fresnelConductor(1.0f, m.eta, m.k), expected, 1e-6f);
    EXPECT_NEAR(fresnelConductor(0.0f, m.eta, m.k), 1.0f, 1e-6f);
    for (float c = 0.0f; c <= 1.0f; c += 0.05f) {
      const float r = fresnelConductor(c, m.eta, m.k);
      EXPECT_TRUE(r >= 0.0f && r <= 1.0f) << r;
    }
  }
  // Gold: ((0.43−1)² + 2.46²)/((1.43)² + 2.46²) = 6.3765/8.0965 = 0.78756.
  EXPECT_NEAR(fresnelConductor(1.0f, 0.43f, 2.46f), 0.78756f, 1e-4f);
  // k = 0 is a dielectric.
  for (float c : {1.0f, 0.8f, 0.5f, 0.2f, 0.05f})
    EXPECT_NEAR(fresnelConductor(c, 1.5f, 0.0f), fresnelDielectric(c, 1.5f), 1e-6f) << c;
  // Spectral version: per wavelength.
  SampledSpectrum eta(0.43f), k(2.46f);
  eta[2] = 1.5f;
  k[2] = 0.0f;
  const SampledSpectrum r = fresnelConductor(1.0f, eta, k);
  EXPECT_NEAR(r[0], 0.78756f, 1e-4f);
  EXPECT_NEAR(r[2], 0.04f, 1e-6f);
}

TEST(Fresnel, SchlickEndpoints) {
  const SampledSpectrum r0(0.04f);
  EXPECT_NEAR(fresnelSchlick(1.0f, r0)[0], 0.04f, 1e-7f);
  EXPECT_NEAR(fresnelSchlick(0.0f, r0)[1], 1.0f, 1e-7f);
  EXPECT_NEAR(fresnelSchlick(0.5f, r0)[2], 0.04f + 0.96f / 32.0f, 1e-7f);
  EXPECT_NEAR(fresnelSchlick(-0.5f, r0)[3], 0.04f + 0.96f / 32.0f, 1e-7f);
  EXPECT_NEAR(fresnelSchlick(0.3f, SampledSpectrum(1.0f))[0], 1.0f, 1e-7f);
}

TEST(Fresnel, RefractionFollowsSnell) {
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  const float eta = 1.5f;
  // Normal incidence: straight through.
  const auto straight = refract(n, n, eta);
  ASSERT_TRUE(straight.has_value());
  EXPECT_NEAR(straight->wt.z, -1.0f, 1e-6f);
  EXPECT_FLOAT_EQ(straight->etap, eta);
  // 60° from outside: sin θt = sin 60°/1.5 = 0.57735.
  const float t = 60.0f * 3.14159265f / 180.0f;
  const glm::vec3 wi(std::sin(t), 0.0f, std::cos(t));
  const auto r = refract(wi, n, eta);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(glm::length(r->wt), 1.0f, 1e-6f);
  EXPECT_NEAR(r->wt.x, -0.57735f, 1e-5f);
  EXPECT_LT(r->wt.z, 0.0f);
  // wt leaves the surface on the inside; refracting it back gives wi, relative index 1/η.
  const auto back = refract(r->wt, n, eta);
  ASSERT_TRUE(back.has_value());
  EXPECT_NEAR(back->etap, 1.0f / eta, 1e-7f);
  EXPECT_NEAR(back->wt.x, wi.x, 1e-5f);
  EXPECT_NEAR(back->wt.z, wi.z, 1e-5f);
  // Beyond the critical angle from the inside: nothing.
  EXPECT_FALSE(refract(glm::vec3(0.8f, 0.0f, -0.6f), n, eta).has_value());
  EXPECT_TRUE(refract(glm::vec3(0.6f, 0.0f, -0.8f), n, eta).has_value());
}

}  // namespace
}  // namespace camsim
