// The EMVA 1288 Release 4.0 Linear measurement and analysis; see photon_transfer.h.
#include "sensor/model/photon_transfer.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <thread>

#include "sensor/base/check.h"
#include "sensor/base/counter_rng.h"
#include "sensor/base/image.h"
#include "sensor/base/input_error.h"
#include "sensor/model/sensor_model.h"

namespace camsim {
namespace {

constexpr double kPlanckJs = 6.62607015e-34;
constexpr double kLightSpeedMs = 299792458.0;
constexpr double kFitTop = 0.70;  // K and R: 0–70 % of saturation
constexpr double kLinearityLow = 0.05, kLinearityHigh = 0.95;

// Least squares through the origin: the slope of y = s·x.
double slopeThroughOrigin(const std::vector<double>& x, const std::vector<double>& y) {
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += x[i] * y[i];
    sxx += x[i] * x[i];
  }
  return sxx > 0.0 ? sxy / sxx : 0.0;
}

// Runs fn(i) for i in [0, n) on `threads` workers (0: all cores).
void parallelFor(int n, int threads, const std::function<void(int)>& fn) {
  int workers = threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency());
  workers = std::clamp(workers, 1, std::max(n, 1));
  std::atomic<int> next{0};
  auto work = [&] {
    for (int i = next++; i < n; i = next++) fn(i);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
}

// Stack statistics over L frames at one irradiation: mean, spatial variance of the mean
// image (s²_y.measured), mean per-pixel temporal variance (σ²_y.stack).
struct StackStatistics {
  double mean = 0.0, spatialVar = 0.0, temporalVar = 0.0;
};

StackStatistics stackStatistics(const std::vector<RawImage>& frames,
                                const std::vector<std::size_t>& pixels) {
  const std::size_t n = pixels.size();
  const double l = static_cast<double>(frames.size());
  CAMSIM_CHECK(n > 1 && frames.size() > 1);
  std::vector<double> sum(n, 0.0), sumSq(n, 0.0);
  for (const RawImage& f : frames)
    for (std::size_t i = 0; i < n; ++i) {
      const double v = f.dn[pixels[i]];
      sum[i] += v;
      sumSq[i] += v * v;
    }
  StackStatistics s;
  for (std::size_t i = 0; i < n; ++i) {
    const double m = sum[i] / l;
    s.mean += m;
    s.temporalVar += std::max(0.0, (sumSq[i] - l * m * m) / (l - 1.0));
  }
  s.mean /= static_cast<double>(n);
  s.temporalVar /= static_cast<double>(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double d = sum[i] / l - s.mean;
    s.spatialVar += d * d;
  }
  s.spatialVar /= static_cast<double>(n - 1);
  return s;
}

// Irradiation steps as fractions of the nominal saturation: a few geometric steps at the
// bottom (for the SNR curve), uniform steps to 85 %, fine steps over 85–105 % (the variance
// maximum lies a few shot-noise σ below the clipping point), then coarser up to maxFraction.
std::vector<double> levelFractions(int count, double maxFraction) {
  const int low = count / 10, high = count / 10, fine = count * 3 / 10;
  const int linear = count - low - high - fine;
  std::vector<double> f;
  for (int i = 0; i < low; ++i)
    f.push_back(1e-4 * std::pow(200.0, static_cast<double>(i) / static_cast<double>(low)));
  for (int i = 1; i <= linear; ++i) f.push_back(0.85 * i / linear);
  for (int i = 1; i <= fine; ++i) f.push_back(0.85 + 0.2 * i / fine);
  for (int i = 1; i <= high; ++i) f.push_back(1.05 + (maxFraction - 1.05) * i / high);
  std::sort(f.begin(), f.end());
  return f;
}

// Index of the largest temporal variance (the saturation point).
int saturationIndexOf(const std::vector<PtcLevel>& levels) {
  int best = 0;
  for (int i = 1; i < static_cast<int>(levels.size()); ++i)
    if (levels[static_cast<std::size_t>(i)].varY > levels[static_cast<std::size_t>(best)].varY)
      best = i;
  return best;
}

// The fit range: levels up to saturation with μ_y − μ_y.dark within [lo, hi]·(saturation's).
std::vector<std::size_t> levelsInRange(const PtcMeasurements& m, int sat, double lo, double hi) {
  const double ySat = m.levels[static_cast<std::size_t>(sat)].muY - m.muYDark;
  std::vector<std::size_t> in;
  for (std::size_t i = 0; i <= static_cast<std::size_t>(sat); ++i) {
    const double y = m.levels[i].muY - m.muYDark;
    if (y >= lo * ySat && y <= hi * ySat) in.push_back(i);
  }
  return in;
}

// EMVA linearity: weighted fit y = a·x + b minimising Σ((y − a·x − b)/y)², then half the
// spread of the relative deviations, in %.
double linearityError(const PtcMeasurements& m, int sat) {
  double sw = 0, swx = 0, swxx = 0, swy = 0, swxy = 0;
  std::vector<std::pair<double, double>> xy;
  for (std::size_t i : levelsInRange(m, sat, kLinearityLow, kLinearityHigh)) {
    const double x = m.levels[i].muP, y = m.levels[i].muY - m.muYDark;
    if (!(y > 0.0)) continue;
    const double w = 1.0 / (y * y);
    sw += w, swx += w * x, swxx += w * x * x, swy += w * y, swxy += w * x * y;
    xy.emplace_back(x, y);
  }
  const double det = sw * swxx - swx * swx;
  if (xy.size() < 3 || !(det > 0.0)) return 0.0;
  const double a = (sw * swxy - swx * swy) / det, b = (swxx * swy - swx * swxy) / det;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& [x, y] : xy) {
    const double fit = a * x + b, d = 100.0 * (y - fit) / fit;
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  return 0.5 * (hi - lo);
}

}  // namespace

