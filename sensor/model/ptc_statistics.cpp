// Standard errors and the fits across ISOs; ptc_statistics.h has the formulas.
#include "sensor/model/ptc_statistics.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "sensor/base/check.h"

namespace camsim {
namespace {

constexpr double kSegmentZ = 4.0, kSegmentRelative = 0.01;

// First-order propagation of independent uncertainties u through f (central differences).
double propagate(const std::function<double(const std::vector<double>&)>& f,
                 const std::vector<double>& x, const std::vector<double>& u) {
  double var = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(u[i] > 0.0)) continue;
    const double h = 0.01 * u[i];
    std::vector<double> a = x, b = x;
    a[i] += h, b[i] -= h;
    const double d = (f(a) - f(b)) / (2.0 * h) * u[i];
    if (std::isfinite(d)) var += d * d;
  }
  return std::sqrt(var);
}

// Standard error of the slope of y = s·x through the origin, from the residuals.
double slopeError(const std::vector<double>& x, const std::vector<double>& y, double s) {
  double sxx = 0.0, ss = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += x[i] * x[i];
    ss += (y[i] - s * x[i]) * (y[i] - s * x[i]);
  }
  return x.size() > 1 && sxx > 0.0 ? std::sqrt(ss / static_cast<double>(x.size() - 1) / sxx) : 0.0;
}

// Solves the symmetric positive system M p = b in place (Gaussian elimination with partial
// pivoting) and returns M⁻¹ in `inverse`. False when singular.
bool solve(std::vector<std::vector<double>> m, std::vector<double>& b,
           std::vector<std::vector<double>>& inverse) {
  const std::size_t n = b.size();
  inverse.assign(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) inverse[i][i] = 1.0;
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t p = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::abs(m[r][c]) > std::abs(m[p][c])) p = r;
    if (!(std::abs(m[p][c]) > 1e-300)) return false;
    std::swap(m[p], m[c]), std::swap(b[p], b[c]), std::swap(inverse[p], inverse[c]);
    for (std::size_t r = 0; r < n; ++r) {
      if (r == c) continue;
      const double f = m[r][c] / m[c][c];
      for (std::size_t k = 0; k < n; ++k)
        m[r][k] -= f * m[c][k], inverse[r][k] -= f * inverse[c][k];
      b[r] -= f * b[c];
    }
  }
  for (std::size_t r = 0; r < n; ++r) {
    b[r] /= m[r][r];
    for (std::size_t k = 0; k < n; ++k) inverse[r][k] /= m[r][r];
  }
  return true;
}

Estimate rootOf(double square, double u) {
  if (!(square > 0.0)) return {0.0, std::sqrt(std::max(0.0, u))};
  const double v = std::sqrt(square);
  return {v, u / (2.0 * v)};
}

}  // namespace

