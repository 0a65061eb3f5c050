// Reusable statistical checks for any Material (header-only, used by the *_material tests).
//
// | check          | what it verifies                                                        |
// |----------------|-------------------------------------------------------------------------|
// | chiSquare      | sample() is distributed as pdf() over the FULL sphere (Pearson χ²)      |
// | pdfIntegral    | ∫ pdf dω = P(sample() returns a non-delta direction)                    |
// | albedo         | E[f |cos θi| / pdf] ≤ 1, finite, = ∫ f |cos θi| dω (+ delta part)         |
// | reciprocity    | f(wo, wi)/n(wo)² = f(wi, wo)/n(wi)² (n = 1 outside, etaInside inside)     |
//
// χ² (Nori/Mitsuba style): the sphere is cut into cosThetaBins × phiBins cells of equal
// solid angle (uniform in z = cos θ ∈ [−1, 1] and φ ∈ [0, 2π)); the expected count of a
// cell is N ∫_cell pdf dω by nested adaptive Simpson quadrature in (θ, φ) (dω = sin θ dθ dφ).
// Delta samples and failed samples (nullopt) form one extra "other" cell whose expected
// count is N (1 − ∫ pdf dω). Cells with expected < minExpected are pooled; the p-value is
// the regularised upper incomplete gamma Q(dof/2, χ²/2), and the test rejects when
// p < 0.01 / testCount (Bonferroni over the tests of a suite). Deterministic (PCG32).
// Every non-delta sample is also checked against f() and pdf() (relative 1e-3).
// Narrow lobes (α ≲ 0.01): raise QuadratureOptions::minDepth (e.g. 6) so that the forced
// panels see the peak, and the bin counts so that the lobe spans several cells.
//
//   const auto chi = bsdfcheck::chiSquare(material, wo, SampledWavelengths::sampleUniform(0.3f),
//                                         BsdfContext{}, options);
//   EXPECT_TRUE(chi.accepted) << chi.report;
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "integrator/materials/material.h"
#include "integrator/sampling/rng.h"
#include "tests/integrator/bsdf_check_quadrature.h"

