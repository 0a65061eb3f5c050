// Standard errors of the EMVA 1288 quantities of one photon-transfer measurement, and the
// fits across several ISO settings.
//
// Per ISO (N analysed photosites in H rows, L stack frames, n_K levels in the gain fit):
// | quantity    | standard error u |
// |-------------|------------------|
// | K           | the larger of the fit residuals' √(Σ(y − Kx)²/(n_K − 1)/Σx²) and sampling theory's √(Σx²·2σ⁴_y/N)/Σx², ⊕ u(σ²_y.dark)·Σx/Σx² (the offset) |
// | R           | the same for μ_y − μ_y.dark against μ_p (theory: u(μ_y) = √(σ²_y/(2N))), ⊕ u(μ_y.dark)·Σμ_p/Σμ_p² |
// | μ_y.dark    | √(σ²_y.dark/(N L) + σ²_row/(H L)) |
// | σ²_y.dark   | √(2/(L−1)·(σ_p⁴/N + 2σ_p²σ²_row/N + σ⁴_row/H)), σ²_p = σ²_y.dark − σ²_row |
// | μ_p.sat     | (w + step)/√12: w = the μ_p span of the levels whose σ²_y is within 2√2·√(2/N)·σ²_max of the maximum, step = the level spacing there |
// | s²_y (DSNU, PRNU) | s²_measured·√(2/(N − 1)) (independent photosites) |
// | LE          | rms over the 5–95 % levels of 100·√(σ²_y/(2N))/(μ_y − μ_y.dark) |
// | the rest    | propagated to first order from (K, R, σ²_y.dark, μ_p.sat, s²'s), taken as independent (η = R/K, σ_d, μ_e.sat, μ_e.clip, SNR_max, μ_p.min, DR, DSNU, PRNU) |
//
// Across ISOs (IsoPoint per measured ISO):
//   conversion-gain segments: consecutive ISOs stay in one segment while g = K/ISO agrees,
//   |g_i+1 − g_i| ≤ 4·√(u_i² + u_i+1²) or within 1 %; per segment g = weighted mean of K/ISO
//   dark-noise split: y_i = σ²_y.dark − 1/12 − σ²_row = K_i²·σ²_pre,s(i) + σ²_post, one σ_pre per
//   segment and one σ_post, weighted least squares (w = 1/u²(y_i), u²(y) = u²(σ²_y.dark) +
//   u²(σ²_row) + (2Kσ²_pre·u_K)²), covariance (AᵀWA)⁻¹·max(1, χ²/dof). σ_pre includes the dark
//   current's shot noise (both scale with K²).
#pragma once

#include <vector>

#include "sensor/model/dark_frame_analysis.h"
#include "sensor/model/photon_transfer.h"

namespace camsim {

struct PtcUncertainty {  // standard errors, units as in PtcResult
  double systemGainK = 0.0, responsivityR = 0.0, quantumEfficiency = 0.0;
  double muYDark = 0.0, varYDark = 0.0, sigmaYDark = 0.0, darkNoiseE = 0.0;
  double muPSat = 0.0, muESat = 0.0, muEClip = 0.0, snrMaxDb = 0.0;
  double muPMin = 0.0, dynamicRangeDb = 0.0;
  double dsnuE = 0.0, prnuPercent = 0.0, linearityErrorPercent = 0.0;
};

// Needs r.data.pixels, r.data.rows and the dark analysis (measurePhotonTransfer fills them).
PtcUncertainty photonTransferUncertainty(const PtcResult& r);

struct IsoPoint {
  double iso = 0.0;
  Estimate systemGainK;   // DN/e⁻
  Estimate darkVariance;  // σ²_y.dark − 1/12 − σ²_row, DN²
};
IsoPoint isoPoint(const PtcResult& r, const PtcUncertainty& u);

struct GainSegment {
  double isoMin = 0.0, isoMax = 0.0;
  int count = 0;        // ISOs in it
  Estimate gainPerIso;  // g = K/ISO, DN/e⁻ per ISO unit
  Estimate sigmaPreE;   // from the split (value 0, uncertainty 0 when not fitted)
  bool sigmaPreFitted = false;
};

struct IsoFit {
  std::vector<GainSegment> segments;  // increasing ISO
  bool splitFitted = false;           // enough ISOs: count ≥ segments + 1
  Estimate sigmaPostDn;
  double chi2 = 0.0;
  int dof = 0;
};

// points in increasing ISO.
IsoFit fitAcrossIsos(const std::vector<IsoPoint>& points);

// σ_d at an ISO from the fit (e⁻): √(σ²_pre,s + (σ²_post + σ²_row)/K²), K = g_s·ISO of its
// segment, σ_row the temporal row noise at that ISO (DN; measured, not part of the fit).
double fittedDarkNoiseE(const IsoFit& fit, double iso, double rowNoiseDn = 0.0);

}  // namespace camsim
