#include "integrator/measure/bench_metrics.h"

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace camsim {
namespace {

void checkComparable(const Image& a, const Image& b, int channel) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("images of different sizes: " + formatSize(a.width, a.height) +
                                " and " + formatSize(b.width, b.height));
  if (channel < 0 || channel >= a.channelCount() || channel >= b.channelCount())
    throw std::invalid_argument("channel " + std::to_string(channel) + " missing");
  if (a.width == 0 || a.height == 0) throw std::invalid_argument("empty image");
}

std::size_t pixelCount(const Image& image) {
  return static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
}

// Channel c of pixel i (row-major).
double valueAt(const Image& image, std::size_t i, int c) {
  return static_cast<double>(image.pixels[i * static_cast<std::size_t>(image.channelCount()) +
                                          static_cast<std::size_t>(c)]);
}

double channelMean(const Image& image, int channel) {
  double sum = 0.0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) sum += static_cast<double>(image.at(x, y, channel));
  return sum / (static_cast<double>(image.width) * static_cast<double>(image.height));
}

}  // namespace

ErrorMetrics compareImages(const Image& image, const Image& reference, int channel) {
  checkComparable(image, reference, channel);
  return relativeErrors(
      pixelCount(image),
      [&](std::size_t i) { return valueAt(image, i, channel) - valueAt(reference, i, channel); },
      [&](std::size_t i) { return valueAt(reference, i, channel); },
      channelMean(reference, channel));
}

ErrorMetrics referenceNoise(const Image& halfA, const Image& halfB, int channel) {
  checkComparable(halfA, halfB, channel);
  auto a = [&](std::size_t i) { return valueAt(halfA, i, channel); };
  auto b = [&](std::size_t i) { return valueAt(halfB, i, channel); };
  const double mean = 0.5 * (channelMean(halfA, channel) + channelMean(halfB, channel));
  return relativeErrors(
      pixelCount(halfA), [&](std::size_t i) { return 0.5 * (a(i) - b(i)); },
      [&](std::size_t i) { return 0.5 * (a(i) + b(i)); }, mean);
}

SlopeFit fitLogLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  SlopeFit fit;
  fit.slope = fit.intercept = std::numeric_limits<double>::quiet_NaN();
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0, syy = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
    if (!(x[i] > 0.0) || !(y[i] > 0.0) || !std::isfinite(x[i]) || !std::isfinite(y[i])) continue;
    const double lx = std::log10(x[i]), ly = std::log10(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    syy += ly * ly;
    ++n;
  }
  fit.points = n;
  const double dn = static_cast<double>(n);
  const double varX = sxx - sx * sx / dn, varY = syy - sy * sy / dn, cov = sxy - sx * sy / dn;
  if (n < 2 || !(varX > 0.0)) return fit;
  fit.slope = cov / varX;
  fit.intercept = (sy - fit.slope * sx) / dn;
  fit.r2 = varY > 0.0 ? cov * cov / (varX * varY) : 1.0;
  return fit;
}

SamplerSlopes fitRows(std::vector<BenchRow*>& rows) {
  SamplerSlopes s;
  std::vector<double> t, cpu, spp, err, mrae;
  for (BenchRow* r : rows) {
    s.scene = r->scene;
    s.sampler = r->sampler;
    r->inFit = r->error.rmse >= kFloorFactor * r->floor.rmse;
    if (!r->inFit) continue;
    t.push_back(r->seconds);
    cpu.push_back(r->cpuSeconds);
    spp.push_back(r->spp);
    err.push_back(r->error.rmse);
    mrae.push_back(r->error.mrae);
  }
  s.vsSeconds = fitLogLogSlope(t, err);
  s.vsCpuSeconds = fitLogLogSlope(cpu, err);
  s.vsSpp = fitLogLogSlope(spp, err);
  s.mraeVsSeconds = fitLogLogSlope(t, mrae);
  return s;
}

