#include "sensor/measure/slanted_edge.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/measure/edge_locate.h"

namespace camsim {
namespace {

constexpr int kMinRoiSide = 8;         // px
constexpr double kMinContrast = 0.02;  // below: no edge to measure
constexpr double kWarnContrast = 0.2;  // sfrmat4 warns below 20 %
constexpr double kMinAngleDeg = 1.0;   // nearer 0°: too few phases per pixel
constexpr double kMaxAngleDeg = 40.0;  // nearer 45°: orientation ambiguous, phases repeat
constexpr double kEdgeMarginPx = 2.0;  // the edge keeps this far from the ROI's sides
constexpr double kMaxEmptyFraction = 0.1;
// A bin's samples should spread evenly over its ¼ px (RMS 0.072 px from its centre for
// one sample at a random place). Phases that repeat every few rows (a slope near p/q)
// cluster them: their mean moves off the centre, which blurs the ESF: refused above this.
constexpr double kMaxBinOffsetPx = 0.05;
// Fewer distinct phases per pixel than this (1 / the widest gap between the rows' edge
// phases) sample the ESF unevenly with a period of about a pixel, which aliases: up to
// ±0.03 at Nyquist with 11 phases (a slope near 4/11, 20°). Flagged in the warnings.
constexpr double kWarnPhasesPerPixel = 16.0;
// The MTF of an unsharpened edge stays at or below 1 (its peak is 1 at DC): above this
// somewhere up to Nyquist the ROI is sharpened or holds an outlier. Flagged in the warnings.
constexpr double kWarnMtfAboveOne = 1.1;

// 1 / the widest gap between the fractional parts of x(r + ½) over the used rows: how
// many evenly spread positions relative to the pixel grid the rows give the edge.
double phasesPerPixel(const EdgeLine& line, int firstRow, int rows) {
  std::vector<double> phase;
  for (int r = firstRow; r < firstRow + rows; ++r) {
    const double x = line.at(r + 0.5);
    phase.push_back(x - std::floor(x));
  }
  if (phase.empty()) return 0.0;
  std::sort(phase.begin(), phase.end());
  double gap = phase[0] + 1.0 - phase[phase.size() - 1];
  for (size_t i = 1; i < phase.size(); ++i) gap = std::max(gap, phase[i] - phase[i - 1]);
  return gap > 0.0 ? 1.0 / gap : 1e9;
}

[[noreturn]] void fail(const SfrOptions& o, const std::string& key, const std::string& message) {
  throw InputError({o.source, 0, 0}, key, message);
}

std::string roiText(const EdgeRoi& r) {
  return std::to_string(r.x) + "," + std::to_string(r.y) + "," + std::to_string(r.width) + "," +
         std::to_string(r.height);
}

// The ROI as a patch whose rows run along the edge: as is (vertical) or transposed.
EdgePatch patchOf(const Image& image, const EdgeRoi& roi, bool vertical) {
  EdgePatch p;
  p.rows = vertical ? roi.height : roi.width;
  p.cols = vertical ? roi.width : roi.height;
  p.values.reserve(static_cast<size_t>(p.rows) * static_cast<size_t>(p.cols));
  for (int r = 0; r < p.rows; ++r)
    for (int c = 0; c < p.cols; ++c)
      p.values.push_back(static_cast<double>(vertical ? image.at(roi.x + c, roi.y + r, 0)
                                                      : image.at(roi.x + r, roi.y + c, 0)));
  return p;
}

// Step 2: the mean of each ¼-px bin of the distance u to the edge; empty bins filled.
void projectEsf(const EdgePatch& p, const EdgeLine& line, int firstRow, int rows,
                const SfrOptions& o, SfrResult& out) {
  const int n = kSfrOversampling * p.cols;
  std::vector<double> sum(static_cast<size_t>(n), 0.0), sumU(static_cast<size_t>(n), 0.0);
  std::vector<int> count(static_cast<size_t>(n), 0);
  for (int r = firstRow; r < firstRow + rows; ++r) {
    const double y = r + 0.5;
    const double edge = line.at(y);
    const double cosA = 1.0 / std::sqrt(1.0 + line.slope(y) * line.slope(y));
    for (int c = 0; c < p.cols; ++c) {
      const double u = (c + 0.5 - edge) * cosA;
      const long b = std::lround(std::floor(u * kSfrOversampling)) + n / 2;
      if (b < 0 || b >= n) continue;
      sum[static_cast<size_t>(b)] += p.at(r, c);
      sumU[static_cast<size_t>(b)] += u;
      ++count[static_cast<size_t>(b)];
    }
  }
  int first = -1, last = -1;
  for (int b = 0; b < n; ++b)
    if (count[static_cast<size_t>(b)] > 0) {
      if (first < 0) first = b;
      last = b;
    }
  if (first < 0) fail(o, "roi", "no pixel projects onto the edge's normal");
  std::vector<double>& esf = out.esf;
  esf.assign(static_cast<size_t>(n), 0.0);
  double offset2 = 0.0;  // Σ k·d²: each bin weighted by its samples (sparse end bins count less)
  long samples = 0;
  for (int b = 0; b < n; ++b)
    if (const int k = count[static_cast<size_t>(b)]; k > 0) {
      esf[static_cast<size_t>(b)] = sum[static_cast<size_t>(b)] / k;
      const double d = sumU[static_cast<size_t>(b)] / k - (b - n / 2 + 0.5) / kSfrOversampling;
      offset2 += k * d * d;
      samples += k;
    }
  out.binOffsetRmsPx = std::sqrt(offset2 / static_cast<double>(samples));
  int& emptyBins = out.emptyBins;
  emptyBins = 0;
  for (int b = first + 1; b < last; ++b) {
    if (count[static_cast<size_t>(b)] > 0) continue;
    int next = b + 1;
    while (count[static_cast<size_t>(next)] == 0) ++next;
    const int prev = b - 1;  // filled, or filled by this loop from its own filled neighbour
    for (int e = b; e < next; ++e) {
      const double t = static_cast<double>(e - prev) / (next - prev);
      esf[static_cast<size_t>(e)] =
          (1.0 - t) * esf[static_cast<size_t>(prev)] + t * esf[static_cast<size_t>(next)];
      ++emptyBins;
    }
    b = next;
  }
  for (int b = 0; b < first; ++b) esf[static_cast<size_t>(b)] = esf[static_cast<size_t>(first)];
  for (int b = last + 1; b < n; ++b) esf[static_cast<size_t>(b)] = esf[static_cast<size_t>(last)];
  if (emptyBins > kMaxEmptyFraction * (last - first + 1))
    fail(o, "edge",
         std::to_string(emptyBins) + " of " + std::to_string(last - first + 1) +
             " quarter-pixel bins got no pixel: the edge's slope is too near a simple ratio "
             "(0°, 45°, atan ½ …) for its phases to fill them; tilt it by about 5°");
}

// Steps 3 and 4: the windowed LSF and its DFT magnitude up to 1 cycle/px, corrected.
void esfToMtf(SfrResult& out) {
  const int n = static_cast<int>(out.esf.size());
  out.lsf.assign(static_cast<size_t>(n), 0.0);
  for (int b = 1; b + 1 < n; ++b)
    out.lsf[static_cast<size_t>(b)] =
        0.5 * (out.esf[static_cast<size_t>(b + 1)] - out.esf[static_cast<size_t>(b - 1)]);
  out.lsf[0] = out.lsf[1];
  out.lsf[static_cast<size_t>(n - 1)] = out.lsf[static_cast<size_t>(n - 2)];
  const double centre = 0.5 * n - 0.5, half = 0.5 * n - 0.5;  // u = 0 between bins N/2−1, N/2
  for (int b = 0; b < n; ++b)
    out.lsf[static_cast<size_t>(b)] *=
        0.54 + 0.46 * std::cos(std::numbers::pi * (b - centre) / half);
  std::vector<double> cosT(static_cast<size_t>(n)), sinT(static_cast<size_t>(n));
  for (int j = 0; j < n; ++j) {
    const double a = 2.0 * std::numbers::pi * j / n;
    cosT[static_cast<size_t>(j)] = std::cos(a);
    sinT[static_cast<size_t>(j)] = std::sin(a);
  }
  const int kMax = n / kSfrOversampling;  // f = 1 cycle/px
  out.frequency.assign(static_cast<size_t>(kMax) + 1, 0.0);
  out.mtf.assign(static_cast<size_t>(kMax) + 1, 0.0);
  double dc = 0.0;
  for (int k = 0; k <= kMax; ++k) {
    double re = 0.0, im = 0.0;
    for (int b = 0; b < n; ++b) {
      const auto j = static_cast<size_t>((static_cast<long>(k) * b) % n);
      re += out.lsf[static_cast<size_t>(b)] * cosT[j];
      im -= out.lsf[static_cast<size_t>(b)] * sinT[j];
    }
    const double magnitude = std::hypot(re, im);
    if (k == 0) dc = magnitude;
    const double a = 2.0 * std::numbers::pi * k / n;  // central difference: sin a / a
    const double correction = k == 0 ? 1.0 : a / std::sin(a);
    out.frequency[static_cast<size_t>(k)] = static_cast<double>(kSfrOversampling) * k / n;
    out.mtf[static_cast<size_t>(k)] = dc > 0.0 ? magnitude / dc * correction : 0.0;
  }
}

}  // namespace

EdgeRoi parseEdgeRoi(const std::string& text, const std::string& source) {
  EdgeRoi roi;
  int* fields[4] = {&roi.x, &roi.y, &roi.width, &roi.height};
  size_t pos = 0;
  for (int i = 0; i < 4; ++i) {
    const size_t comma = i < 3 ? text.find(',', pos) : text.size();
    const std::string part = comma == std::string::npos ? "" : text.substr(pos, comma - pos);
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(part.c_str(), &end, 10);
    if (part.empty() || end != part.c_str() + part.size() || errno != 0 || v < 0 ||
        v > 1'000'000'000 || (i >= 2 && v < 1) || comma == std::string::npos)
      throw InputError({source, 0, 0}, "roi",
                       "expected x,y,w,h (pixels: x, y ≥ 0 the top-left corner, w, h ≥ 1), "
                       "got '" +
                           text + "'");
    *fields[i] = static_cast<int>(v);
    pos = comma + 1;
  }
  return roi;
}

std::vector<double> SfrResult::frequencyPerMm(double pixelPitchM) const {
  std::vector<double> f;
  if (!(pixelPitchM > 0.0)) return f;
  for (double v : frequency) f.push_back(v / (pixelPitchM * 1e3));
  return f;
}

std::optional<double> mtfCrossing(const std::vector<double>& frequency,
                                  const std::vector<double>& mtf, double level) {
  for (size_t k = 1; k < mtf.size() && k < frequency.size(); ++k)
    if (mtf[k - 1] >= level && mtf[k] < level) {
      const double t = (mtf[k - 1] - level) / (mtf[k - 1] - mtf[k]);
      return frequency[k - 1] + t * (frequency[k] - frequency[k - 1]);
    }
  return std::nullopt;
}

double mtfAt(const std::vector<double>& frequency, const std::vector<double>& mtf, double f) {
  if (mtf.empty()) return 0.0;
  if (f <= frequency.front()) return mtf.front();
  for (size_t k = 1; k < mtf.size(); ++k)
    if (f <= frequency[k]) {
      const double t = (f - frequency[k - 1]) / (frequency[k] - frequency[k - 1]);
      return mtf[k - 1] + t * (mtf[k] - mtf[k - 1]);
    }
  return mtf.back();
}

SfrResult measureSfr(const Image& image, const EdgeRoi& roi, const SfrOptions& o) {
  if (image.channelCount() != 1)
    fail(o, "channel",
         "the e-SFR measures one channel at a time, got " + std::to_string(image.channelCount()));
  if (o.fitOrder != 1 && o.fitOrder != 2)
    fail(o, "fit_order", "the edge fit's order is 1 or 2, got " + std::to_string(o.fitOrder));
  if (!(o.pixelPitchM == 0.0 ||
        (o.pixelPitchM >= kMinPixelPitchM && o.pixelPitchM <= kMaxPixelPitchM)))
    fail(o, "pixel_pitch",
         "the pixel pitch must be in [0.01, 1000] µm (or not given), got " +
             formatNumber(o.pixelPitchM * 1e6, 6) + " µm");
  const std::string size = std::to_string(image.width) + "×" + std::to_string(image.height);
  if (roi.x < 0 || roi.y < 0 || roi.width < 1 || roi.height < 1 ||
      roi.width > image.width - roi.x || roi.height > image.height - roi.y)
    fail(o, "roi", "the ROI " + roiText(roi) + " is not inside the " + size + " px image");
  if (roi.width < kMinRoiSide || roi.height < kMinRoiSide)
    fail(o, "roi",
         "the ROI " + roiText(roi) + " is smaller than " + std::to_string(kMinRoiSide) + " × " +
             std::to_string(kMinRoiSide) + " px");
  for (int y = roi.y; y < roi.y + roi.height; ++y)
    for (int x = roi.x; x < roi.x + roi.width; ++x)
      if (!std::isfinite(image.at(x, y, 0)))
        fail(o, "roi",
             "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                 ") in the ROI is not finite");

  // Orientation: the pair of opposite sides that differ more (sfrmat's rotatev2).
  const EdgePatch vPatch = patchOf(image, roi, true), hPatch = patchOf(image, roi, false);
  const EdgeSides vSides = edgeSides(vPatch), hSides = edgeSides(hPatch);
  const double across = std::abs(vSides.high - vSides.low);  // left vs right columns
  const double down = std::abs(hSides.high - hSides.low);    // top vs bottom rows
  const bool vertical = o.orientation == EdgeOrientation::kAuto
                            ? across >= down
                            : o.orientation == EdgeOrientation::kVertical;
  if (o.orientation != EdgeOrientation::kAuto && (vertical ? down > across : across > down))
    fail(o, "edge",
         std::string("the edge in the ROI runs ") +
             (vertical ? "left to right (horizontal)" : "top to bottom (vertical)") +
             ", not as the asked orientation '" + std::string(enumName(o.orientation)) + "'");
  const EdgePatch& patch = vertical ? vPatch : hPatch;
  const EdgeSides sides = vertical ? vSides : hSides;
  SfrResult out;
  out.vertical = vertical;
  out.contrast = std::abs(sides.contrast());
  if (!(out.contrast >= kMinContrast))
    fail(o, "roi",
         "no contrast across the edge: the two sides differ by " +
             formatFixed(100.0 * out.contrast, 2) + " % (at least " +
             formatFixed(100.0 * kMinContrast, 0) + " % needed)");
  if (out.contrast < kWarnContrast)
    out.warnings.push_back("edge contrast " + formatFixed(100.0 * out.contrast, 1) +
                           " % is below 20 %: the SFR may be in error (sfrmat4's warning)");
  if (std::min(across, down) > 0.9 * std::max(across, down) &&
      o.orientation == EdgeOrientation::kAuto)
    fail(o, "edge",
         "the ROI's sides differ as much left to right as top to bottom: the edge is "
         "near 45° or does not cross the ROI; choose an ROI the edge crosses "
         "from one side to the opposite one");

  // The edge, per row, and its fit.
  const EdgeLocation loc = locateEdge(patch, sides.high > sides.low, o.fitOrder);
  if (loc.rowsFitted < std::max(3, (patch.rows + 1) / 2))
    fail(o, "edge",
         "a rising edge was found in only " + std::to_string(loc.rowsFitted) + " of " +
             std::to_string(patch.rows) + " rows");
  for (int r = 0; r < patch.rows; ++r) {
    const double x = loc.line.at(r + 0.5);
    if (!std::isfinite(x) || x < kEdgeMarginPx || x > patch.cols - kEdgeMarginPx)
      fail(o, "edge",
           "the fitted edge leaves the ROI (or comes within " + formatFixed(kEdgeMarginPx, 0) +
               " px of its side) at ROI " + (vertical ? "row " : "column ") + std::to_string(r) +
               ": centre the ROI on the edge");
  }
  const double middle = 0.5 * patch.rows;
  out.fit = loc.line.coefficients;
  out.slope = loc.line.slope(middle);
  out.angleDeg = std::atan(std::abs(out.slope)) * 180.0 / std::numbers::pi;
  const double edgeMid = loc.line.at(middle);
  out.edgeX = vertical ? roi.x + edgeMid : roi.x + middle;
  out.edgeY = vertical ? roi.y + middle : roi.y + edgeMid;
  if (out.angleDeg < kMinAngleDeg || out.angleDeg > kMaxAngleDeg)
    fail(o, "edge",
         "the edge is " + formatFixed(out.angleDeg, 2) + "° from the " +
             (vertical ? "vertical" : "horizontal") + ", too near " +
             (out.angleDeg < kMinAngleDeg ? "0°" : "45°") + ": it must be tilted by " +
             formatFixed(kMinAngleDeg, 0) + "° to " + formatFixed(kMaxAngleDeg, 0) +
             "° (ISO 12233 suggests about 5°)");

  // Step 1: a whole number of phase cycles, centred.
  const double shift = patch.rows * std::abs(out.slope);  // px the edge moves along the ROI
  const double cycles = std::floor(shift);
  if (cycles < 1.0)
    fail(o, "roi",
         "too few rows along the edge: over the ROI's " + std::to_string(patch.rows) +
             " rows the edge moves " + formatFixed(shift, 2) +
             " px, at least one whole pixel is needed (" +
             std::to_string(static_cast<int>(std::ceil(1.0 / std::abs(out.slope)))) + " rows at " +
             formatFixed(out.angleDeg, 2) + "°)");
  out.rowsUsed =
      std::clamp(static_cast<int>(std::lround(cycles / std::abs(out.slope))), 1, patch.rows);
  const int firstRow = (patch.rows - out.rowsUsed) / 2;

  projectEsf(patch, loc.line, firstRow, out.rowsUsed, o, out);
  const std::string offset =
      "the quarter-pixel bins are filled unevenly (their samples' mean "
      "lies " +
      formatFixed(out.binOffsetRmsPx, 3) + " px RMS from the bin centres): the slope " +
      formatFixed(out.slope, 4) +
      " is near a ratio of small integers, "
      "whose phases repeat every few rows";
  if (out.binOffsetRmsPx > kMaxBinOffsetPx)
    fail(o, "edge", offset + "; tilt the edge by a degree or two");
  out.phasesPerPixel = phasesPerPixel(loc.line, firstRow, out.rowsUsed);
  if (out.phasesPerPixel < kWarnPhasesPerPixel)
    out.warnings.push_back(
        "the rows give the edge only " + formatFixed(out.phasesPerPixel, 1) +
        " distinct positions per pixel (slope " + formatFixed(out.slope, 4) +
        " near a ratio of small integers): the MTF near Nyquist may be off by a few %; tilt "
        "the edge by a degree or use more rows");
  esfToMtf(out);
  if (out.mtf[0] <= 0.0) fail(o, "roi", "no contrast across the edge: the LSF sums to zero");
  out.mtf50 = mtfCrossing(out.frequency, out.mtf, 0.5);
  out.mtfAtNyquist = mtfAt(out.frequency, out.mtf, kNyquist);
  // An MTF above 1 up to Nyquist: a sharpened image, or an outlier in the ROI (found by
  // probing: one hot pixel gave 1.7 at Nyquist, with no warning).
  std::size_t peak = 0;
  for (std::size_t i = 0; i < out.mtf.size() && out.frequency[i] <= kNyquist; ++i)
    if (out.mtf[i] > out.mtf[peak]) peak = i;
  if (out.mtf[peak] > kWarnMtfAboveOne)
    out.warnings.push_back("the MTF reaches " + formatFixed(out.mtf[peak], 3) + " at " +
                           formatFixed(out.frequency[peak], 3) +
                           " cy/px: above 1, the image is sharpened or the ROI holds an "
                           "outlier (a hot pixel, a speck); check the ROI");
  return out;
}

}  // namespace camsim
