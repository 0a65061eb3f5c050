// Row noise, Tukey-λ PPCC and normal-probability-plot fits of dark frames; see
// dark_frame_analysis.h for the equations.
#include "sensor/model/dark_frame_analysis.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>

#include "sensor/base/check.h"
#include "sensor/model/sensor_noise.h"

namespace camsim {
namespace {

constexpr std::size_t kMaxOrderStatistics = 20001;
constexpr double kLambdaMin = -0.25, kLambdaMax = 1.0, kLambdaStep = 0.025;

// Evenly spaced order statistics of sorted `values` and their plotting positions.
struct ProbabilityPlot {
  std::vector<double> x, u;
};

ProbabilityPlot orderStatistics(const std::vector<double>& sorted) {
  ProbabilityPlot p;
  const std::size_t n = sorted.size();
  const std::size_t m = std::min(n, kMaxOrderStatistics);
  for (std::size_t j = 0; j < m; ++j) {
    const std::size_t k = m > 1 ? (j * (n - 1) + (m - 1) / 2) / (m - 1) : 0;
    p.x.push_back(sorted[k]);
    p.u.push_back((static_cast<double>(k) + 0.5) / static_cast<double>(n));
  }
  return p;
}

// Correlation and slope of x against q.
TukeyFit regress(const std::vector<double>& q, const std::vector<double>& x) {
  const double n = static_cast<double>(q.size());
  double mq = 0.0, mx = 0.0;
  for (std::size_t i = 0; i < q.size(); ++i) mq += q[i], mx += x[i];
  mq /= n, mx /= n;
  double sqq = 0.0, sxx = 0.0, sqx = 0.0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    const double a = q[i] - mq, b = x[i] - mx;
    sqq += a * a, sxx += b * b, sqx += a * b;
  }
  TukeyFit f;
  f.scale = sqq > 0.0 ? sqx / sqq : 0.0;
  f.correlation = sqq > 0.0 && sxx > 0.0 ? sqx / std::sqrt(sqq * sxx) : 0.0;
  return f;
}

TukeyFit tukeyAt(const ProbabilityPlot& p, double lambda) {
  std::vector<double> q(p.u.size());
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = tukeyQuantile(lambda, p.u[i]);
  TukeyFit f = regress(q, p.x);
  f.lambda = lambda;
  return f;
}

// Mean and standard error of the mean of batch values.
Estimate batchMean(const std::vector<double>& v, double full) {
  if (v.size() < 2) return {full, 0.0};
  double m = 0.0;
  for (double x : v) m += x;
  m /= static_cast<double>(v.size());
  double ss = 0.0;
  for (double x : v) ss += (x - m) * (x - m);
  const double b = static_cast<double>(v.size());
  return {full, std::sqrt(ss / (b - 1.0) / b)};
}

}  // namespace

double normalQuantile(double p) {
  CAMSIM_CHECK(p > 0.0 && p < 1.0);
  if (p > 0.5) return -normalQuantile(1.0 - p);
  // Start from Tukey-λ 0.14 (close to the normal), then Halley's method on Φ(x) − p.
  double x = 4.91 * (std::pow(p, 0.14) - std::pow(1.0 - p, 0.14));
  for (int i = 0; i < 60; ++i) {
    const double cdf = 0.5 * std::erfc(-x / std::numbers::sqrt2);
    const double pdf = std::exp(-0.5 * x * x) / std::sqrt(2.0 * std::numbers::pi);
    const double d = (cdf - p) / pdf;
    x -= d / (1.0 + 0.5 * x * d);
    if (std::abs(d) < 1e-15 * (1.0 + std::abs(x))) break;
  }
  return x;
}

TukeyFit fitTukeyLambda(std::vector<double>& values) {
  CAMSIM_CHECK(values.size() >= 3);
  std::sort(values.begin(), values.end());
  const ProbabilityPlot p = orderStatistics(values);
  TukeyFit best = tukeyAt(p, kLambdaMin);
  const int steps = static_cast<int>(std::lround((kLambdaMax - kLambdaMin) / kLambdaStep));
  for (int i = 1; i <= steps; ++i) {
    const TukeyFit f = tukeyAt(p, kLambdaMin + kLambdaStep * i);
    if (f.correlation > best.correlation) best = f;
  }
  // Golden section within one grid step either side of the best node.
  double a = std::max(kLambdaMin, best.lambda - kLambdaStep);
  double b = std::min(kLambdaMax, best.lambda + kLambdaStep);
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int i = 0; i < 30; ++i) {
    const double x1 = b - r * (b - a), x2 = a + r * (b - a);
    if (tukeyAt(p, x1).correlation < tukeyAt(p, x2).correlation)
      a = x1;
    else
      b = x2;
  }
  const TukeyFit refined = tukeyAt(p, 0.5 * (a + b));
  return refined.correlation > best.correlation ? refined : best;
}

TukeyFit fitNormal(std::vector<double>& values) {
  CAMSIM_CHECK(values.size() >= 3);
  std::sort(values.begin(), values.end());
  const ProbabilityPlot p = orderStatistics(values);
  std::vector<double> q(p.u.size());
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = normalQuantile(p.u[i]);
  return regress(q, p.x);
}

