// The dark frames of a photon-transfer measurement, taken apart the way the low-light raw
// denoising literature does (ELD, Wei et al. CVPR 2020 / TPAMI 2021): temporal row noise,
// the shape of the read-noise distribution (Tukey-λ by a probability-plot correlation fit),
// and a Gaussian read noise from the normal probability plot.
//
// | quantity             | unit | how (L frames, N analysed photosites in H rows of n each) |
// |----------------------|------|-----------------------------------------------------------|
// | σ²_pix.total         | DN²  | v_t = mean over photosites of the temporal variance over the L frames |
// | σ_row (temporal)     | DN   | row means of the residuals y − ȳ(pixel) per frame: v_r = their variance over frames, averaged over rows; E[v_r] = σ²_row + (v_t − σ²_row)/n, so σ²_row = (v_r − v_t/n)/(1 − 1/n) |
// | σ_row.fixed          | DN   | spatial std of the stack mean's row means (less each CFA row class's mean) less the temporal part: √(s²_rows − v_r/L) (DSNU/n stays in it) |
// | residuals e          | DN   | y − (mean of that row in that frame) − (column pattern c_x from all frames): ELD's row-mean-removed bias values (the per-photosite DSNU stays in them, as in a bias frame) |
// | λ, s (Tukey-λ)       | —, DN | PPCC: the λ ∈ [−0.25, 1] maximising corr(sorted e, Q_λ(u)) (grid of 0.025, then golden section); s = the regression slope of sorted e on Q_λ(u) |
// | σ_read (Gaussian)    | DN   | slope of sorted e on Φ⁻¹(u) (normal probability plot) |
//   Q_λ(u) = (u^λ − (1−u)^λ)/λ (ln(u/(1−u)) at λ = 0), plotting positions u = (k + ½)/N_e for
//   rank k of N_e residuals; at most 20 001 order statistics are used, evenly spaced in rank.
// Uncertainties (standard errors): σ²_row from sampling theory, u(σ²_row) = v_r·√(2/(H(L−1)))
// /(1 − 1/n), u(σ_row) = u(σ²_row)/(2σ_row) (√u(σ²_row) when the estimate is 0); the fixed
// pattern likewise, u(σ²) = s²_rows·√(2/(H − 1)); λ, s, σ_read and the correlations from batch
// means: the frames split into B = min(4, L/2) groups (frame mod B), each fitted alone,
// u = std of the B fits / √B.
#pragma once

#include <cstddef>
#include <vector>

#include "sensor/model/raw_image.h"

namespace camsim {

// A measured value with its standard error (same unit).
struct Estimate {
  double value = 0.0, uncertainty = 0.0;
};

struct TukeyFit {
  double lambda = 0.0, scale = 0.0;  // shape, DN
  double correlation = 0.0;          // the maximised PPCC
};

struct DarkFrameAnalysis {
  Estimate rowTemporalDn;      // σ_row, DN per row per frame
  Estimate rowFixedDn;         // the fixed row pattern's std, DN
  Estimate tukeyLambda;        // λ
  Estimate tukeyScaleDn;       // s
  Estimate tukeyCorrelation;   // the PPCC at λ
  Estimate readGaussianDn;     // σ_read, normal-probability-plot slope
  Estimate normalCorrelation;  // the normal probability plot's correlation
  std::size_t residuals = 0;   // values in the distribution fits
};

// frames: the L ≥ 2 dark frames; pixels: the analysed photosites (indices into dn, row-major
// with the frames' width). Rows are those holding analysed photosites.
DarkFrameAnalysis analyseDarkFrames(const std::vector<RawImage>& frames,
                                    const std::vector<std::size_t>& pixels);

// The PPCC Tukey-λ fit of `values` (sorted in place).
TukeyFit fitTukeyLambda(std::vector<double>& values);
// The normal probability plot of `values` (sorted in place): slope (σ) and correlation.
TukeyFit fitNormal(std::vector<double>& values);

// Φ⁻¹(p), the standard normal quantile, for p ∈ (0, 1) (Halley's iteration on erfc).
double normalQuantile(double p);

}  // namespace camsim