PairStatistics pairStatistics(const RawImage& a, const RawImage& b,
                              const std::vector<std::size_t>& pixels) {
  CAMSIM_CHECK(!pixels.empty() && a.dn.size() == b.dn.size());
  const double n = static_cast<double>(pixels.size());
  double sa = 0.0, sb = 0.0;
  for (std::size_t p : pixels) sa += a.dn[p], sb += b.dn[p];
  const double ma = sa / n, mb = sb / n;
  double ss = 0.0;
  for (std::size_t p : pixels) {
    const double d = (static_cast<double>(a.dn[p]) - ma) - (static_cast<double>(b.dn[p]) - mb);
    ss += d * d;
  }
  return {0.5 * (ma + mb), ss / (2.0 * n)};
}

double modelSnr(double muP, double eta, double darkNoiseE, double systemGainK) {
  const double e = eta * muP;
  return e / std::sqrt(darkNoiseE * darkNoiseE +
                       kPtcQuantisationVarDn2 / (systemGainK * systemGainK) + e);
}

PtcResult analysePhotonTransfer(const PtcMeasurements& data) {
  CAMSIM_CHECK(data.levels.size() >= 3 && data.spatialFrames >= 1);
  PtcResult r;
  r.data = data;
  r.saturationIndex = saturationIndexOf(data.levels);
  const std::vector<std::size_t> fit =
      levelsInRange(data, r.saturationIndex, -std::numeric_limits<double>::infinity(), kFitTop);
  std::vector<double> signal, variance, photons;
  for (std::size_t i : fit) {
    signal.push_back(data.levels[i].muY - data.muYDark);
    variance.push_back(data.levels[i].varY - data.varYDark);
    photons.push_back(data.levels[i].muP);
  }
  r.gainFitCount = fit.empty() ? 0 : static_cast<int>(fit.back()) + 1;
  r.systemGainK = slopeThroughOrigin(signal, variance);
  r.responsivityR = slopeThroughOrigin(photons, signal);
  const double k = r.systemGainK;
  r.quantumEfficiency = k > 0.0 ? r.responsivityR / k : 0.0;
  // The 0.24 DN² floor is σ_d's (EMVA 1288's); σ_y.dark is the measured √σ²_y.dark (found by
  // probing: a noiseless sensor reported σ²_y.dark 0 beside σ_y.dark 0.49).
  const double darkVar = std::max(data.varYDark, kPtcMinDarkVarDn2);
  r.sigmaYDark = std::sqrt(std::max(data.varYDark, 0.0));
  r.darkNoiseE = std::sqrt(darkVar - kPtcQuantisationVarDn2) / k;
  r.muPSat = data.levels[static_cast<std::size_t>(r.saturationIndex)].muP;
  r.muESat = r.quantumEfficiency * r.muPSat;
  double maxY = data.levels.front().muY;
  for (const PtcLevel& lv : data.levels) maxY = std::max(maxY, lv.muY);
  r.muEClip = (maxY - data.muYDark) / k;
  r.snrMax = std::sqrt(r.muESat);
  r.snrMaxDb = 20.0 * std::log10(r.snrMax);
  r.muEMin = 0.5 + std::sqrt(0.25 + darkVar / (k * k));
  r.muPMin = r.muEMin / r.quantumEfficiency;
  r.dynamicRange = r.muPSat / r.muPMin;
  r.dynamicRangeDb = 20.0 * std::log10(r.dynamicRange);
  const double l = static_cast<double>(data.spatialFrames);
  const double s2Dark = std::max(0.0, data.darkSpatialVar - data.darkStackVar / l);
  const double s2Bright = std::max(0.0, data.brightSpatialVar - data.brightStackVar / l);
  r.dsnuE = std::sqrt(s2Dark) / k;
  const double brightSignal = data.brightMuY - data.muYDark;
  r.prnuPercent =
      brightSignal > 0.0 ? 100.0 * std::sqrt(std::max(0.0, s2Bright - s2Dark)) / brightSignal : 0.0;
  r.linearityErrorPercent = linearityError(data, r.saturationIndex);
  for (PtcLevel& lv : r.data.levels)
    lv.snr = lv.varY > 0.0 ? (lv.muY - data.muYDark) / std::sqrt(lv.varY) : 0.0;
  return r;
}