DarkFrameAnalysis analyseDarkFrames(const std::vector<RawImage>& frames,
                                    const std::vector<std::size_t>& pixels) {
  CAMSIM_CHECK(frames.size() >= 2 && pixels.size() >= 3);
  const std::size_t l = frames.size(), n = pixels.size();
  const auto width = static_cast<std::size_t>(frames.front().width);
  const double ld = static_cast<double>(l);
  // Rows and columns of the analysed photosites, in index order.
  std::map<std::size_t, std::vector<std::size_t>> rowsOf;  // row → positions in `pixels`
  std::map<std::size_t, std::vector<std::size_t>> colsOf;
  for (std::size_t i = 0; i < n; ++i) {
    rowsOf[pixels[i] / width].push_back(i);
    colsOf[pixels[i] % width].push_back(i);
  }
  // Per-photosite means over the frames, total temporal variance v_t.
  std::vector<double> mean(n, 0.0);
  for (const RawImage& f : frames)
    for (std::size_t i = 0; i < n; ++i) mean[i] += f.dn[pixels[i]];
  for (double& m : mean) m /= ld;
  double vt = 0.0;
  for (const RawImage& f : frames)
    for (std::size_t i = 0; i < n; ++i) {
      const double d = f.dn[pixels[i]] - mean[i];
      vt += d * d;
    }
  vt /= static_cast<double>(n) * (ld - 1.0);

  // Temporal row noise from the residuals' row means; the fixed pattern from the stack mean.
  DarkFrameAnalysis a;
  double vr = 0.0, perRow = 0.0;
  const int cfaRows = std::max(1, frames.front().cfa.height);
  std::map<std::size_t, std::vector<double>> classRowMeans;  // row mod CFA height → means
  for (const auto& [row, members] : rowsOf) {
    const double count = static_cast<double>(members.size());
    perRow += count;
    for (const RawImage& f : frames) {
      double s = 0.0;
      for (std::size_t i : members) s += f.dn[pixels[i]] - mean[i];
      vr += (s / count) * (s / count);
    }
    double m = 0.0;
    for (std::size_t i : members) m += mean[i];
    classRowMeans[row % static_cast<std::size_t>(cfaRows)].push_back(m / count);
  }
  const double h = static_cast<double>(rowsOf.size());
  vr /= h * (ld - 1.0);
  perRow /= h;
  const double shrink = perRow > 1.0 ? 1.0 - 1.0 / perRow : 1.0;
  const double row2 = (vr - vt / perRow) / shrink;
  const double uRow2 = vr * std::sqrt(2.0 / (h * (ld - 1.0))) / shrink;
  a.rowTemporalDn.value = std::sqrt(std::max(0.0, row2));
  a.rowTemporalDn.uncertainty =
      a.rowTemporalDn.value > 0.0 ? uRow2 / (2.0 * a.rowTemporalDn.value) : std::sqrt(uRow2);
  double ssRows = 0.0, dofRows = 0.0;
  for (const auto& [cls, means] : classRowMeans) {
    double m = 0.0;
    for (double v : means) m += v;
    m /= static_cast<double>(means.size());
    for (double v : means) ssRows += (v - m) * (v - m);
    dofRows += static_cast<double>(means.size()) - 1.0;
  }
  if (dofRows > 0.0) {
    const double s2 = ssRows / dofRows, fixed2 = s2 - vr / ld;
    const double u2 = s2 * std::sqrt(2.0 / std::max(1.0, dofRows));
    a.rowFixedDn.value = std::sqrt(std::max(0.0, fixed2));
    a.rowFixedDn.uncertainty =
        a.rowFixedDn.value > 0.0 ? u2 / (2.0 * a.rowFixedDn.value) : std::sqrt(u2);
  }

  // ELD's residuals: row mean of each frame removed, then the column pattern.
  std::vector<double> resid(n * l);
  for (std::size_t f = 0; f < l; ++f)
    for (const auto& [row, members] : rowsOf) {
      double s = 0.0;
      for (std::size_t i : members) s += frames[f].dn[pixels[i]];
      s /= static_cast<double>(members.size());
      for (std::size_t i : members) resid[f * n + i] = frames[f].dn[pixels[i]] - s;
    }
  for (const auto& [col, members] : colsOf) {
    double c = 0.0;
    for (std::size_t f = 0; f < l; ++f)
      for (std::size_t i : members) c += resid[f * n + i];
    c /= static_cast<double>(members.size()) * ld;
    for (std::size_t f = 0; f < l; ++f)
      for (std::size_t i : members) resid[f * n + i] -= c;
  }
  a.residuals = resid.size();

  // The fits on all residuals, and on B batches of frames for the standard errors.
  std::vector<double> all = resid;
  const TukeyFit tukey = fitTukeyLambda(all);
  const TukeyFit normal = fitNormal(all);
  const std::size_t batches = std::min<std::size_t>(4, l / 2);
  std::vector<double> lambdas, scales, tukeyCorr, sigmas, normalCorr;
  for (std::size_t b = 0; b < batches && batches >= 2; ++b) {
    std::vector<double> part;
    for (std::size_t f = b; f < l; f += batches)
      part.insert(part.end(), resid.begin() + static_cast<std::ptrdiff_t>(f * n),
                  resid.begin() + static_cast<std::ptrdiff_t>((f + 1) * n));
    const TukeyFit t = fitTukeyLambda(part);
    const TukeyFit g = fitNormal(part);
    lambdas.push_back(t.lambda), scales.push_back(t.scale), tukeyCorr.push_back(t.correlation);
    sigmas.push_back(g.scale), normalCorr.push_back(g.correlation);
  }
  a.tukeyLambda = batchMean(lambdas, tukey.lambda);
  a.tukeyScaleDn = batchMean(scales, tukey.scale);
  a.tukeyCorrelation = batchMean(tukeyCorr, tukey.correlation);
  a.readGaussianDn = batchMean(sigmas, normal.scale);
  a.normalCorrelation = batchMean(normalCorr, normal.correlation);
  return a;
}

}  // namespace camsim
