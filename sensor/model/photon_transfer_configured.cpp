// What a sensor's configuration implies for the EMVA 1288 quantities at one ISO
// (PtcConfigured, photon_transfer.h), from noiseAtIso (sensor_noise.h):
//
// | quantity      | configured value |
// |---------------|------------------|
// | K             | noiseAtIso(iso).systemGainK, DN/e⁻ |
// | η             | fill factor · QE_c(λ₀) |
// | σ²_y.dark     | K²(σ_pre² + μ_d) + σ_R² + σ²_row + 1/12, DN² (μ_d = dark current · t_exp) |
// | σ_d           | √(σ_pre² + μ_d + (σ_R² + σ²_row)/K²), e⁻ |
// | σ_read        | √(K²(σ_pre² + μ_d + dsnu²) + σ_R² + 1/12), DN: what the row-mean-removed residuals hold (ELD's bias frames: DSNU included) |
// | μ_e.clip      | saturationElectrons(iso) |
// | μ_e.sat       | the maximum of the clipped-normal temporal variance (below) |
// | DSNU, PRNU    | √(dsnu² + row FPN² + column FPN²), e⁻; prnu, % |
// σ_R² = σ_post² (Gaussian) or s²·v(λ) (Tukey-λ).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "sensor/model/photon_transfer.h"
#include "sensor/model/sensor_noise.h"

