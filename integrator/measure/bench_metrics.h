// `camsim bench`: error metrics, the log-log slope fit, and the table / CSV formats.
//
// Errors are on one channel of the film image: luminance Y (CIE 1931, the "Y" channel of
// the XYZ film), against a reference image r of the same size: rMSE and MRAE as
// error_estimate.h defines them (e = x − r), which every render also estimates of itself.
//
// A rendered reference has noise of its own. From two independent renders a, b of half the
// reference's samples each (r = (a + b)/2), (a − b)/2 has the same variance as r's error,
// so its rMSE / MRAE against r estimate the floor the measured errors cannot go below
// (referenceNoise()); measured rMSE ≈ the render's own + the floor.
//
// Slope: least squares of log rMSE on log seconds over the budgets whose rMSE is at least
// kFloorFactor × the floor (plain Monte Carlo gives −1: rMSE is a squared error). rMSE is
// dominated by rare very bright samples (a pixel whose reference is dark gets one hit of a
// small bright light: its error then falls as N⁻²); MRAE's slope (−0.5 for plain Monte
// Carlo) is printed next to it.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "integrator/render/error_estimate.h"
#include "sensor/base/format.h"
#include "sensor/base/image.h"

namespace camsim {

// Throws std::invalid_argument if the sizes differ or the channel is missing.
ErrorMetrics compareImages(const Image& image, const Image& reference, int channel);
// The floor: metrics of (a − b)/2 against (a + b)/2 (a, b: the two half references).
ErrorMetrics referenceNoise(const Image& halfA, const Image& halfB, int channel);

inline constexpr double kFloorFactor = 4.0;

struct SlopeFit {
  double slope = 0.0, intercept = 0.0;  // log10 y = intercept + slope·log10 x
  int points = 0;                       // 0 or 1: no fit (slope is NaN)
  double r2 = 0.0;
};
// Least squares on (log10 x, log10 y) over the pairs with x > 0, y > 0.
SlopeFit fitLogLogSlope(const std::vector<double>& x, const std::vector<double>& y);

struct BenchRow {
  std::string scene, sampler;
  int spp = 0;
  int width = 0, height = 0;
  double seconds = 0.0;     // wall time of the render
  double cpuSeconds = 0.0;  // this process's CPU time during it (all threads)
  std::uint64_t samples = 0, rays = 0;
  ErrorMetrics error;
  ErrorMetrics floor;  // the reference's own noise
  // The render's estimate of its own error (error_estimate.h); NaN below 2 spp.
  ErrorMetrics estimate{std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::quiet_NaN()};
  bool inFit = false;  // used for the slope (error ≥ kFloorFactor × floor)

  double samplesPerSecond() const {
    return seconds > 0.0 ? static_cast<double>(samples) / seconds : 0.0;
  }
  double raysPerSecond() const { return seconds > 0.0 ? static_cast<double>(rays) / seconds : 0.0; }
};

// Marks the rows of one scene and sampler that enter the fit, and fits them: rMSE
// against wall seconds, and for comparison against CPU seconds (robust when other
// processes share the cores) and against spp.
struct SamplerSlopes {
  std::string scene, sampler;
  SlopeFit vsSeconds, vsCpuSeconds, vsSpp;
  SlopeFit mraeVsSeconds;  // MRAE (robust to rare bright samples; −0.5 for plain Monte Carlo)
};
SamplerSlopes fitRows(std::vector<BenchRow*>& rows);

// The sweeps' samplers: "independent", "sobol", and with adaptive sampling
// kAdaptiveSampler (Sobol' numbers, adaptive_sampling.h), in that order.
inline constexpr std::string_view kAdaptiveSampler = "sobol+adaptive";
std::vector<std::string_view> benchSamplers(bool adaptive);
// Per kAdaptiveSampler row: the CPU time plain Sobol' rows of the same scene need for its
// rMSE (then for its MRAE), interpolated linearly in log error – log CPU seconds between the
// two budgets whose errors bracket it (n/a outside their range), and the row's CPU seconds
// ÷ that: below 1, adaptive sampling reached the error sooner.
std::string formatAdaptiveTable(const std::vector<BenchRow>& rows);

// The CSV columns, in order.
const std::vector<std::string>& benchCsvColumns();
std::string formatBenchCsv(const std::vector<BenchRow>& rows);
// A CSV field: quoted (with "" for ") when it holds a comma, a quote or a newline.
std::string csvField(const std::string& s);
// Fixed-width text tables as printed.
std::string formatBenchTable(const std::vector<BenchRow>& rows);
std::string formatSlopeTable(const std::vector<SamplerSlopes>& slopes);
// Each row's estimated error against its measured one with the reference's noise taken
// out: rMSE − floor rMSE, and √(MRAE² − floor MRAE²) (the floor adds in quadrature for
// Gaussian noise); ratio = estimate ÷ that.
std::string formatEstimateTable(const std::vector<BenchRow>& rows);
// The measured errors with the reference's noise taken out, as formatEstimateTable uses.
ErrorMetrics errorBeyondFloor(const BenchRow& row);

// User + system CPU time of this process (all threads), s.
double processCpuSeconds();

// "1.23 M" style rates; "%.3g"-style numbers.

}  // namespace camsim