const std::vector<std::string>& benchCsvColumns() {
  static const std::vector<std::string> columns = {
      "scene",       "sampler",       "spp",          "width",    "height", "seconds",
      "cpu_seconds", "samples_per_s", "rays_per_s",   "rmse_rel", "mrae",   "ref_rmse_rel",
      "ref_mrae",    "in_fit",        "est_rmse_rel", "est_mrae"};
  return columns;
}

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string quoted = "\"";
  for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string formatBenchCsv(const std::vector<BenchRow>& rows) {
  std::ostringstream out;
  const auto& columns = benchCsvColumns();
  for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
  out << "\n";
  auto g = [](double v) { return formatNumber(v, 9); };
  // The render's own estimate needs two samples per pixel: empty below that (not "nan").
  auto estimate = [](double v) { return std::isfinite(v) ? formatNumber(v, 9) : std::string(); };
  for (const BenchRow& r : rows)
    out << csvField(r.scene) << "," << csvField(r.sampler) << "," << r.spp << "," << r.width << ","
        << r.height << "," << g(r.seconds) << "," << g(r.cpuSeconds) << ","
        << g(r.samplesPerSecond()) << "," << g(r.raysPerSecond()) << "," << g(r.error.rmse) << ","
        << g(r.error.mrae) << "," << g(r.floor.rmse) << "," << g(r.floor.mrae) << ","
        << (r.inFit ? 1 : 0) << "," << estimate(r.estimate.rmse) << "," << estimate(r.estimate.mrae)
        << "\n";
  return out.str();
}

double processCpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::string formatBenchTable(const std::vector<BenchRow>& rows) {
  char line[256];
  std::ostringstream out;
  std::snprintf(line, sizeof line, "%-13s %-11s %5s %9s %8s %10s %10s %10s %8s %s\n", "scene",
                "sampler", "spp", "seconds", "CPU-s", "samples/s", "rays/s", "rMSE", "MRAE", "fit");
  out << line;
  for (const BenchRow& r : rows) {
    std::snprintf(line, sizeof line, "%-13s %-11s %5d %9.3f %8.3f %10s %10s %10.3e %8.4f %s\n",
                  r.scene.c_str(), r.sampler.c_str(), r.spp, r.seconds, r.cpuSeconds,
                  formatRate(r.samplesPerSecond()).c_str(), formatRate(r.raysPerSecond()).c_str(),
                  r.error.rmse, r.error.mrae, r.inFit ? "*" : "");
    out << line;
  }
  return out.str();
}

ErrorMetrics errorBeyondFloor(const BenchRow& r) {
  const double mrae2 = r.error.mrae * r.error.mrae - r.floor.mrae * r.floor.mrae;
  return {r.error.rmse - r.floor.rmse, mrae2 > 0.0 ? std::sqrt(mrae2) : 0.0};
}

std::string formatEstimateTable(const std::vector<BenchRow>& rows) {
  char line[256];
  std::ostringstream out;
  std::snprintf(line, sizeof line, "%-13s %-11s %5s %11s %11s %6s %9s %9s %6s\n", "scene",
                "sampler", "spp", "rMSE-floor", "est rMSE", "ratio", "MRAE*", "est MRAE", "ratio");
  out << line;
  for (const BenchRow& r : rows) {
    if (!std::isfinite(r.estimate.rmse)) continue;
    const ErrorMetrics e = errorBeyondFloor(r);
    std::snprintf(line, sizeof line, "%-13s %-11s %5d %11.3e %11.3e %6.2f %9.4f %9.4f %6.2f\n",
                  r.scene.c_str(), r.sampler.c_str(), r.spp, e.rmse, r.estimate.rmse,
                  r.estimate.rmse / e.rmse, e.mrae, r.estimate.mrae, r.estimate.mrae / e.mrae);
    out << line;
  }
  return out.str();
}