namespace camsim {
namespace {

// The mean temporal variance (e⁻²) of photosites clipped at `clip` electrons when μ
// photo-electrons are expected and readE e⁻ of signal-independent noise is added: the
// clipped-normal variance averaged over the PRNU gain and the offset patterns (21 × 21 nodes
// over ±4σ).
double clippedVariance(const SensorSpec& s, double mu, double darkE, double readE, double offsetSd,
                       double clip) {
  double sum = 0.0, weights = 0.0;
  for (int i = 0; i < 21; ++i)
    for (int j = 0; j < 21; ++j) {
      const double zi = -4.0 + 0.4 * i, zj = -4.0 + 0.4 * j;
      const double w = std::exp(-0.5 * (zi * zi + zj * zj));
      const double g = 1.0 + s.prnuFraction * zi, n = mu + darkE;
      const double sd = std::sqrt(g * g * n + readE * readE);
      const double t = (clip - g * n - offsetSd * zj) / sd;
      const double pdf = std::exp(-0.5 * t * t) / std::sqrt(2.0 * std::numbers::pi);
      const double tail = 0.5 * std::erfc(t / std::sqrt(2.0));
      const double ey = -pdf + t * tail, ey2 = (1.0 - tail) - t * pdf + t * t * tail;
      sum += w * sd * sd * std::max(0.0, ey2 - ey * ey);
      weights += w;
    }
  return sum / weights;
}

// Where that variance is largest (golden-section search; it is unimodal below the clip).
double varianceMaximumE(const SensorSpec& s, double darkE, double readE, double offsetSd,
                        double clip) {
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = 0.5 * clip, b = clip;
  for (int i = 0; i < 80; ++i) {
    const double x1 = b - r * (b - a), x2 = a + r * (b - a);
    if (clippedVariance(s, x1, darkE, readE, offsetSd, clip) <
        clippedVariance(s, x2, darkE, readE, offsetSd, clip))
      a = x1;
    else
      b = x2;
  }
  return 0.5 * (a + b);
}

}  // namespace

double photonTransferIso(const SensorSpec& sensor, const PtcOptions& options) {
  return options.iso > 0.0 ? options.iso : sensor.baseIso;
}

PtcConfigured configuredPhotonTransfer(const SensorSpec& sensor, const PtcOptions& options) {
  PtcConfigured c;
  const int ch = photonTransferChannel(sensor, options.wavelengthNm);
  c.channel = static_cast<std::size_t>(ch) < sensor.cfa.channels.size()
                  ? sensor.cfa.channels[static_cast<std::size_t>(ch)]
                  : "?";
  c.iso = photonTransferIso(sensor, options);
  const NoiseAtIso n = noiseAtIso(sensor, c.iso);
  c.highConversionGain = n.highConversionGain;
  c.systemGainK = n.systemGainK;
  c.quantumEfficiency =
      sensor.qe.empty()
          ? 0.0
          : sensor.fillFactor * static_cast<double>(sensor.qe[static_cast<std::size_t>(ch)](
                                    static_cast<float>(options.wavelengthNm)));
  const double k = c.systemGainK, e = c.quantumEfficiency;
  const double darkE = sensor.darkCurrentAtTemperature() * options.exposureTimeS;
  const double postVar = n.postReadVarianceDn2(), rowVar = n.rowNoiseDn * n.rowNoiseDn;
  c.readPreE = n.readPreE;
  c.readPreDarkE = std::sqrt(n.readPreE * n.readPreE + darkE);
  c.readPostDn = std::sqrt(postVar);
  c.rowNoiseDn = n.rowNoiseDn;
  c.tukey = n.shape == ReadNoiseShape::kTukeyLambda && n.tukeyScaleDn > 0.0;
  c.tukeyLambda = n.tukeyLambda;
  c.tukeyScaleDn = n.tukeyScaleDn;
  c.darkNoiseE = std::sqrt(c.readPreDarkE * c.readPreDarkE + (postVar + rowVar) / (k * k));
  c.darkVarianceDn2 =
      k * k * c.readPreDarkE * c.readPreDarkE + postVar + rowVar + kPtcQuantisationVarDn2;
  c.readGaussianDn =
      std::sqrt(k * k * (c.readPreDarkE * c.readPreDarkE + sensor.dsnuE * sensor.dsnuE) + postVar +
                kPtcQuantisationVarDn2);
  c.muESat = sensor.saturationElectrons(c.iso);
  // The black offsets of the analysed channel's tile positions are a fixed pattern too: their
  // spread over those photosites (DN, over K) is DSNU (found by probing: eld-canon-5d4's G1
  // and G2 offsets, ±0.39 DN, measured 1.77 e⁻ against a configured 0).
  double offsetSum = 0.0, offsetSquares = 0.0;
  int offsetCount = 0;
  for (std::size_t pos = 0; pos < n.blackOffsetsDn.size() && pos < sensor.cfa.tile.size(); ++pos)
    if (sensor.cfa.tile[pos] == ch) {
      offsetSum += n.blackOffsetsDn[pos];
      offsetSquares += n.blackOffsetsDn[pos] * n.blackOffsetsDn[pos];
      ++offsetCount;
    }
  const double offsetMean = offsetCount ? offsetSum / offsetCount : 0.0;
  const double offsetVarE =
      offsetCount ? std::max(0.0, offsetSquares / offsetCount - offsetMean * offsetMean) / (k * k)
                  : 0.0;
  c.dsnuE = std::sqrt(sensor.dsnuE * sensor.dsnuE + sensor.rowFpnE * sensor.rowFpnE +
                      sensor.columnFpnE * sensor.columnFpnE + offsetVarE);
  const double readE = std::sqrt(n.readPreE * n.readPreE + (postVar + rowVar) / (k * k));
  c.muESatEmva = varianceMaximumE(sensor, darkE, readE, c.dsnuE, c.muESat);
  const double muEMin =
      0.5 + std::sqrt(0.25 + c.darkNoiseE * c.darkNoiseE + kPtcQuantisationVarDn2 / (k * k));
  c.muPMin = muEMin / e;
  c.dynamicRangeDb = 20.0 * std::log10(c.muESatEmva / muEMin);
  c.snrMaxDb = 10.0 * std::log10(c.muESatEmva);
  c.prnuPercent = 100.0 * sensor.prnuFraction;
  return c;
}

double darkClippedFraction(const PtcConfigured& c, const SensorSpec& sensor,
                           const PtcOptions& options) {
  const double k = c.systemGainK;
  const double mean =
      sensor.blackLevelDn + k * sensor.darkCurrentAtTemperature() * options.exposureTimeS;
  const double sigma = std::sqrt(c.darkVarianceDn2 + k * k * c.dsnuE * c.dsnuE);
  if (!(sigma > 0.0)) return mean > 0.0 ? 0.0 : 1.0;
  return 0.5 * std::erfc(mean / (sigma * std::numbers::sqrt2));
}

}  // namespace camsim