namespace camsim::bsdfcheck {

// ---------------------------------------------------------------- sample checks
struct ChiSquareOptions {
  int cosThetaBins = 10;
  int phiBins = 20;
  int sampleCount = 200000;
  std::uint64_t seed = 7;
  int testCount = 1;         // significance = 0.01 / testCount
  double minExpected = 5.0;  // pooling threshold
  QuadratureOptions quadrature;
};

struct ChiSquareResult {
  bool accepted = false;
  double statistic = 0.0, pValue = 0.0, significance = 0.0;
  int dof = 0;
  int nonDelta = 0, delta = 0, failed = 0;
  int invalid = 0;  // non-finite / negative values, non-unit wi, pdf ≤ 0 on a non-delta sample
  int pdfMismatch = 0;       // sample().pdf ≠ pdf(wo, wi) (relative 1e-3)
  int fMismatch = 0;         // sample().f ≠ f(wo, wi) (relative 1e-3)
  double pdfIntegral = 0.0;  // ∫ pdf dω over the sphere
  long unresolvedCells = 0;  // cells whose quadrature ran out of evaluations (rejects)
  std::string report;        // grid of observed/expected, and the reason for a rejection
};

namespace detail {
inline bool close(double a, double b, double rel) {
  return std::abs(a - b) <= rel * std::max({std::abs(a), std::abs(b), 1e-12});
}
inline bool finiteNonNegative(const SampledSpectrum& s) {
  for (int c = 0; c < kWavelengthSamples; ++c)
    if (!std::isfinite(s[c]) || s[c] < 0.0f) return false;
  return true;
}
}  // namespace detail

inline ChiSquareResult chiSquare(const Material& m, const glm::vec3& wo,
                                 const SampledWavelengths& lambda, const BsdfContext& ctx,
                                 const ChiSquareOptions& o = {}) {
  ChiSquareResult r;
  const int nz = o.cosThetaBins, nphi = o.phiBins, cells = nz * nphi;
  std::vector<double> observed(static_cast<std::size_t>(cells) + 1, 0.0);
  std::vector<double> expected(observed.size(), 0.0);
  Pcg32 rng(o.seed, 0x5eed);
  for (int n = 0; n < o.sampleCount; ++n) {
    const float uc = rng.uniform();
    const float u0 = rng.uniform(), u1 = rng.uniform();
    const std::optional<BsdfSample> s = m.sample(wo, uc, {u0, u1}, lambda, ctx);
    if (!s) {
      ++r.failed;
      observed[static_cast<std::size_t>(cells)] += 1.0;
      continue;
    }
    const float len = glm::length(s->wi);
    if (!std::isfinite(len) || std::abs(len - 1.0f) > 1e-3f || !detail::finiteNonNegative(s->f) ||
        !std::isfinite(s->pdf) || s->pdf < 0.0f) {
      ++r.invalid;
      continue;
    }
    if (s->specular) {
      ++r.delta;
      observed[static_cast<std::size_t>(cells)] += 1.0;
      continue;
    }
    if (!(s->pdf > 0.0f)) {
      ++r.invalid;
      continue;
    }
    ++r.nonDelta;
    if (!detail::close(s->pdf, m.pdf(wo, s->wi, lambda, ctx), 1e-3)) ++r.pdfMismatch;
    const SampledSpectrum fv = m.f(wo, s->wi, lambda, ctx);
    for (int c = 0; c < kWavelengthSamples; ++c)
      if (!detail::close(s->f[c], fv[c], 1e-3)) {
        ++r.fMismatch;
        break;
      }
    const double z = std::clamp(static_cast<double>(s->wi.z), -1.0, 1.0);
    double phi = std::atan2(static_cast<double>(s->wi.y), static_cast<double>(s->wi.x));
    if (phi < 0.0) phi += kTwoPi;
    const int iz = std::clamp(static_cast<int>((z + 1.0) * 0.5 * nz), 0, nz - 1);
    const int ip = std::clamp(static_cast<int>(phi / kTwoPi * nphi), 0, nphi - 1);
    observed[static_cast<std::size_t>(iz * nphi + ip)] += 1.0;
  }

  const auto pdfAt = [&](const glm::vec3& wi) {
    return static_cast<double>(m.pdf(wo, wi, lambda, ctx));
  };
  const double total = static_cast<double>(o.sampleCount);
  QuadratureOptions q = o.quadrature;
  q.exhaustedCells = &r.unresolvedCells;
  for (int i = 0; i < nz; ++i)
    for (int j = 0; j < nphi; ++j) {
      const double p = integrateCell(pdfAt, -1.0 + 2.0 * i / nz, -1.0 + 2.0 * (i + 1) / nz,
                                     kTwoPi * j / nphi, kTwoPi * (j + 1) / nphi, q);
      r.pdfIntegral += p;
      expected[static_cast<std::size_t>(i * nphi + j)] = p * total;
    }
  expected[static_cast<std::size_t>(cells)] = std::max(0.0, total * (1.0 - r.pdfIntegral));

  std::ostringstream rep;
  rep << "wo = (" << wo.x << ", " << wo.y << ", " << wo.z << "), N = " << o.sampleCount
      << ", non-delta " << r.nonDelta << ", delta " << r.delta << ", failed " << r.failed
      << ", invalid " << r.invalid << ", ∫pdf = " << r.pdfIntegral << ", unresolved cells "
      << r.unresolvedCells << "\n";
  // Observed samples where the pdf integrates to 0: sample() and pdf() disagree outright.
  for (std::size_t c = 0; c < observed.size(); ++c)
    if (expected[c] == 0.0 && observed[c] > 0.0) {
      rep << "cell " << c << ": " << observed[c] << " samples where ∫pdf = 0\n";
      r.report = rep.str();
      r.significance = 0.01 / o.testCount;
      return r;
    }

  // Pool cells with small expected counts; a pool still below the threshold joins the
  // smallest regular cell.
  std::vector<std::size_t> order(observed.size());
  for (std::size_t c = 0; c < order.size(); ++c) order[c] = c;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });
  double poolObs = 0.0, poolExp = 0.0;
  std::vector<std::array<double, 2>> bins;
  for (std::size_t c : order) {
    if (expected[c] < o.minExpected || (poolExp > 0.0 && poolExp < o.minExpected)) {
      poolObs += observed[c];
      poolExp += expected[c];
    } else {
      bins.push_back({observed[c], expected[c]});
    }
  }
  if (poolExp > 0.0 || poolObs > 0.0) {
    if (poolExp < o.minExpected && !bins.empty()) {
      bins.front()[0] += poolObs;
      bins.front()[1] += poolExp;
    } else {
      bins.push_back({poolObs, poolExp});
    }
  }
  for (const auto& b : bins) {
    const double d = b[0] - b[1];
    r.statistic += d * d / b[1];
  }
  r.dof = static_cast<int>(bins.size()) - 1;
  r.pValue = chiSquarePValue(r.statistic, r.dof);
  r.significance = 0.01 / o.testCount;
  r.accepted = r.pValue >= r.significance && r.invalid == 0 && r.unresolvedCells == 0;
  rep << "chi2 = " << r.statistic << ", dof = " << r.dof << ", p = " << r.pValue
      << (r.accepted ? " (accepted)" : " (REJECTED)") << " at " << r.significance << "\n";
  if (!r.accepted) {
    rep << "observed / expected per cell (rows: cos theta from -1, columns: phi):\n";
    for (int i = 0; i < nz; ++i) {
      for (int j = 0; j < nphi; ++j) {
        const auto c = static_cast<std::size_t>(i * nphi + j);
        rep << static_cast<long>(observed[c]) << "/" << static_cast<long>(std::lround(expected[c]))
            << (j + 1 < nphi ? " " : "\n");
      }
    }
    rep << "other (delta + failed): " << observed.back() << "/" << expected.back() << "\n";
  }
  r.report = rep.str();
  return r;
}

