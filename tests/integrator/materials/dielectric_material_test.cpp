// DielectricMaterial: sampling vs pdf (χ² over the full sphere), ∫pdf, smooth Fresnel/Snell,
// furnace energy, generalised reciprocity, dispersion and hard inputs.
#include "integrator/materials/dielectric_material.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "integrator/sampling/rng.h"
#include "integrator/scene/factory.h"
#include "sensor/spectra/spectral_data.h"
#include "tests/integrator/bsdf_check.h"

namespace camsim {
namespace {

using MD = MicrofacetDistribution;
using MM = MaskingModel;

SampledWavelengths lambdaAt(float nm) {
  return SampledWavelengths::sampleUniform((nm - static_cast<float>(kLambdaMinNm)) /
                                           static_cast<float>(kLambdaMaxNm - kLambdaMinNm));
}

// Direction with cos θ = c (negative: inside) at azimuth phi.
glm::vec3 dir(double c, double phi = 0.4) {
  return bsdfcheck::direction(c, phi);
}

// Independent double-precision Fresnel reflectance (η = inside / outside).
double fresnelRef(double cosI, double eta) {
  if (cosI < 0.0) {
    eta = 1.0 / eta;
    cosI = -cosI;
  }
  const double sin2T = (1.0 - cosI * cosI) / (eta * eta);
  if (sin2T >= 1.0) return 1.0;
  const double cosT = std::sqrt(1.0 - sin2T);
  const double rPar = (eta * cosI - cosT) / (eta * cosI + cosT);
  const double rPerp = (cosI - eta * cosT) / (cosI + eta * cosT);
  return 0.5 * (rPar * rPar + rPerp * rPerp);
}

const char* name(MD d) {
  return d == MD::kGgx ? "ggx" : "beckmann";
}
const char* name(MM m) {
  return m == MM::kSmith ? "smith" : "v-groove";
}

// (1) + (2): χ² of sample() against pdf() over the sphere, and ∫pdf dω = P(non-delta sample).
TEST(DielectricMaterial, ChiSquareRoughGlassAllModels) {
  struct Case {
    MD d;
    MM m;
    float alpha, aniso, eta;
    double cosO, phi;
  };
  // η = 1.5 and 1/1.5, each seen from outside and from inside.
  const std::pair<float, double> kSides[] = {
      {1.5f, 0.7}, {1.5f, -0.6}, {1.0f / 1.5f, 0.5}, {1.0f / 1.5f, -0.8}};
  std::vector<Case> cases;
  for (MD d : {MD::kGgx, MD::kBeckmann})
    for (MM m : {MM::kSmith, MM::kVGroove})
      for (float alpha : {0.05f, 0.3f, 1.0f})
        for (const auto& [eta, cosO] : kSides) cases.push_back({d, m, alpha, 0.0f, eta, cosO, 0.4});
  cases.push_back({MD::kGgx, MM::kSmith, 0.3f, 0.6f, 1.5f, 0.6, 0.5});
  cases.push_back({MD::kBeckmann, MM::kVGroove, 0.3f, -0.5f, 1.5f, -0.7, 2.0});
  bsdfcheck::ChiSquareOptions o;
  o.sampleCount = 100000;
  o.testCount = static_cast<int>(cases.size());
  const SampledWavelengths lambda = lambdaAt(550.0f);
  double worstP = 1.0, worstPdfSigma = 0.0, minPdf = 1.0, maxPdf = 0.0;
  for (const Case& c : cases) {
    const DielectricMaterial mat(Spectrum::constant(c.eta), c.alpha, c.aniso, c.d, c.m);
    const glm::vec3 wo = dir(c.cosO, c.phi);
    const bsdfcheck::ChiSquareResult r = bsdfcheck::chiSquare(mat, wo, lambda, {}, o);
    const std::string label = std::string(name(c.d)) + " " + name(c.m) + " alpha " +
                              std::to_string(c.alpha) + " aniso " + std::to_string(c.aniso) +
                              " eta " + std::to_string(c.eta) + " cos " + std::to_string(c.cosO) +
                              "\n" + r.report;
    SCOPED_TRACE(label);
    worstP = std::min(worstP, r.pValue);
    EXPECT_TRUE(r.accepted);
    EXPECT_EQ(r.invalid, 0);
    EXPECT_EQ(r.delta, 0);
    EXPECT_EQ(r.pdfMismatch, 0);
    EXPECT_EQ(r.fMismatch, 0);
    // ∫pdf dω equals the probability that sample() returns a direction (binomial 4σ +
    // quadrature), and never exceeds 1.
    const double p = static_cast<double>(r.nonDelta) / o.sampleCount;
    const double sigma = std::sqrt(std::max(p * (1.0 - p), 1e-6) / o.sampleCount);
    EXPECT_NEAR(r.pdfIntegral, p, 4.0 * sigma + 1e-3);
    EXPECT_LE(r.pdfIntegral, 1.0 + 1e-3);
    worstPdfSigma = std::max(worstPdfSigma, std::abs(r.pdfIntegral - p) / sigma);
    minPdf = std::min(minPdf, r.pdfIntegral);
    maxPdf = std::max(maxPdf, r.pdfIntegral);
    if (c.alpha == 0.3f && c.m == MM::kSmith && c.aniso == 0.0f)
      std::printf(
          "  %-8s alpha 0.3 eta %.3f cos %+.1f: int pdf = %.5f, P(sample) = %.5f, p = %.3f\n",
          name(c.d), static_cast<double>(c.eta), c.cosO, r.pdfIntegral, p, r.pValue);
  }
  std::printf("  %zu chi-square cases, smallest p-value %.4f (threshold %.5f)\n", cases.size(),
              worstP, 0.01 / static_cast<double>(cases.size()));
  std::printf("  int pdf in [%.4f, %.4f]; largest |int pdf - P(sample)| = %.2f sigma\n", minPdf,
              maxPdf, worstPdfSigma);
}

// (3) Smooth glass: Fresnel lobe probabilities, Snell, weights, total internal reflection.
TEST(DielectricMaterial, SmoothFresnelSnellAndWeights) {
  const float eta = 1.5f;
  const DielectricMaterial mat(Spectrum::constant(eta), 0.0f);
  EXPECT_FALSE(mat.hasNonSpecular());
  const SampledWavelengths lambda = lambdaAt(550.0f);
  for (double cosO : {1.0, 0.9, 0.5, 0.2, 0.05, -1.0, -0.9, -0.8, -0.75, -0.7, -0.3, -0.05}) {
    SCOPED_TRACE("cos theta_o = " + std::to_string(cosO));
    const glm::vec3 wo = dir(cosO);
    const double etap = cosO > 0.0 ? 1.5 : 1.0 / 1.5;
    constexpr int kN = 20000;
    int reflected = 0;
    for (int i = 0; i < kN; ++i) {
      const float uc = (static_cast<float>(i) + 0.5f) / kN;
      const std::optional<BsdfSample> s = mat.sample(wo, uc, {0.3f, 0.7f}, lambda, {});
      ASSERT_TRUE(s.has_value());
      ASSERT_TRUE(s->specular);
      const double weight =
          static_cast<double>(s->f[0] * std::abs(s->wi.z)) / static_cast<double>(s->pdf);
      EXPECT_EQ(mat.f(wo, s->wi, lambda, {})[0], 0.0f);
      EXPECT_EQ(mat.pdf(wo, s->wi, lambda, {}), 0.0f);
      if (!s->transmission) {
        ++reflected;
        EXPECT_NEAR(s->wi.x, -wo.x, 1e-6f);
        EXPECT_NEAR(s->wi.y, -wo.y, 1e-6f);
        EXPECT_NEAR(s->wi.z, wo.z, 1e-6f);
        EXPECT_NEAR(weight, 1.0, 1e-5);
        EXPECT_NEAR(s->pdf, fresnelRef(cosO, eta), 1e-5);
      } else {
        ASSERT_LT(s->wi.z * wo.z, 0.0f);
        // Snell: η' sinθi = sinθo (η' = index of wi's side over wo's side), φi = φo + π.
        const double sinO = std::sqrt(1.0 - cosO * cosO);
        const double sinI = std::hypot(static_cast<double>(s->wi.x), static_cast<double>(s->wi.y));
        EXPECT_NEAR(etap * sinI, sinO, 2e-6);
        EXPECT_LE(s->wi.x * wo.x + s->wi.y * wo.y, 0.0f);
        EXPECT_NEAR(weight, 1.0 / (etap * etap), 1e-5);
        EXPECT_NEAR(s->pdf, 1.0 - fresnelRef(cosO, eta), 1e-5);
      }
    }
    const double R = fresnelRef(cosO, eta);
    EXPECT_NEAR(static_cast<double>(reflected) / kN, R, 1.0 / kN + 1e-5);
    if (cosO < 0.0 && cosO > -std::sqrt(1.0 - 1.0 / 2.25)) {  // η = 1.5
      EXPECT_EQ(reflected, kN);                               // beyond the critical angle
    }
  }
}

// Energy albedo E[f |cos θi| / pdf · η'²] (η'² on transmitted samples undoes the radiance
// 1/η² factor: this is the fraction of flux scattered), by sampling.
struct Albedo {
  double total = 0.0, reflected = 0.0, stdErr = 0.0;
};
Albedo energyAlbedo(const Material& mat, const glm::vec3& wo, float eta, int n,
                    std::uint64_t seed) {
  const SampledWavelengths lambda = lambdaAt(550.0f);
  Pcg32 rng(seed, 3);
  double sum = 0.0, sum2 = 0.0, refl = 0.0;
  for (int i = 0; i < n; ++i) {
    const float uc = rng.uniform(), u0 = rng.uniform(), u1 = rng.uniform();
    const std::optional<BsdfSample> s = mat.sample(wo, uc, {u0, u1}, lambda, {});
    if (!s) continue;
    double w = static_cast<double>(s->f[0]) * std::abs(static_cast<double>(s->wi.z)) /
               static_cast<double>(s->pdf);
    if (s->transmission) {
      const double etap = static_cast<double>(wo.z > 0.0f ? eta : 1.0f / eta);
      w *= etap * etap;
    } else {
      refl += w;
    }
    sum += w;
    sum2 += w * w;
  }
  Albedo a;
  a.total = sum / n;
  a.reflected = refl / n;
  a.stdErr = std::sqrt(std::max(0.0, sum2 / n - a.total * a.total) / n);
  return a;
}

// (4) Furnace: a rough dielectric never creates energy, at any angle including grazing.
TEST(DielectricMaterial, FurnaceEnergyAtMostOne) {
  const float eta = 1.5f;
  constexpr int kN = 100000;
  for (double sign : {1.0, -1.0}) {
    std::printf(
        "  energy albedo, GGX/Smith, eta 1.5, wo %s:\n  alpha   cos 1    cos 0.5  cos 0.1\n",
        sign > 0.0 ? "outside" : "inside");
    for (float alpha : {0.01f, 0.1f, 0.3f, 1.0f}) {
      const DielectricMaterial mat(Spectrum::constant(eta), alpha);
      std::printf("  %-6.2f", static_cast<double>(alpha));
      for (double c : {1.0, 0.5, 0.1}) {
        const Albedo a = energyAlbedo(mat, dir(sign * c), eta, kN, 5);
        std::printf("  %.4f", a.total);
        EXPECT_LE(a.total, 1.0 + 4.0 * a.stdErr + 1e-4) << "alpha " << alpha << " cos " << sign * c;
        if (alpha == 0.01f && c >= 0.5) {
          // Nearly smooth: all energy is kept, and the reflected share is Fresnel's R.
          EXPECT_GT(a.total, 0.985) << "cos " << sign * c;
          EXPECT_NEAR(a.reflected, fresnelRef(sign * c, eta), 0.01) << "cos " << sign * c;
        }
      }
      std::printf("\n");
    }
  }
  for (MD d : {MD::kGgx, MD::kBeckmann})
    for (MM m : {MM::kSmith, MM::kVGroove})
      for (float alpha : {0.05f, 0.5f, 1.0f})
        for (double c : {0.9, 1e-3, 1e-6, -0.9, -1e-3, -1e-6}) {
          const DielectricMaterial mat(Spectrum::constant(eta), alpha, 0.0f, d, m);
          const Albedo a = energyAlbedo(mat, dir(c), eta, 20000, 9);
          EXPECT_TRUE(std::isfinite(a.total));
          EXPECT_LE(a.total, 1.0 + 4.0 * a.stdErr + 1e-4)
              << name(d) << " " << name(m) << " alpha " << alpha << " cos " << c;
        }
}

// Sampling covers f: the sampled albedo E[f |cos θi| / pdf] equals the quadrature
// ∫ f |cos θi| dω (a direction where f > 0 but pdf = 0 would make the estimate low).
TEST(DielectricMaterial, SampledAlbedoMatchesQuadrature) {
  const SampledWavelengths lambda = lambdaAt(550.0f);
  for (MD d : {MD::kGgx, MD::kBeckmann})
    for (double c : {0.8, 0.2, -0.9, -0.3}) {
      const DielectricMaterial mat(Spectrum::constant(1.5), 0.3f, 0.2f, d);
      bsdfcheck::AlbedoOptions o;
      o.sampleCount = 100000;
      const bsdfcheck::AlbedoResult r = bsdfcheck::albedo(mat, dir(c), lambda, {}, o);
      SCOPED_TRACE(std::string(name(d)) + " cos " + std::to_string(c));
      EXPECT_EQ(r.nonFinite, 0);
      EXPECT_NEAR(r.mean[0], r.quadrature[0], 4.0 * r.stdErr[0] + 2e-3);
      std::printf("  %-8s alpha 0.3 cos %+.1f: sampled %.4f +- %.4f, quadrature %.4f\n", name(d), c,
                  r.mean[0], r.stdErr[0], r.quadrature[0]);
    }
}

// (5) Reciprocity: reflection f(wo, wi) = f(wi, wo); transmission (radiance BTDF)
// f(wo, wi)/η_o² = f(wi, wo)/η_i², η_o and η_i the indices of wo's and wi's sides. Pairs
// where f < 1e-30 sr⁻¹ are skipped: denormal floats keep fewer than 24 significant bits.
TEST(DielectricMaterial, GeneralisedReciprocity) {
  const SampledWavelengths lambda = lambdaAt(550.0f);
  double worst[2] = {0.0, 0.0};
  int pairs[2] = {0, 0};
  Pcg32 rng(13, 5);
  const auto uniform = [&] { return static_cast<double>(rng.uniform()); };
  for (MD d : {MD::kGgx, MD::kBeckmann})
    for (MM m : {MM::kSmith, MM::kVGroove})
      for (float eta : {1.5f, 1.0f / 1.5f})
        for (int t : {0, 1}) {
          const DielectricMaterial mat(Spectrum::constant(eta), 0.4f, 0.3f, d, m);
          SCOPED_TRACE(std::string(name(d)) + " " + name(m) + " eta " + std::to_string(eta));
          const auto n2 = [&](const glm::vec3& w) {
            return w.z > 0.0f ? 1.0 : static_cast<double>(eta * eta);
          };
          int used = 0;
          for (int p = 0; p < 2000; ++p) {
            const glm::vec3 wo = dir(2.0 * uniform() - 1.0, 6.283185307 * uniform());
            glm::vec3 wi = dir(2.0 * uniform() - 1.0, 6.283185307 * uniform());
            if ((wi.z * wo.z < 0.0f) != (t == 1)) wi.z = -wi.z;
            const double a = static_cast<double>(mat.f(wo, wi, lambda, {})[0]) / n2(wo);
            const double b = static_cast<double>(mat.f(wi, wo, lambda, {})[0]) / n2(wi);
            ASSERT_TRUE(std::isfinite(a) && std::isfinite(b));
            if (std::max(a, b) < 1e-30) continue;
            ++used;
            const double e = std::abs(a - b) / std::max(a, b);
            EXPECT_LT(e, 1e-3) << "wo " << wo.z << " wi " << wi.z << ": " << a << " vs " << b;
            worst[t] = std::max(worst[t], e);
          }
          EXPECT_GT(used, 250);
          pairs[t] += used;
        }
  std::printf(
      "  reciprocity: reflection %d pairs, max rel. error %.2e; transmission %d pairs, %.2e\n",
      pairs[0], worst[0], pairs[1], worst[1]);
}

// (6) Dispersion: BK7 refracts 450 nm and 650 nm by the angles Snell predicts.
TEST(DielectricMaterial, DispersionBk7) {
  const SpectralTable table =
      readSpectralCsv(std::string(CAMSIM_SOURCE_DIR) + "/luts/spectra/glasses/BK7.csv");
  const Spectrum bk7 = table.spectrum(table.columnIndex("eta"), Extrapolation::kClamp);
  const DielectricMaterial glass(bk7, 0.0f);
  EXPECT_TRUE(glass.dispersive());
  EXPECT_FALSE(DielectricMaterial(Spectrum::constant(1.5), 0.0f).dispersive());
  EXPECT_FALSE(DielectricMaterial(Spectrum::constant(1.5), 0.3f).dispersive());
  // η from the table by our own linear interpolation.
  const auto etaRef = [&](double nm) {
    const auto& x = table.wavelengthsNm;
    const auto& y = table.values[table.columnIndex("eta")];
    for (std::size_t i = 0; i + 1 < x.size(); ++i)
      if (nm <= x[i + 1]) return y[i] + (nm - x[i]) / (x[i + 1] - x[i]) * (y[i + 1] - y[i]);
    return y.back();
  };
  const double thetaO = 60.0 * 3.14159265358979 / 180.0;
  const glm::vec3 wo = dir(std::cos(thetaO), 0.0);
  double angle[2];
  int k = 0;
  for (float nm : {450.0f, 650.0f}) {
    SampledWavelengths lambda = lambdaAt(nm);
    lambda.terminateSecondary();
    const double hero = static_cast<double>(lambda[0]);
    const double eta = etaRef(hero);
    EXPECT_NEAR(static_cast<double>(glass.etaAt(lambda)), eta, 1e-5);
    const std::optional<BsdfSample> s = glass.sample(wo, 0.999f, {0.5f, 0.5f}, lambda, {});
    ASSERT_TRUE(s && s->transmission);
    angle[k] = std::acos(-static_cast<double>(s->wi.z));
    EXPECT_NEAR(angle[k], std::asin(std::sin(thetaO) / eta), 2e-5) << nm << " nm";
    ++k;
  }
  const double predicted =
      std::asin(std::sin(thetaO) / etaRef(650.0)) - std::asin(std::sin(thetaO) / etaRef(450.0));
  std::printf(
      "  BK7 at 60 deg: eta(450) %.5f eta(650) %.5f, angle difference %.4f deg (Snell %.4f deg)\n",
      etaRef(450.0), etaRef(650.0), (angle[1] - angle[0]) * 180.0 / 3.14159265358979,
      predicted * 180.0 / 3.14159265358979);
  EXPECT_GT(predicted, 0.003);  // about 0.28°: blue bends more
  EXPECT_NEAR(angle[1] - angle[0], predicted, 4e-5);
}

// (7) Hard inputs: α = 0, 1e-4, 1 and cos θ = 1e-6 give finite values; η = 1 passes straight
// through.
TEST(DielectricMaterial, HardCasesStayFinite) {
  const SampledWavelengths lambda = lambdaAt(550.0f);
  Pcg32 rng(21, 1);
  for (float alpha : {0.0f, 1e-4f, 1e-3f, 1.0f})
    for (MD d : {MD::kGgx, MD::kBeckmann})
      for (float eta : {1.5f, 1.0f / 1.5f, 1.0001f}) {
        const DielectricMaterial mat(Spectrum::constant(eta), alpha, 0.0f, d);
        for (double c : {1.0, 1e-6, -1e-6, -1.0, 0.3}) {
          SCOPED_TRACE(std::string(name(d)) + " alpha " + std::to_string(alpha) + " eta " +
                       std::to_string(eta) + " cos " + std::to_string(c));
          const glm::vec3 wo = dir(c, 1.1);
          int produced = 0;
          for (int i = 0; i < 2000; ++i) {
            const float uc = rng.uniform(), u0 = rng.uniform(), u1 = rng.uniform();
            const std::optional<BsdfSample> s = mat.sample(wo, uc, {u0, u1}, lambda, {});
            const glm::vec3 wr =
                dir(2.0 * static_cast<double>(rng.uniform()) - 1.0, 6.28 * static_cast<double>(u0));
            ASSERT_TRUE(mat.f(wo, wr, lambda, {}).isFinite());
            ASSERT_TRUE(std::isfinite(mat.pdf(wo, wr, lambda, {})));
            if (!s) continue;
            ++produced;
            ASSERT_TRUE(s->f.isFinite());
            ASSERT_GE(s->f[0], 0.0f);
            ASSERT_TRUE(std::isfinite(s->pdf) && s->pdf > 0.0f);
            ASSERT_NEAR(glm::length(s->wi), 1.0f, 1e-4f);
            ASSERT_EQ(s->transmission, s->wi.z * wo.z < 0.0f);
            ASSERT_TRUE(mat.f(wo, s->wi, lambda, {}).isFinite());
            ASSERT_TRUE(std::isfinite(mat.pdf(wo, s->wi, lambda, {})));
          }
          if (std::abs(c) >= 0.3) {
            EXPECT_GT(produced, 200);
          }
        }
      }
  // Index-matched: smooth or rough, every sample goes straight through with weight 1.
  for (float alpha : {0.0f, 0.5f}) {
    const DielectricMaterial mat(Spectrum::constant(1.0), alpha);
    EXPECT_FALSE(mat.hasNonSpecular());
    for (double c : {1.0, 0.6, 1e-6, -0.4}) {
      const glm::vec3 wo = dir(c, 2.0);
      for (float uc : {0.0f, 0.5f, 0.9999f}) {
        const std::optional<BsdfSample> s = mat.sample(wo, uc, {0.2f, 0.9f}, lambda, {});
        ASSERT_TRUE(s.has_value());
        EXPECT_TRUE(s->transmission && s->specular);
        EXPECT_EQ(s->wi, -wo);
        EXPECT_NEAR(s->f[0] * std::abs(s->wi.z) / s->pdf, 1.0f, 1e-6f);
      }
    }
  }
}

TEST(DielectricMaterial, FactoryBuildsGlass) {
  MaterialDescription d;
  d.type = MaterialDescription::Type::kDielectric;
  d.eta = Spectrum::constant(1.5);
  const std::unique_ptr<Material> smooth = makeMaterial(d);
  ASSERT_NE(smooth, nullptr);
  EXPECT_FALSE(smooth->hasNonSpecular());
  EXPECT_FALSE(smooth->dispersive());
  d.roughness = TextureDescription::constant(0.2);
  d.anisotropy = 0.5f;
  const std::unique_ptr<Material> rough = makeMaterial(d);
  EXPECT_TRUE(rough->hasNonSpecular());
  const glm::vec3 wo = dir(0.8);
  const std::optional<BsdfSample> s = rough->sample(wo, 0.99f, {0.3f, 0.6f}, lambdaAt(550.0f), {});
  ASSERT_TRUE(s && s->transmission && !s->specular);
  EXPECT_NEAR(s->pdf, rough->pdf(wo, s->wi, lambdaAt(550.0f), {}), 1e-3f * s->pdf);
}

}  // namespace
}  // namespace camsim