PtcUncertainty photonTransferUncertainty(const PtcResult& r) {
  const PtcMeasurements& d = r.data;
  CAMSIM_CHECK(d.pixels > 1 && d.rows > 0 && !d.levels.empty());
  PtcUncertainty u;
  const double n = static_cast<double>(d.pixels), h = static_cast<double>(d.rows);
  const double l = static_cast<double>(d.spatialFrames);
  const double row2 = d.dark.rowTemporalDn.value * d.dark.rowTemporalDn.value;
  const double pix2 = std::max(0.0, d.varYDark - row2);
  u.muYDark = std::sqrt(d.varYDark / (n * l) + row2 / (h * l));
  u.varYDark =
      l > 1.0
          ? std::sqrt(2.0 / (l - 1.0) * (pix2 * pix2 / n + 2.0 * pix2 * row2 / n + row2 * row2 / h))
          : 0.0;
  u.sigmaYDark = r.sigmaYDark > 0.0 ? u.varYDark / (2.0 * r.sigmaYDark) : 0.0;

  // The two fits.
  std::vector<double> signal, variance, photons;
  for (int i = 0; i < r.gainFitCount; ++i) {
    const PtcLevel& lv = d.levels[static_cast<std::size_t>(i)];
    signal.push_back(lv.muY - d.muYDark);
    variance.push_back(lv.varY - d.varYDark);
    photons.push_back(lv.muP);
  }
  double sx = 0.0, sxx = 0.0, sp = 0.0, spp = 0.0;
  for (std::size_t i = 0; i < signal.size(); ++i)
    sx += signal[i], sxx += signal[i] * signal[i], sp += photons[i], spp += photons[i] * photons[i];
  // Sampling theory of each level's statistics: u(σ²_y) = √(2/N)·σ²_y (two-frame
  // difference), u(μ_y) = √(σ²_y/(2N)); propagated through the slopes.
  double theoryK = 0.0, theoryR = 0.0;
  for (int i = 0; i < r.gainFitCount; ++i) {
    const double v = d.levels[static_cast<std::size_t>(i)].varY;
    const auto j = static_cast<std::size_t>(i);
    theoryK += signal[j] * signal[j] * (2.0 / n) * v * v;
    theoryR += photons[j] * photons[j] * v / (2.0 * n);
  }
  theoryK = sxx > 0.0 ? std::sqrt(theoryK) / sxx : 0.0;
  theoryR = spp > 0.0 ? std::sqrt(theoryR) / spp : 0.0;
  const double uKfit = std::max(slopeError(signal, variance, r.systemGainK), theoryK);
  const double uKoff = sxx > 0.0 ? u.varYDark * sx / sxx : 0.0;
  u.systemGainK = std::hypot(uKfit, uKoff);
  const double uRoff = spp > 0.0 ? u.muYDark * sp / spp : 0.0;
  u.responsivityR =
      std::hypot(std::max(slopeError(photons, signal, r.responsivityR), theoryR), uRoff);
  u.quantumEfficiency = r.quantumEfficiency * std::hypot(u.responsivityR / r.responsivityR,
                                                         u.systemGainK / r.systemGainK);

  // Saturation: the span of the levels statistically tied with the maximum.
  const auto sat = static_cast<std::size_t>(r.saturationIndex);
  const double varMax = d.levels[sat].varY;
  const double tie = 2.0 * std::sqrt(2.0) * std::sqrt(2.0 / n) * varMax;
  double lo = d.levels[sat].muP, hi = lo;
  for (const PtcLevel& lv : d.levels)
    if (lv.varY >= varMax - tie) lo = std::min(lo, lv.muP), hi = std::max(hi, lv.muP);
  const double below = sat > 0 ? d.levels[sat].muP - d.levels[sat - 1].muP : 0.0;
  const double above = sat + 1 < d.levels.size() ? d.levels[sat + 1].muP - d.levels[sat].muP : 0.0;
  const double step = std::max(below, above);
  u.muPSat = (hi - lo + step) / std::sqrt(12.0);

  // Propagation through (K, R, σ²_y.dark, μ_p.sat).
  const std::vector<double> x = {r.systemGainK, r.responsivityR, d.varYDark, r.muPSat};
  const std::vector<double> ux = {u.systemGainK, u.responsivityR, u.varYDark, u.muPSat};
  const auto darkVar = [](double v) { return std::max(v, kPtcMinDarkVarDn2); };
  const auto muPMin = [&](const std::vector<double>& p) {
    return (0.5 + std::sqrt(0.25 + darkVar(p[2]) / (p[0] * p[0]))) * p[0] / p[1];
  };
  u.darkNoiseE = propagate(
      [&](const std::vector<double>& p) {
        return std::sqrt(darkVar(p[2]) - kPtcQuantisationVarDn2) / p[0];
      },
      x, ux);
  u.muESat = propagate([](const std::vector<double>& p) { return p[1] / p[0] * p[3]; }, x, ux);
  u.muEClip = r.muEClip * u.systemGainK / r.systemGainK;
  u.snrMaxDb = 10.0 / std::log(10.0) * u.muESat / r.muESat;
  u.muPMin = propagate(muPMin, x, ux);
  u.dynamicRangeDb = propagate(
      [&](const std::vector<double>& p) { return 20.0 * std::log10(p[3] / muPMin(p)); }, x, ux);

  // Spatial noise.
  const double s2 = std::sqrt(2.0 / (n - 1.0));
  const std::vector<double> y = {r.systemGainK, d.darkSpatialVar, d.brightSpatialVar};
  const std::vector<double> uy = {u.systemGainK, s2 * d.darkSpatialVar, s2 * d.brightSpatialVar};
  const auto s2Dark = [&](const std::vector<double>& p) {
    return std::max(0.0, p[1] - d.darkStackVar / l);
  };
  u.dsnuE =
      propagate([&](const std::vector<double>& p) { return std::sqrt(s2Dark(p)) / p[0]; }, y, uy);
  if (!(s2Dark(y) > 0.0)) u.dsnuE = std::sqrt(uy[1]) / r.systemGainK;  // at 0: one-sided
  const double brightSignal = d.brightMuY - d.muYDark;
  if (brightSignal > 0.0)
    u.prnuPercent = propagate(
        [&](const std::vector<double>& p) {
          const double s2b = std::max(0.0, p[2] - d.brightStackVar / l);
          return 100.0 * std::sqrt(std::max(0.0, s2b - s2Dark(p))) / brightSignal;
        },
        y, uy);
  if (brightSignal > 0.0 && !(r.prnuPercent > 0.0))  // at 0: one-sided
    u.prnuPercent = 100.0 * std::sqrt(std::hypot(uy[1], uy[2])) / brightSignal;

  // Linearity: the relative noise of the level means it is drawn from.
  const double ySat = d.levels[sat].muY - d.muYDark;
  double ss = 0.0;
  int count = 0;
  for (std::size_t i = 0; i <= sat; ++i) {
    const double s = d.levels[i].muY - d.muYDark;
    if (s < 0.05 * ySat || s > 0.95 * ySat) continue;
    const double rel = 100.0 * std::sqrt(d.levels[i].varY / (2.0 * n)) / s;
    ss += rel * rel;
    ++count;
  }
  u.linearityErrorPercent = count > 0 ? std::sqrt(ss / count) : 0.0;
  return u;
}

