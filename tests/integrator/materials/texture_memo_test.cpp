// BsdfContext's texture memo (integrator/materials/material.h): at one shading point the
// path tracer calls f, pdf, sample and aov, and each needs the material's spectral texture.
//  - one lookup per point: every call of the four at the same uv and wavelengths after the
//    first takes the memo (a counting texture sees one evaluation), for each material with
//    a spectral texture (diffuse, plastic, mirror);
//  - the memo never answers for another texture, uv or wavelengths: each of those evaluates
//    again, and the values equal a fresh context's (bit for bit);
//  - copying a context keeps nothing shared (the copy's memo is its own).
#include <gtest/gtest.h>

#include <memory>

#include "integrator/materials/diffuse_material.h"
#include "integrator/materials/mirror_material.h"
#include "integrator/materials/plastic_material.h"
#include "tests/integrator/bsdf_check.h"

namespace camsim {
namespace {

using bsdfcheck::direction;

// ρ(λ, uv) = 0.2 + 0.5 u + λ/2000 nm, counting its evaluations.
class CountingTexture final : public SpectrumTexture {
 public:
  explicit CountingTexture(int* count) : count_(count) {}
  SampledSpectrum evaluate(glm::vec2 uv, const SampledWavelengths& lambda) const override {
    ++*count_;
    SampledSpectrum out;
    for (int i = 0; i < kWavelengthSamples; ++i) out[i] = 0.2f + 0.5f * uv.x + lambda[i] / 2000.0f;
    return out;
  }
  double maxValue() const override { return 1.0; }

 private:
  int* count_;
};

TEST(TextureMemo, DiffuseBounceLooksTheTextureUpOnce) {
  int count = 0;
  const DiffuseMaterial m(std::make_unique<CountingTexture>(&count));
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.3f);
  const glm::vec3 wo = direction(0.8, 0.1), wi = direction(0.5, 2.0);
  const BsdfContext ctx(glm::vec2(0.25f, 0.5f));
  const SurfaceAov aov = m.aov(lambda, ctx);
  const SampledSpectrum f = m.f(wo, wi, lambda, ctx);
  (void)m.pdf(wo, wi, lambda, ctx);
  const std::optional<BsdfSample> s = m.sample(wo, 0.5f, glm::vec2(0.3f, 0.7f), lambda, ctx);
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(count, 1);
  EXPECT_EQ(ctx.textureEvaluations(), 1);
  for (int i = 0; i < kWavelengthSamples; ++i) {
    const float rho = 0.2f + 0.5f * 0.25f + lambda[i] / 2000.0f;
    EXPECT_EQ(aov.albedo[i], rho);
    EXPECT_EQ(f[i], s->f[i]);
  }
}

TEST(TextureMemo, AnotherUvWavelengthOrTextureEvaluatesAgain) {
  int count = 0, otherCount = 0;
  const DiffuseMaterial m(std::make_unique<CountingTexture>(&count));
  const DiffuseMaterial other(std::make_unique<CountingTexture>(&otherCount));
  const glm::vec3 wo = direction(0.8, 0.1), wi = direction(0.5, 2.0);
  const SampledWavelengths a = SampledWavelengths::sampleUniform(0.3f);
  const SampledWavelengths b = SampledWavelengths::sampleUniform(0.7f);
  BsdfContext ctx(glm::vec2(0.25f, 0.5f));
  const SampledSpectrum fa = m.f(wo, wi, a, ctx);
  const SampledSpectrum fb = m.f(wo, wi, b, ctx);  // other wavelengths
  EXPECT_EQ(count, 2);
  ctx.uv = glm::vec2(0.75f, 0.5f);
  const SampledSpectrum fc = m.f(wo, wi, b, ctx);  // other uv
  EXPECT_EQ(count, 3);
  (void)other.f(wo, wi, b, ctx);  // another material's texture
  EXPECT_EQ(otherCount, 1);
  const SampledSpectrum fd = m.f(wo, wi, b, ctx);  // back: evaluated again, not stale
  EXPECT_EQ(count, 4);
  const auto fresh = [&](const SampledWavelengths& lambda, glm::vec2 uv) {
    return m.f(wo, wi, lambda, BsdfContext(uv));
  };
  const SampledSpectrum ra = fresh(a, {0.25f, 0.5f}), rb = fresh(b, {0.25f, 0.5f}),
                        rc = fresh(b, {0.75f, 0.5f});
  for (int i = 0; i < kWavelengthSamples; ++i) {
    EXPECT_EQ(fa[i], ra[i]);
    EXPECT_EQ(fb[i], rb[i]);
    EXPECT_EQ(fc[i], rc[i]);
    EXPECT_EQ(fd[i], rc[i]);
    EXPECT_NE(fa[i], fb[i]);
  }
}

TEST(TextureMemo, PlasticAndMirrorShareTheirLookup) {
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.4f);
  const glm::vec3 wo = direction(0.8, 0.1), wi = direction(0.6, 3.0);
  {
    int count = 0;
    const BsdfContext ctx(glm::vec2(0.5f, 0.5f));
    PlasticParameters p;
    p.reflectance = std::make_unique<CountingTexture>(&count);
    p.roughness = std::make_unique<ConstantFloatTexture>(0.3f);
    const PlasticMaterial m(std::move(p));
    (void)m.f(wo, wi, lambda, ctx);
    (void)m.pdf(wo, wi, lambda, ctx);
    (void)m.sample(wo, 0.3f, glm::vec2(0.2f, 0.6f), lambda, ctx);
    (void)m.sample(wo, 0.8f, glm::vec2(0.2f, 0.6f), lambda, ctx);
    (void)m.aov(lambda, ctx);
    EXPECT_EQ(count, 1);
  }
  {
    int count = 0;
    const BsdfContext ctx(glm::vec2(0.5f, 0.5f));  // a context lives at one point, one material
    const MirrorMaterial m(std::make_unique<CountingTexture>(&count));
    (void)m.sample(wo, 0.5f, glm::vec2(0.5f), lambda, ctx);
    (void)m.aov(lambda, ctx);
    EXPECT_EQ(count, 1);
  }
}

TEST(TextureMemo, ACopyHasItsOwnMemo) {
  int count = 0;
  const DiffuseMaterial m(std::make_unique<CountingTexture>(&count));
  const SampledWavelengths lambda = SampledWavelengths::sampleUniform(0.3f);
  const BsdfContext ctx(glm::vec2(0.25f, 0.5f));
  (void)m.aov(lambda, ctx);
  BsdfContext copy = ctx;
  copy.uv = glm::vec2(0.9f, 0.1f);
  (void)m.aov(lambda, copy);
  (void)m.aov(lambda, ctx);  // ctx's memo still holds its own uv
  EXPECT_EQ(count, 2);
  EXPECT_EQ(ctx.textureEvaluations(), 1);
}

}  // namespace
}  // namespace camsim