std::string formatSlopeTable(const std::vector<SamplerSlopes>& slopes) {
  char line[256];
  std::ostringstream out;
  std::snprintf(line, sizeof line, "%-13s %-11s %16s %6s %6s %15s %14s %15s\n", "scene", "sampler",
                "slope rMSE/time", "R^2", "points", "slope rMSE/CPU", "slope rMSE/spp",
                "slope MRAE/time");
  out << line;
  for (const SamplerSlopes& s : slopes) {
    const bool ok = s.vsSeconds.points >= 2;
    std::snprintf(line, sizeof line, "%-13s %-11s %16s %6s %6d %15s %14s %15s\n", s.scene.c_str(),
                  s.sampler.c_str(), ok ? formatFixed(s.vsSeconds.slope, 3).c_str() : "n/a",
                  ok ? formatFixed(s.vsSeconds.r2, 3).c_str() : "", s.vsSeconds.points,
                  ok ? formatFixed(s.vsCpuSeconds.slope, 3).c_str() : "n/a",
                  ok ? formatFixed(s.vsSpp.slope, 3).c_str() : "n/a",
                  ok ? formatFixed(s.mraeVsSeconds.slope, 3).c_str() : "n/a");
    out << line;
  }
  return out.str();
}

std::vector<std::string_view> benchSamplers(bool adaptive) {
  std::vector<std::string_view> out = {"independent", "sobol"};
  if (adaptive) out.push_back(kAdaptiveSampler);
  return out;
}

namespace {

// CPU seconds (robust on a shared machine) at which the rows (one scene and sampler, by
// budget) reach `error` (of what `metric` picks), interpolated log-log between the two
// consecutive rows that bracket it; NaN outside.
template <typename Metric>
double secondsAtError(const std::vector<const BenchRow*>& rows, double error, Metric metric) {
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    const double e0 = metric(*rows[i]), e1 = metric(*rows[i + 1]);
    if (!(e0 >= error && error >= e1 && e0 > e1 && e1 > 0.0)) continue;
    const double f = std::log(e0 / error) / std::log(e0 / e1);
    return rows[i]->cpuSeconds * std::pow(rows[i + 1]->cpuSeconds / rows[i]->cpuSeconds, f);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

std::string ratioText(double adaptive, double fixed) {
  return std::isfinite(fixed) ? formatFixed(fixed, 3) + " " + formatFixed(adaptive / fixed, 3)
                              : "n/a";
}

}  // namespace

std::string formatAdaptiveTable(const std::vector<BenchRow>& rows) {
  char line[256];
  std::ostringstream out;
  std::snprintf(line, sizeof line, "%-13s %5s %8s %9s %10s %8s %20s %20s\n", "scene", "spp",
                "mean spp", "CPU-s", "rMSE", "MRAE", "Sobol' CPU-s, ratio", "Sobol' CPU-s, ratio");
  out << line;
  for (const BenchRow& r : rows) {
    if (r.sampler != kAdaptiveSampler) continue;
    std::vector<const BenchRow*> fixed;
    for (const BenchRow& f : rows)
      if (f.scene == r.scene && f.sampler == "sobol") fixed.push_back(&f);
    const double pixels = static_cast<double>(r.width) * static_cast<double>(r.height);
    const auto rmse = [](const BenchRow& b) { return b.error.rmse; };
    const auto mrae = [](const BenchRow& b) { return b.error.mrae; };
    std::snprintf(line, sizeof line, "%-13s %5d %8.1f %9.3f %10.3e %8.4f %20s %20s\n",
                  r.scene.c_str(), r.spp, static_cast<double>(r.samples) / pixels, r.cpuSeconds,
                  r.error.rmse, r.error.mrae,
                  ratioText(r.cpuSeconds, secondsAtError(fixed, r.error.rmse, rmse)).c_str(),
                  ratioText(r.cpuSeconds, secondsAtError(fixed, r.error.mrae, mrae)).c_str());
    out << line;
  }
  return out.str();
}

}  // namespace camsim
