#include "sensor/model/sensor_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "sensor/base/check.h"
#include "sensor/base/counter_rng.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"

namespace camsim {

const char* noiseModeName(NoiseMode mode) {
  return enumName(mode).data();
}

std::optional<NoiseMode> noiseModeFromName(std::string_view name) {
  return enumFromName<NoiseMode>(name);
}

std::string noiseModeNames() {
  return enumNameList<NoiseMode>();
}
namespace {

// Domain tags, so that noise streams and pattern streams never share a key even when the
// noise seed equals the pattern seed.
constexpr std::uint64_t kNoiseDomain = 0x6e6f697365ull;     // "noise"
constexpr std::uint64_t kPatternDomain = 0x7061747465ull;   // "patte"
constexpr std::uint64_t kRowNoiseDomain = 0x726f776e6full;  // "rowno": temporal row noise
constexpr std::uint64_t kShotTag = 1, kReadTag = 2, kPostReadTag = 3;
constexpr std::uint64_t kPrnuTag = 1, kDsnuTag = 2, kRowTag = 3, kColumnTag = 4, kHotTag = 5,
                        kStuckTag = 6;

constexpr double kMaxPoissonMean = 0x1p52;              // larger means are clamped (see the header)
constexpr double kLogSqrt2Pi = 0.91893853320467274178;  // ½ log 2π

// δ(k) = log k! − [(k + ½) log k − k + ½ log 2π], Stirling's error, for k ≥ 1.
double stirlingError(double k) {
  if (k < 16.0) return std::lgamma(k + 1.0) - (k + 0.5) * std::log(k) + k - kLogSqrt2Pi;
  const double inv = 1.0 / k, inv2 = inv * inv;
  return inv * (1.0 / 12.0 - inv2 * (1.0 / 360.0 - inv2 * (1.0 / 1260.0 - inv2 / 1680.0)));
}

// k log(k/μ) + μ − k without cancellation when k ≈ μ: with v = (k − μ)/(k + μ) it equals
// (k − μ) v + 2k Σ_{j≥1} v^(2j+1)/(2j+1).
double deviance(double k, double mu) {
  if (std::abs(k - mu) < 0.1 * (k + mu)) {
    const double v = (k - mu) / (k + mu), v2 = v * v;
    double sum = (k - mu) * v;
    double term = 2.0 * k * v;
    for (int j = 1; j < 100; ++j) {
      term *= v2;
      const double next = sum + term / (2 * j + 1);
      if (next == sum) break;
      sum = next;
    }
    return sum;
  }
  return k * std::log(k / mu) + mu - k;
}

// log P(k; μ), accurate to a few ulps for every k and μ (no log k! − k log μ cancellation).
double logPoissonPmf(double k, double mu) {
  if (k == 0.0) return -mu;
  return -stirlingError(k) - deviance(k, mu) - 0.5 * std::log(k) - kLogSqrt2Pi;
}

// Inversion by sequential search: exact up to rounding, ~μ + 1 steps (used for μ < 10).
std::uint64_t poissonInversion(double mu, CounterRng& rng) {
  const double u = rng.uniformOpen();
  double p = std::exp(-mu), cdf = p;
  std::uint64_t k = 0;
  while (u > cdf) {
    ++k;
    p *= mu / static_cast<double>(k);
    cdf += p;
    if (p < cdf * 1e-17) break;  // rounding left the cdf just below u: the tail is empty
  }
  return k;
}

// Hörmann (1993), "The transformed rejection method for generating Poisson random
// variables", algorithm PTRS; exact (a rejection method) for μ ≥ 10.
std::uint64_t poissonPtrs(double mu, CounterRng& rng) {
  const double sqrtMu = std::sqrt(mu);
  const double b = 0.931 + 2.53 * sqrtMu;
  const double a = -0.059 + 0.02483 * b;
  const double invAlpha = 1.1239 + 1.1328 / (b - 3.4);
  const double vr = 0.9277 - 3.6224 / (b - 2.0);
  for (;;) {
    const double u = rng.uniformOpen() - 0.5;
    const double v = rng.uniformOpen();
    const double us = 0.5 - std::abs(u);  // > 0: the uniforms are never 0 or 1
    const double k = std::floor((2.0 * a / us + b) * u + mu + 0.43);
    if (us >= 0.07 && v <= vr) return static_cast<std::uint64_t>(k);
    if (k < 0.0 || (us < 0.013 && v > us)) continue;
    if (std::log(v * invAlpha / (a / (us * us) + b)) <= logPoissonPmf(k, mu))
      return static_cast<std::uint64_t>(k);
  }
}

std::uint64_t poisson(double mean, CounterRng& rng) {
  if (!(mean > 0.0)) return 0;
  mean = std::min(mean, kMaxPoissonMean);
  return mean < 10.0 ? poissonInversion(mean, rng) : poissonPtrs(mean, rng);
}

// A fixed-pattern N(0, 1) value: depends on the pattern seed and position only.
double patternNormal(std::uint64_t patternSeed, std::uint64_t tag, std::uint64_t x,
                     std::uint64_t y) {
  return CounterRng(streamKey(kPatternDomain, patternSeed, tag, x, y)).normal();
}

// A fixed-pattern uniform in (0, 1), for choosing hot and stuck photosites.
double patternUniform(std::uint64_t patternSeed, std::uint64_t tag, std::uint64_t x,
                      std::uint64_t y) {
  return CounterRng(streamKey(kPatternDomain, patternSeed, tag, x, y)).uniformOpen();
}

void checkSettings(const ExposureSettings& settings) {
  if (!(settings.iso > 0.0) || !std::isfinite(settings.iso))
    throw InputError({}, "iso", "ISO must be a finite number > 0");
  if (!(settings.exposureTimeS >= 0.0) || !std::isfinite(settings.exposureTimeS))
    throw InputError({}, "exposure_time", "exposure time must be a finite number ≥ 0");
}

// expose() with dark frames (dark_frames.h): shot noise and PRNU on the photo-electrons,
// then one whole recorded dark frame.
RawImage exposeWithDarkFrames(const Image& electrons, const SensorSpec& sensor,
                              const ExposureSettings& settings, std::uint64_t noiseSeed,
                              std::uint64_t frame, RawImage raw) {
  const DarkFrameSet& dark = *settings.darkFrames;
  if (dark.frames.empty()) throw InputError({}, "dark_frames", "the dark-frame set is empty");
  if (dark.width != raw.width || dark.height != raw.height)
    throw InputError({}, "dark_frames",
                     "dark frames of " + std::to_string(dark.width) + "×" +
                         std::to_string(dark.height) +
                         " photosites cannot be added to an image of " + std::to_string(raw.width) +
                         "×" + std::to_string(raw.height));
  if (dark.blackLevelDn != sensor.blackLevelDn)
    throw InputError({}, "dark_frames",
                     "the dark frames' black level " + formatShortest(dark.blackLevelDn) +
                         " DN differs from the sensor's " + formatShortest(sensor.blackLevelDn));
  const std::vector<std::uint16_t>& d = dark.frames[dark.frameFor(noiseSeed, frame)];
  const NoiseAtIso at = noiseAtIso(sensor, settings.iso);
  const double white = sensor.whiteLevelDn();
  for (int y = 0; y < raw.height; ++y) {
    const auto uy = static_cast<std::uint64_t>(y);
    for (int x = 0; x < raw.width; ++x) {
      const auto ux = static_cast<std::uint64_t>(x);
      double mu = static_cast<double>(electrons.at(x, y, 0));
      if (!(mu > 0.0)) mu = 0.0;  // also NaN
      CounterRng shot(streamKey(streamKey(kNoiseDomain, noiseSeed, frame, ux, uy), kShotTag));
      double n = static_cast<double>(poisson(std::min(mu, kMaxPoissonMean), shot));
      if (sensor.prnuFraction > 0.0)
        n *= 1.0 + sensor.prnuFraction * patternNormal(sensor.patternSeed, kPrnuTag, ux, uy);
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(raw.width) +
                            static_cast<std::size_t>(x);
      const double dn = std::floor(std::min(n, at.fullWellE) * at.systemGainK + d[i] + 0.5);
      raw.dn[i] = static_cast<std::uint16_t>(std::clamp(dn, 0.0, white));
    }
  }
  return raw;
}

}  // namespace

std::uint64_t samplePoisson(double mean, std::uint64_t key) {
  CounterRng rng(key);
  return poisson(mean, rng);
}

std::vector<RawImage> exposeChannels(const Image& expectedElectrons, const SensorSpec& sensor,
                                     const ExposureSettings& settings, NoiseMode mode,
                                     std::uint64_t noiseSeed, std::uint64_t frame) {
  if (expectedElectrons.channelCount() == 1)
    return {expose(expectedElectrons, sensor, settings, mode, noiseSeed, frame)};
  std::vector<RawImage> raws;
  for (int c = 0; c < expectedElectrons.channelCount(); ++c)
    raws.push_back(expose(expectedElectrons.channel(c), sensor, settings, mode,
                          noiseSeed + static_cast<std::uint64_t>(c) * 0x9e3779b9u, frame));
  return raws;
}

double expectedDn(double electrons, const SensorSpec& sensor, const ExposureSettings& settings) {
  checkSettings(settings);
  const double mu =
      std::max(0.0, electrons) + sensor.darkCurrentAtTemperature() * settings.exposureTimeS;
  const NoiseAtIso n = noiseAtIso(sensor, settings.iso);
  const double y = std::min(mu, n.fullWellE) * n.systemGainK;
  return std::clamp(y + sensor.blackLevelDn, 0.0, sensor.whiteLevelDn());
}

VarianceLine temporalVarianceLine(const SensorSpec& sensor, const ExposureSettings& settings) {
  checkSettings(settings);
  const NoiseAtIso n = noiseAtIso(sensor, settings.iso);
  // σ² = K²(μ_e + μ_d) + K²σ_pre² + σ_R² + σ_row², and μ_y − black = K(μ_e + μ_d).
  return {n.systemGainK, n.readVarianceDn2()};
}

std::vector<std::string> exposedNoiseTerms(const SensorSpec& sensor, double iso, NoiseMode mode) {
  checkSettings(ExposureSettings{0.0, iso});
  if (sensor.noiseless || mode == NoiseMode::kNone) return {};
  if (mode == NoiseMode::kPhoton) return {"shot"};
  if (sensor.darkFramesDir.empty()) return modelledNoiseTerms(sensor, iso);
  std::vector<std::string> terms = {"shot"};
  if (sensor.prnuFraction > 0.0) terms.emplace_back("prnu");
  terms.emplace_back("dark_frames");
  return terms;
}

std::optional<VarianceLine> exposedVarianceLine(const SensorSpec& sensor,
                                                const ExposureSettings& settings, NoiseMode mode) {
  VarianceLine line = temporalVarianceLine(sensor, settings);  // checks the settings
  if (sensor.noiseless || mode == NoiseMode::kNone) return std::nullopt;
  if (mode == NoiseMode::kPhoton) return VarianceLine{line.slopeDn, 0.0};
  if (!sensor.darkFramesDir.empty()) return std::nullopt;
  return line;
}

RawImage expose(const Image& expectedElectrons, const SensorSpec& sensor,
                const ExposureSettings& settings, NoiseMode mode, std::uint64_t noiseSeed,
                std::uint64_t frame) {
  CAMSIM_CHECK(expectedElectrons.channelCount() == 1);
  CAMSIM_CHECK(sensor.adcBits >= 1 && sensor.adcBits <= 16);
  checkSettings(settings);
  if (sensor.noiseless) mode = NoiseMode::kNone;
  const int width = expectedElectrons.width, height = expectedElectrons.height;

  RawImage raw;
  raw.width = width;
  raw.height = height;
  raw.dn.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
  raw.cfa = sensor.cfa;
  raw.blackLevelDn = sensor.blackLevelDn;
  raw.whiteLevelDn = sensor.whiteLevelDn();
  raw.adcBits = sensor.adcBits;
  if (mode == NoiseMode::kFull && settings.darkFrames)
    return exposeWithDarkFrames(expectedElectrons, sensor, settings, noiseSeed, frame,
                                std::move(raw));

  const NoiseAtIso at = noiseAtIso(sensor, settings.iso);
  const SensorNoiseSpec& ns = sensor.noise;
  const double darkE = sensor.darkCurrentAtTemperature() * settings.exposureTimeS;
  const double gain = at.systemGainK, fullWell = at.fullWellE;
  const double white = sensor.whiteLevelDn();
  const bool full = mode == NoiseMode::kFull;
  // Hot photosites' extra dark electrons (same temperature law as the dark current).
  const double hotE =
      ns.hotPixelFraction > 0.0
          ? sensor.darkAtTemperature(ns.hotPixelDarkCurrentEPerS) * settings.exposureTimeS
          : 0.0;
  const bool tukey = at.shape == ReadNoiseShape::kTukeyLambda && at.tukeyScaleDn > 0.0;

  // Row and column offsets (step 3), one N(0, 1) each, drawn once per image; the temporal
  // row noise (DN) once per row per frame; the black offsets per tile position.
  std::vector<double> rowOffset(static_cast<size_t>(height), 0.0);
  std::vector<double> columnOffset(static_cast<size_t>(width), 0.0);
  std::vector<double> rowNoise(static_cast<size_t>(height), 0.0);
  if (full && sensor.rowFpnE > 0.0) {
    for (int y = 0; y < height; ++y)
      rowOffset[static_cast<size_t>(y)] =
          sensor.rowFpnE *
          patternNormal(sensor.patternSeed, kRowTag, 0, static_cast<std::uint64_t>(y));
  }
  if (full && sensor.columnFpnE > 0.0) {
    for (int x = 0; x < width; ++x)
      columnOffset[static_cast<size_t>(x)] =
          sensor.columnFpnE *
          patternNormal(sensor.patternSeed, kColumnTag, static_cast<std::uint64_t>(x), 0);
  }
  if (full && at.rowNoiseDn > 0.0) {
    for (int y = 0; y < height; ++y)
      rowNoise[static_cast<size_t>(y)] =
          at.rowNoiseDn *
          CounterRng(streamKey(kRowNoiseDomain, noiseSeed, frame, static_cast<std::uint64_t>(y)))
              .normal();
  }
  const bool offsets = full && !at.blackOffsetsDn.empty();

  for (int y = 0; y < height; ++y) {
    const auto uy = static_cast<std::uint64_t>(y);
    for (int x = 0; x < width; ++x) {
      const auto ux = static_cast<std::uint64_t>(x);
      double mu = static_cast<double>(expectedElectrons.at(x, y, 0));
      if (!(mu > 0.0)) mu = 0.0;  // also NaN
      mu = std::min(mu, kMaxPoissonMean);
      double n = mu + darkE;  // step 1
      if (full && hotE > 0.0 &&
          patternUniform(sensor.patternSeed, kHotTag, ux, uy) < ns.hotPixelFraction)
        n += hotE;
      double post = 0.0;  // after the gain, DN
      if (mode != NoiseMode::kNone) {
        const std::uint64_t key = streamKey(kNoiseDomain, noiseSeed, frame, ux, uy);
        CounterRng shot(streamKey(key, kShotTag));
        n = static_cast<double>(poisson(n, shot));  // step 2
        if (full) {
          if (sensor.prnuFraction > 0.0)  // step 3
            n *= 1.0 + sensor.prnuFraction * patternNormal(sensor.patternSeed, kPrnuTag, ux, uy);
          if (sensor.dsnuE > 0.0)
            n += sensor.dsnuE * patternNormal(sensor.patternSeed, kDsnuTag, ux, uy);
          n += rowOffset[static_cast<size_t>(y)] + columnOffset[static_cast<size_t>(x)];
          if (at.readPreE > 0.0) n += at.readPreE * CounterRng(streamKey(key, kReadTag)).normal();
          // After the gain: read noise R, temporal row noise, black offsets.
          if (tukey)
            post = at.tukeyScaleDn *
                   tukeyQuantile(at.tukeyLambda,
                                 CounterRng(streamKey(key, kPostReadTag)).uniformOpen());
          else if (at.readPostDn > 0.0)
            post = at.readPostDn * CounterRng(streamKey(key, kPostReadTag)).normal();
          post += rowNoise[static_cast<size_t>(y)];
          if (offsets)
            post += at.blackOffsetsDn[static_cast<size_t>(
                (y % sensor.cfa.height) * sensor.cfa.width + x % sensor.cfa.width)];
        }
      }
      n = std::min(n, fullWell);                                            // step 5
      double dn = std::floor(n * gain + post + sensor.blackLevelDn + 0.5);  // steps 6, 7
      if (full && ns.stuckPixelFraction > 0.0 &&
          patternUniform(sensor.patternSeed, kStuckTag, ux, uy) < ns.stuckPixelFraction)
        dn = ns.stuckPixelValueDn;
      raw.dn[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)] =
          static_cast<std::uint16_t>(std::clamp(dn, 0.0, white));
    }
  }
  return raw;
}

}  // namespace camsim
