// `camsim bench --peer cycles`: each renderer's errors against its own reference, the
// equal-error time, and the report.
//
// Images are linear Rec.709 R, G, B plus luminance Y (camsim: its XYZ film through
// RgbColorSpace::linearRec709(), Y its own; Cycles: its EXR's R, G, B, Y = the Rec.709
// luminance row). Errors are bench_metrics.h's rMSE and MRAE (eps = 1% of the channel's
// mean): "RGB" is the mean of the three channels' values, "Y" the luminance's. Each
// renderer's reference is two independent half renders; the noise floor of their mean
// (referenceNoise) is subtracted from every measured rMSE (error* = rMSE − floor rMSE: the
// reference's noise adds to the error it measures).
//
// Equal-error time: Cycles' error* at the top of its ladder (256 spp by default) is the
// target; the time camsim needs for it is interpolated linearly in (log seconds, log error*)
// between the two ladder renders around it (extrapolated on the log-log least-squares line
// of the whole ladder when it does not reach it, and marked so). Ratio = camsim's time ÷ Cycles' time at the top.
// Rounds: the renders' times vary from run to run (Cycles' 256-spp Cornell box took 56.9 to
// 65.2 s in five runs on one idle machine, its images the same): with K rounds each renderer renders its
// ladder K times, taking turns, each rung keeps its fastest time, and the report also gives
// the range of the K rounds' own ratios.
#pragma once

#include <string>
#include <vector>

#include "integrator/render/error_estimate.h"
#include "sensor/base/image.h"

namespace camsim {

// R, G, B, Y (4 channels) from a CIE XYZ film image (3 channels X, Y, Z).
Image peerRgbyFromXyz(const Image& xyz);
// R, G, B, Y from a linear Rec.709 image with channels named R, G and B (others ignored);
// std::invalid_argument if one is missing.
Image peerRgbyFromRgb(const Image& rgb);

struct PeerErrors {
  ErrorMetrics rgb, y;  // rgb: the mean over R, G, B
};
// image and reference: R, G, B, Y images of the same size.
PeerErrors peerCompare(const Image& image, const Image& reference);
// The floor of (a + b)/2 (referenceNoise per channel).
PeerErrors peerNoise(const Image& halfA, const Image& halfB);

struct PeerLadderPoint {
  int spp = 0;
  double seconds = 0.0;  // wall time of the render (Cycles: around bpy.ops.render.render);
                         // with several rounds the fastest round's
  PeerErrors error;      // against the renderer's own reference, floor included
  double slowest = 0.0;  // the slowest round's time (seconds' with one round)
};

struct PeerRun {
  std::string renderer;  // "camsim" or "cycles"
  PeerErrors floor;
  double referenceSeconds = 0.0;  // 0 when read from the cache
  bool referenceCached = false;
  std::vector<PeerLadderPoint> ladder;  // by increasing spp
};

// Folds a later round's ladder into the kept one, rung by rung (the same spp, checked):
// seconds the fastest, slowest the slowest (the renders, and so the errors, are the same
// every round).
void keepFastest(std::vector<PeerLadderPoint>& kept, const std::vector<PeerLadderPoint>& round);

// rMSE − the floor's rMSE, not below 1e-12 of the rMSE (log-log needs it positive).
double beyondFloor(double rmse, double floorRmse);

struct EqualError {
  double target = 0.0;         // Cycles' error* at its top spp
  double cyclesSeconds = 0.0;  // Cycles' time at its top spp
  double camsimSeconds = 0.0;  // camsim's time to reach target
  bool extrapolated = false;
  double ratio() const { return cyclesSeconds > 0.0 ? camsimSeconds / cyclesSeconds : 0.0; }
};

// The time at which (seconds[i], error[i]), by increasing seconds, reaches `target`:
// log-log interpolated between the first two neighbours around it; when none are, extrapolated
// (flag set) on the least-squares log-log line through all points (NaN unless it falls).
// Fewer than two points: NaN.
double timeToReach(const std::vector<double>& seconds, const std::vector<double>& error,
                   double target, bool& extrapolated);

// On RGB (luminance = false) or on Y.
EqualError equalError(const PeerRun& camsim, const PeerRun& cycles, bool luminance);

struct PeerSceneResult {
  std::string scene;
  int width = 0, height = 0;
  int maxDepth = 0;  // camsim's; Cycles max_bounces = maxDepth − 1
  PeerRun camsim, cycles;
  EqualError rgb, y;
  std::vector<std::string> approximations;
  // Rounds (PeerPlan::rounds): each ladder's times are every rung's fastest; each round's own
  // ratios (its camsim ladder against its Cycles ladder), in round order.
  int rounds = 1;
  std::vector<double> rgbRoundRatios, yRoundRatios;
};

std::string formatPeerReport(const std::vector<PeerSceneResult>& results, int threads,
                             int referenceSpp);
std::string formatPeerCsv(const std::vector<PeerSceneResult>& results);
// bench_peer_equal.csv: per scene, RGB and Y, the equal-error line of the report (what
// scripts/peer_plot.py draws; camsim_seconds and ratio empty when not reached).
std::string formatPeerEqualCsv(const std::vector<PeerSceneResult>& results);

}  // namespace camsim