// ∫ pdf dω over the sphere, to compare with the probability of a non-delta sample
// (chiSquare().nonDelta / sampleCount, binomial σ = √(p(1 − p)/N)).
inline double pdfIntegral(const Material& m, const glm::vec3& wo, const SampledWavelengths& lambda,
                          const BsdfContext& ctx, int cosThetaBins = 10, int phiBins = 20,
                          const QuadratureOptions& o = {}) {
  return integrateSphere(
      [&](const glm::vec3& wi) { return static_cast<double>(m.pdf(wo, wi, lambda, ctx)); },
      cosThetaBins, phiBins, o);
}

// ---------------------------------------------------------------- furnace
struct AlbedoOptions {
  int sampleCount = 100000;
  std::uint64_t seed = 11;
  bool quadrature = true;  // also integrate ∫ f |cos θi| dω numerically (non-delta part)
  int cosThetaBins = 10, phiBins = 20;
  QuadratureOptions quadratureOptions;
};

struct AlbedoResult {
  std::array<double, kWavelengthSamples> mean{}, stdErr{};  // all samples (delta included)
  std::array<double, kWavelengthSamples> nonDeltaMean{}, nonDeltaStdErr{};
  Channels quadrature{};     // ∫ f |cos θi| dω (non-delta)
  double maxWeight = 0.0;    // largest f |cos| / pdf of one sample
  int nonFinite = 0;         // samples or evaluations with NaN/Inf or negative values
  long unresolvedCells = 0;  // quadrature cells that ran out of evaluations
};