IsoPoint isoPoint(const PtcResult& r, const PtcUncertainty& u) {
  const Estimate& row = r.data.dark.rowTemporalDn;
  IsoPoint p;
  p.iso = r.iso;
  p.systemGainK = {r.systemGainK, u.systemGainK};
  p.darkVariance = {r.data.varYDark - kPtcQuantisationVarDn2 - row.value * row.value,
                    std::hypot(u.varYDark, 2.0 * row.value * row.uncertainty)};
  return p;
}

IsoFit fitAcrossIsos(const std::vector<IsoPoint>& points) {
  IsoFit fit;
  if (points.empty()) return fit;
  // Segments of constant K/ISO.
  std::vector<int> segmentOf;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double g = points[i].systemGainK.value / points[i].iso;
    const double ug = points[i].systemGainK.uncertainty / points[i].iso;
    bool same = false;
    if (i > 0) {
      const double g0 = points[i - 1].systemGainK.value / points[i - 1].iso;
      const double u0 = points[i - 1].systemGainK.uncertainty / points[i - 1].iso;
      same = std::abs(g - g0) <= kSegmentZ * std::hypot(ug, u0) ||
             std::abs(g - g0) <= kSegmentRelative * std::abs(g0);
    }
    if (!same) fit.segments.push_back({points[i].iso, points[i].iso, 0, {}, {}, false});
    GainSegment& s = fit.segments.back();
    s.isoMax = points[i].iso;
    ++s.count;
    segmentOf.push_back(static_cast<int>(fit.segments.size()) - 1);
  }
  for (std::size_t s = 0; s < fit.segments.size(); ++s) {
    double sw = 0.0, swg = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (segmentOf[i] != static_cast<int>(s)) continue;
      const double g = points[i].systemGainK.value / points[i].iso;
      const double ug = points[i].systemGainK.uncertainty / points[i].iso;
      const double w = ug > 0.0 ? 1.0 / (ug * ug) : 1.0;
      sw += w, swg += w * g;
    }
    fit.segments[s].gainPerIso = {swg / sw, 1.0 / std::sqrt(sw)};
  }

  // The split: parameters σ²_pre per segment, then σ²_post.
  const std::size_t np = fit.segments.size() + 1;
  if (points.size() < np) return fit;
  std::vector<double> params(np, 0.0);
  std::vector<std::vector<double>> inverse;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::vector<double>> m(np, std::vector<double>(np, 0.0));
    std::vector<double> b(np, 0.0);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double k = points[i].systemGainK.value;
      const auto s = static_cast<std::size_t>(segmentOf[i]);
      const double pre = std::max(0.0, params[s]);
      const double uy = std::hypot(points[i].darkVariance.uncertainty,
                                   2.0 * k * pre * points[i].systemGainK.uncertainty);
      const double w = uy > 0.0 ? 1.0 / (uy * uy) : 1.0;
      std::vector<double> a(np, 0.0);
      a[s] = k * k;
      a[np - 1] = 1.0;
      for (std::size_t p = 0; p < np; ++p) {
        b[p] += w * a[p] * points[i].darkVariance.value;
        for (std::size_t q = 0; q < np; ++q) m[p][q] += w * a[p] * a[q];
      }
    }
    if (!solve(m, b, inverse)) return fit;
    params = b;
    fit.chi2 = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double k = points[i].systemGainK.value;
      const auto s = static_cast<std::size_t>(segmentOf[i]);
      const double uy =
          std::hypot(points[i].darkVariance.uncertainty,
                     2.0 * k * std::max(0.0, params[s]) * points[i].systemGainK.uncertainty);
      const double res = points[i].darkVariance.value - (k * k * params[s] + params[np - 1]);
      fit.chi2 += uy > 0.0 ? res * res / (uy * uy) : 0.0;
    }
  }
  fit.dof = static_cast<int>(points.size() - np);
  const double scale = fit.dof > 0 ? std::max(1.0, fit.chi2 / fit.dof) : 1.0;
  for (std::size_t s = 0; s + 1 < np; ++s) {
    fit.segments[s].sigmaPreE = rootOf(params[s], std::sqrt(inverse[s][s] * scale));
    fit.segments[s].sigmaPreFitted = true;
  }
  fit.sigmaPostDn = rootOf(params[np - 1], std::sqrt(inverse[np - 1][np - 1] * scale));
  fit.splitFitted = true;
  return fit;
}

double fittedDarkNoiseE(const IsoFit& fit, double iso, double rowNoiseDn) {
  if (!fit.splitFitted || fit.segments.empty()) return std::numeric_limits<double>::quiet_NaN();
  const GainSegment* s = &fit.segments.front();
  for (const GainSegment& g : fit.segments)
    if (iso >= g.isoMin) s = &g;
  const double k = s->gainPerIso.value * iso;
  const double pre = s->sigmaPreE.value, post = fit.sigmaPostDn.value;
  return std::sqrt(pre * pre + (post * post + rowNoiseDn * rowNoiseDn) / (k * k));
}

}  // namespace camsim