int photonTransferChannel(const SensorSpec& sensor, double wavelengthNm) {
  int best = 0;
  const float lambda = static_cast<float>(wavelengthNm);
  for (std::size_t c = 1; c < sensor.qe.size(); ++c)
    if (sensor.qe[c](lambda) > sensor.qe[static_cast<std::size_t>(best)](lambda))
      best = static_cast<int>(c);
  return best;
}

std::uint64_t photonTransferSeed(const SensorSpec& sensor, const PtcOptions& options) {
  const double iso = photonTransferIso(sensor, options);
  if (iso == sensor.baseIso) return options.seed;
  return streamKey(options.seed, std::bit_cast<std::uint64_t>(iso));
}

PtcResult measurePhotonTransfer(const SensorSpec& sensor, const PtcOptions& options) {
  CAMSIM_CHECK(options.width >= 2 && options.height >= 2 && options.levels >= 50 &&
               options.spatialFrames >= 2 && options.maxSaturationFraction > 1.05);
  const SourceLocation where{sensor.sourceName(), 0, 0};
  if (sensor.noiseless)
    throw InputError(where, "",
                     "a noiseless sensor has no photon transfer curve (no temporal noise)");
  const PtcConfigured nominal = configuredPhotonTransfer(sensor, options);
  if (!(nominal.quantumEfficiency > 0.0))
    throw InputError(where, "qe",
                     "zero quantum efficiency at " + std::to_string(options.wavelengthNm) + " nm");
  const int channel = photonTransferChannel(sensor, options.wavelengthNm);

  // Expected electrons per photon for each photosite, and the analysed photosites.
  const int w = options.width, h = options.height;
  std::vector<float> eta(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  std::vector<std::size_t> pixels;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int c = sensor.cfa.channelAt(x, y);
      const std::size_t i =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
      const double qe = static_cast<std::size_t>(c) < sensor.qe.size()
                            ? static_cast<double>(sensor.qe[static_cast<std::size_t>(c)](
                                  static_cast<float>(options.wavelengthNm)))
                            : 0.0;
      eta[i] = static_cast<float>(sensor.fillFactor * qe);
      if (c == channel) pixels.push_back(i);
    }
  // A layout whose photosites carry no single channel (a stacked sensor: cfa xyz) leaves
  // none to analyse; the statistics below need two (found by probing: a check failed).
  if (pixels.size() < 2)
    throw InputError(where, "cfa",
                     "no photosites of channel " + std::to_string(channel) +
                         " to measure (a stacked layout such as xyz has no photon-transfer "
                         "measurement here; docs/ptc.md)");
  const ExposureSettings settings{options.exposureTimeS, photonTransferIso(sensor, options)};
  const std::uint64_t seed = photonTransferSeed(sensor, options);
  auto frame = [&](double muP, std::uint64_t index) {
    Image electrons(w, h, {"electrons"});
    for (std::size_t i = 0; i < eta.size(); ++i)
      electrons.pixels[i] = static_cast<float>(static_cast<double>(eta[i]) * muP);
    return expose(electrons, sensor, settings, NoiseMode::kFull, seed, index);
  };
  auto stackFrames = [&](double muP, std::uint64_t firstFrame) {
    std::vector<RawImage> frames(static_cast<std::size_t>(options.spatialFrames));
    parallelFor(options.spatialFrames, options.threads, [&](int i) {
      frames[static_cast<std::size_t>(i)] = frame(muP, firstFrame + static_cast<std::uint64_t>(i));
    });
    return frames;
  };

  // Frame indices: dark stack 0…L−1, level i: L + 2i and L + 2i + 1, 50 % stack after them.
  PtcMeasurements m;
  m.spatialFrames = options.spatialFrames;
  const std::vector<RawImage> darkFrames = stackFrames(0.0, 0);
  const StackStatistics dark = stackStatistics(darkFrames, pixels);
  m.dark = analyseDarkFrames(darkFrames, pixels);
  m.pixels = pixels.size();
  m.rows = 0;
  for (std::size_t i = 0; i < pixels.size(); ++i)
    m.rows += i == 0 || pixels[i] / static_cast<std::size_t>(w) !=
                            pixels[i - 1] / static_cast<std::size_t>(w);
  m.muYDark = dark.mean;
  m.varYDark = dark.temporalVar;
  m.darkSpatialVar = dark.spatialVar;
  m.darkStackVar = dark.temporalVar;

  // Irradiation steps: E in W/m², μ_p = E·A·t_exp·λ₀/(hc) photons on the pixel area A.
  const double photonsPerJoule = options.wavelengthNm * 1e-9 / (kPlanckJs * kLightSpeedMs);
  const double areaTime = sensor.pixelPitchM * sensor.pixelPitchM * options.exposureTimeS;
  const double muPSatNominal = nominal.muESat / nominal.quantumEfficiency;
  const double irradianceSat = muPSatNominal / (areaTime * photonsPerJoule);
  const std::vector<double> fractions =
      levelFractions(options.levels, options.maxSaturationFraction);
  m.levels.resize(fractions.size());
  const auto l = static_cast<std::uint64_t>(options.spatialFrames);
  parallelFor(static_cast<int>(fractions.size()), options.threads, [&](int i) {
    const double e = fractions[static_cast<std::size_t>(i)] * irradianceSat;
    const double muP = e * areaTime * photonsPerJoule;
    const std::uint64_t first = l + 2 * static_cast<std::uint64_t>(i);
    const PairStatistics s = pairStatistics(frame(muP, first), frame(muP, first + 1), pixels);
    m.levels[static_cast<std::size_t>(i)] = {muP, s.mean, s.variance, 0.0, e};
  });

  // The 50 % stack: at half the measured saturation signal, through the measured R.
  const PtcResult sweep = analysePhotonTransfer(m);
  const double ySat = m.levels[static_cast<std::size_t>(sweep.saturationIndex)].muY - m.muYDark;
  const double muP50 =
      sweep.responsivityR > 0.0 ? 0.5 * ySat / sweep.responsivityR : 0.5 * muPSatNominal;
  const StackStatistics bright = stackStatistics(
      stackFrames(muP50, l + 2 * static_cast<std::uint64_t>(fractions.size())), pixels);
  m.brightMuY = bright.mean;
  m.brightSpatialVar = bright.spatialVar;
  m.brightStackVar = bright.temporalVar;

  PtcResult r = analysePhotonTransfer(m);
  r.channel = nominal.channel;
  r.wavelengthNm = options.wavelengthNm;
  r.exposureTimeS = options.exposureTimeS;
  r.iso = settings.iso;
  r.pixels = pixels.size();
  return r;
}

}  // namespace camsim
