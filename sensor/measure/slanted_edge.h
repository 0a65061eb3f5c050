// The ISO 12233:2017 edge-based spatial frequency response (e-SFR) of one image channel,
// measured in a region of interest around a slanted edge, the way Burns' sfrmat4 does it
// (docs/mtf.md). It measures what the image holds: for a rendered or captured image that is
// the system MTF, lens × pixel aperture (× sensor and ISP when they ran), as ISO reports it.
//
//   parameter          unit       meaning
//   EdgeRoi x, y       px         top-left pixel of the ROI in the image (row 0 = top)
//   EdgeRoi w, h       px         its width and height
//   fitOrder           —          1: straight edge (ISO 12233:2017); 2: sfrmat4's npol = 2
//   orientation        —          auto (sfrmat's rotatev2 test), vertical or horizontal
//   pixelPitchM        m          > 0: frequencies also in cycles/mm; 0 … 1 mm
//
// Steps (the edge located per row and fitted as in edge_locate.h; a horizontal edge is
// transposed first, so "rows" run along the edge):
//   1. rows: only the rows(n) = round(⌊n·|x'|⌋/|x'|) central rows are used (a whole number
//      of phase cycles of the slope x' = dx/dy at the ROI's middle, ISO's rule)
//   2. projection: each pixel's signed distance to the edge along its normal,
//      u = (x − x(y))·cos(atan x'(y)) (px), into bins of ¼ px (4× oversampling), N = 4·cols
//      bins centred on the edge; empty bins between filled ones are interpolated
//      linearly, empty end bins copy their nearest filled neighbour
//   3. LSF(k) = (ESF(k+1) − ESF(k−1))/2 (ends copied), times a Hamming window centred on
//      the edge (u = 0) spanning the N bins
//   4. MTF(f_k) = |Σ_b LSF(b) e^{−2πikb/N}| / |Σ_b LSF(b)| · D(k) at f_k = 4k/N cycles/px
//      along the edge normal, k = 0 … N/4 (0 to 1 cycle/px, twice Nyquist); the central
//      difference's response is undone by D(k) = (2πk/N)/sin(2πk/N) (sfrmat's fir2fix,
//      in its exact form)
//   5. MTF50: the first frequency where the MTF falls through 0.5, linearly interpolated
// The ¼-px bins average the ESF over ¼ px: a factor sinc(f/4) (0.974 at Nyquist) that ISO
// and sfrmat leave in, as this does.
//
// Bad input throws InputError (file: options.source, key "roi" or "edge"): an ROI outside the
// image or smaller than 8 × 8 px, a non-finite pixel, no contrast across the edge (below
// 2 %), an orientation other than the one asked, an edge that leaves the ROI, an edge angle
// under 1° or over 40° from the axis, rows too few for one phase cycle, more than 10 % of
// the bins empty or their samples bunched 0.05 px RMS off the bin centres (a slope near a
// ratio of small integers such as ½ or ⅓: phases that repeat every few rows; warned for
// fewer than 16 distinct edge phases per pixel). Results are never NaN.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sensor/base/enum_names.h"
#include "sensor/base/image.h"

namespace camsim {

struct EdgeRoi {
  int x = 0, y = 0;           // px, top-left
  int width = 0, height = 0;  // px
};
// "x,y,w,h" (integers, w and h ≥ 1); InputError (file `source`, key "roi") otherwise.
EdgeRoi parseEdgeRoi(const std::string& text, const std::string& source = "--roi");

enum class EdgeOrientation { kAuto, kVertical, kHorizontal };
template <>
struct EnumNames<EdgeOrientation> {
  using O = EdgeOrientation;
  static constexpr EnumName<O> kTable[] = {
      {O::kAuto, "auto"}, {O::kVertical, "vertical"}, {O::kHorizontal, "horizontal"}};
};

struct SfrOptions {
  int fitOrder = 1;  // 1 or 2
  EdgeOrientation orientation = EdgeOrientation::kAuto;
  double pixelPitchM = 0.0;      // m; 0: unknown (no cycles/mm)
  std::string source = "image";  // the image's name in error messages (a file path)
};

inline constexpr int kSfrOversampling = 4;       // bins per pixel (ISO 12233)
inline constexpr double kMaxPixelPitchM = 1e-3;  // m: pitches above 1 mm are refused
// m: pitches below 0.01 µm are refused (1e-306 µm gave infinite cycles/mm, and the plot failed)
inline constexpr double kMinPixelPitchM = 1e-8;
inline constexpr double kNyquist = 0.5;  // cycles/px

struct SfrResult {
  std::vector<double> frequency;    // cycles/px along the edge normal, 0 … 1 in steps of 4/N
  std::vector<double> mtf;          // normalised at DC (mtf[0] = 1)
  std::optional<double> mtf50;      // cycles/px; none if the MTF stays above 0.5 to 1 cycle/px
  double mtfAtNyquist = 0.0;        // interpolated at 0.5 cycles/px
  bool vertical = true;             // the edge runs top to bottom (else left to right)
  double slope = 0.0;               // dx/dy (vertical) or dy/dx (horizontal) at the ROI's middle
  double angleDeg = 0.0;            // |atan slope| in degrees: the edge's angle from the axis
  double edgeX = 0.0, edgeY = 0.0;  // px, image coordinates of the edge at the ROI's middle
  std::vector<double> fit;      // the fit x(y) (ROI-local, rows along the edge), c₀, c₁[, c₂]
  int rowsUsed = 0;             // rows projected (whole phase cycles)
  int emptyBins = 0;            // interpolated bins (within the filled range)
  double binOffsetRmsPx = 0.0;  // RMS of each bin's mean u from its centre, per sample (px)
  double phasesPerPixel = 0.0;  // 1 / the widest gap between the rows' edge phases
  double contrast = 0.0;        // (bright − dark)/(bright + dark) of the two sides
  std::vector<double> esf;      // N bins of ¼ px, u = (b − N/2 + ½)/4 px
  std::vector<double> lsf;      // windowed LSF, same bins
  std::vector<std::string> warnings;  // e.g. a contrast below 20 % (sfrmat4's warning)

  // Frequencies in cycles/mm for a pitch in m (empty if pitch ≤ 0).
  std::vector<double> frequencyPerMm(double pixelPitchM) const;
};

// The e-SFR of `image` (one channel) in `roi`. InputError for bad input (see above).
SfrResult measureSfr(const Image& image, const EdgeRoi& roi, const SfrOptions& options = {});

// The MTF's first fall through `level` (linear interpolation), or none.
std::optional<double> mtfCrossing(const std::vector<double>& frequency,
                                  const std::vector<double>& mtf, double level);
// The MTF at frequency f (linear interpolation; clamped to the ends).
double mtfAt(const std::vector<double>& frequency, const std::vector<double>& mtf, double f);

}  // namespace camsim