inline AlbedoResult albedo(const Material& m, const glm::vec3& wo, const SampledWavelengths& lambda,
                           const BsdfContext& ctx, const AlbedoOptions& o = {}) {
  AlbedoResult r;
  std::array<double, kWavelengthSamples> sum{}, sum2{}, nsum{}, nsum2{};
  Pcg32 rng(o.seed, 0xa1bed0);
  for (int n = 0; n < o.sampleCount; ++n) {
    const float uc = rng.uniform();
    const float u0 = rng.uniform(), u1 = rng.uniform();
    const std::optional<BsdfSample> s = m.sample(wo, uc, {u0, u1}, lambda, ctx);
    if (!s) continue;
    if (!detail::finiteNonNegative(s->f) || !std::isfinite(s->pdf) || !(s->pdf > 0.0f) ||
        !std::isfinite(s->wi.z)) {
      ++r.nonFinite;
      continue;
    }
    for (int c = 0; c < kWavelengthSamples; ++c) {
      const double w = static_cast<double>(s->f[c]) * std::abs(static_cast<double>(s->wi.z)) /
                       static_cast<double>(s->pdf);
      if (!std::isfinite(w)) {
        ++r.nonFinite;
        continue;
      }
      r.maxWeight = std::max(r.maxWeight, w);
      sum[static_cast<std::size_t>(c)] += w;
      sum2[static_cast<std::size_t>(c)] += w * w;
      if (!s->specular) {
        nsum[static_cast<std::size_t>(c)] += w;
        nsum2[static_cast<std::size_t>(c)] += w * w;
      }
    }
  }
  const double n = static_cast<double>(o.sampleCount);
  for (std::size_t c = 0; c < sum.size(); ++c) {
    r.mean[c] = sum[c] / n;
    r.stdErr[c] = std::sqrt(std::max(0.0, sum2[c] / n - r.mean[c] * r.mean[c]) / n);
    r.nonDeltaMean[c] = nsum[c] / n;
    r.nonDeltaStdErr[c] =
        std::sqrt(std::max(0.0, nsum2[c] / n - r.nonDeltaMean[c] * r.nonDeltaMean[c]) / n);
  }
  if (o.quadrature) {
    QuadratureOptions q = o.quadratureOptions;
    q.exhaustedCells = &r.unresolvedCells;
    r.quadrature = integrateSphere<Channels>(
        [&](const glm::vec3& wi) {
          const SampledSpectrum v = m.f(wo, wi, lambda, ctx);
          Channels out{};
          for (int c = 0; c < kWavelengthSamples; ++c) {
            if (!std::isfinite(v[c]) || v[c] < 0.0f) {
              ++r.nonFinite;
              continue;
            }
            out[static_cast<std::size_t>(c)] =
                static_cast<double>(v[c]) * std::abs(static_cast<double>(wi.z));
          }
          return out;
        },
        o.cosThetaBins, o.phiBins, q);
  }
  return r;
}

// ---------------------------------------------------------------- reciprocity
struct ReciprocityOptions {
  int pairs = 2000;
  std::uint64_t seed = 13;
  bool transmission = false;  // false: wi on wo's side; true: opposite sides
  float etaInside = 1.0f;     // index on the −z side (outside: 1), for transmission pairs
  double minValue = 1e-30;    // pairs where both values are below this (denormal range of
                              // float, no relative precision left) are not compared
};

struct ReciprocityResult {
  double maxRelError = 0.0;  // max over pairs and wavelengths of |a − b| / max(|a|, |b|)
  glm::vec3 worstWo{0.0f}, worstWi{0.0f};
  int nonZeroPairs = 0;  // pairs where f ≠ 0 (so the check is not vacuous)
  int nonFinite = 0;
};

inline ReciprocityResult reciprocity(const Material& m, const SampledWavelengths& lambda,
                                     const BsdfContext& ctx, const ReciprocityOptions& o = {}) {
  ReciprocityResult r;
  Pcg32 rng(o.seed, 0x7ec1);
  const auto uniformSphere = [&] {
    return direction(2.0 * static_cast<double>(rng.uniform()) - 1.0,
                     kTwoPi * static_cast<double>(rng.uniform()));
  };
  const auto n2 = [&](const glm::vec3& w) { return w.z > 0.0f ? 1.0f : o.etaInside * o.etaInside; };
  for (int p = 0; p < o.pairs; ++p) {
    const glm::vec3 wo = uniformSphere();
    glm::vec3 wi = uniformSphere();
    if ((wi.z * wo.z < 0.0f) != o.transmission) wi.z = -wi.z;
    const SampledSpectrum a = m.f(wo, wi, lambda, ctx) * (1.0f / n2(wo));
    const SampledSpectrum b = m.f(wi, wo, lambda, ctx) * (1.0f / n2(wi));
    if (!a.isFinite() || !b.isFinite()) {
      ++r.nonFinite;
      continue;
    }
    if (!a.isZero() || !b.isZero()) ++r.nonZeroPairs;
    for (int c = 0; c < kWavelengthSamples; ++c) {
      const double x = a[c], y = b[c];
      const double scale = std::max(std::abs(x), std::abs(y));
      if (scale <= o.minValue) continue;
      const double e = std::abs(x - y) / scale;
      if (e > r.maxRelError) {
        r.maxRelError = e;
        r.worstWo = wo;
        r.worstWi = wi;
      }
    }
  }
  return r;
}

}  // namespace camsim::bsdfcheck
