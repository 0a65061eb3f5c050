#include "integrator/measure/peer_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "integrator/measure/bench_metrics.h"
#include "sensor/base/check.h"
#include "sensor/spectra/color_space.h"

namespace camsim {
namespace {

const std::vector<std::string>& rgbyNames() {
  static const std::vector<std::string> names = {"R", "G", "B", "Y"};
  return names;
}

int channelIndex(const Image& image, const std::string& name) {
  for (int c = 0; c < image.channelCount(); ++c)
    if (image.channels[static_cast<std::size_t>(c)] == name) return c;
  throw std::invalid_argument("image has no channel " + name);
}

PeerErrors combine(const ErrorMetrics (&m)[4]) {
  PeerErrors e;
  e.rgb.rmse = (m[0].rmse + m[1].rmse + m[2].rmse) / 3.0;
  e.rgb.mrae = (m[0].mrae + m[1].mrae + m[2].mrae) / 3.0;
  e.y = m[3];
  return e;
}

std::string sci(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3e", v);
  return buf;
}

}  // namespace

Image peerRgbyFromXyz(const Image& xyz) {
  if (xyz.channelCount() != 3) throw std::invalid_argument("expected an X, Y, Z image");
  const RgbColorSpace& space = RgbColorSpace::linearRec709();
  Image out(xyz.width, xyz.height, rgbyNames());
  for (int y = 0; y < xyz.height; ++y)
    for (int x = 0; x < xyz.width; ++x) {
      const glm::dvec3 v(xyz.at(x, y, 0), xyz.at(x, y, 1), xyz.at(x, y, 2));
      const glm::dvec3 rgb = space.fromXyz(v);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(rgb[c]);
      out.at(x, y, 3) = static_cast<float>(v.y);
    }
  return out;
}

Image peerRgbyFromRgb(const Image& rgb) {
  const int r = channelIndex(rgb, "R"), g = channelIndex(rgb, "G"), b = channelIndex(rgb, "B");
  const glm::dmat3& m = RgbColorSpace::linearRec709().xyzFromRgb();  // row 1: Y
  Image out(rgb.width, rgb.height, rgbyNames());
  for (int y = 0; y < rgb.height; ++y)
    for (int x = 0; x < rgb.width; ++x) {
      const glm::dvec3 v(rgb.at(x, y, r), rgb.at(x, y, g), rgb.at(x, y, b));
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(v[c]);
      out.at(x, y, 3) = static_cast<float>(m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z);
    }
  return out;
}

PeerErrors peerCompare(const Image& image, const Image& reference) {
  ErrorMetrics m[4];
  for (int c = 0; c < 4; ++c) m[c] = compareImages(image, reference, c);
  return combine(m);
}

PeerErrors peerNoise(const Image& halfA, const Image& halfB) {
  ErrorMetrics m[4];
  for (int c = 0; c < 4; ++c) m[c] = referenceNoise(halfA, halfB, c);
  return combine(m);
}

double beyondFloor(double rmse, double floorRmse) {
  return std::max(rmse - floorRmse, 1e-12 * rmse);
}

double timeToReach(const std::vector<double>& seconds, const std::vector<double>& error,
                   double target, bool& extrapolated) {
  extrapolated = false;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = std::min(seconds.size(), error.size());
  if (n < 2 || !(target > 0.0)) return nan;
  // Interpolation between the first pair that brackets the target.
  for (std::size_t i = 1; i < n; ++i)
    if (error[i - 1] >= target && error[i] <= target) {
      const double x0 = std::log(seconds[i - 1]), x1 = std::log(seconds[i]);
      const double y0 = std::log(error[i - 1]), y1 = std::log(error[i]);
      if (!(y1 != y0)) return seconds[i];
      return std::exp(x0 + (std::log(target) - y0) * (x1 - x0) / (y1 - y0));
    }
  // Outside the ladder: the least-squares line through all of it, if it falls.
  extrapolated = true;
  const SlopeFit fit = fitLogLogSlope(seconds, error);
  if (fit.points < 2 || !(fit.slope < 0.0)) return nan;
  return std::pow(10.0, (std::log10(target) - fit.intercept) / fit.slope);
}

EqualError equalError(const PeerRun& camsim, const PeerRun& cycles, bool luminance) {
  EqualError e;
  const auto errorOf = [&](const PeerRun& run, const PeerLadderPoint& p) {
    return luminance ? beyondFloor(p.error.y.rmse, run.floor.y.rmse)
                     : beyondFloor(p.error.rgb.rmse, run.floor.rgb.rmse);
  };
  if (cycles.ladder.empty()) return e;
  e.target = errorOf(cycles, cycles.ladder.back());
  e.cyclesSeconds = cycles.ladder.back().seconds;
  std::vector<double> t, err;
  for (const PeerLadderPoint& p : camsim.ladder) {
    t.push_back(p.seconds);
    err.push_back(errorOf(camsim, p));
  }
  e.camsimSeconds = timeToReach(t, err, e.target, e.extrapolated);
  return e;
}

void keepFastest(std::vector<PeerLadderPoint>& kept, const std::vector<PeerLadderPoint>& round) {
  CAMSIM_CHECK(kept.size() == round.size());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    CAMSIM_CHECK(kept[i].spp == round[i].spp);
    kept[i].seconds = std::min(kept[i].seconds, round[i].seconds);
    kept[i].slowest = std::max(kept[i].slowest, round[i].seconds);
  }
}

std::string formatPeerReport(const std::vector<PeerSceneResult>& results, int threads,
                             int referenceSpp) {
  std::ostringstream out;
  out << "peer: Cycles (Debian's blender, CPU, " << threads
      << " threads, no denoiser, no adaptive sampling, no clamping) against camsim (Sobol', seed "
         "1), each against its own reference of "
      << referenceSpp
      << " spp (two halves, seeds 1001/1002); error* = rMSE − the reference's floor, on linear "
         "Rec.709 RGB (mean of R, G, B) and on luminance Y; Cycles' time is its render alone "
         "(around bpy.ops.render.render: its scene sync and BVH build included, Blender's "
         "start-up excluded)\n";
  char line[256];
  std::snprintf(line, sizeof line, "%-13s %-7s %6s %9s %10s %10s %10s %10s\n", "scene", "renderer",
                "spp", "seconds", "rMSE RGB", "error*RGB", "rMSE Y", "error* Y");
  for (const PeerSceneResult& r : results) {
    out << "\n"
        << r.scene << " " << r.width << "x" << r.height << ", camsim max_depth " << r.maxDepth
        << " / Cycles max_bounces " << r.maxDepth - 1 << "\n";
    for (const PeerRun* run : {&r.cycles, &r.camsim})
      out << "  " << run->renderer << " reference floor: rMSE RGB " << sci(run->floor.rgb.rmse)
          << ", Y " << sci(run->floor.y.rmse)
          << (run->referenceCached
                  ? " (cached)"
                  : " (rendered in " + formatFixed(run->referenceSeconds, 1) + " s)")
          << "\n";
    out << line;
    for (const PeerRun* run : {&r.cycles, &r.camsim})
      for (const PeerLadderPoint& p : run->ladder) {
        char row[256];
        std::snprintf(row, sizeof row, "%-13s %-7s %6d %9.3f %10.3e %10.3e %10.3e %10.3e\n",
                      r.scene.c_str(), run->renderer.c_str(), p.spp, p.seconds, p.error.rgb.rmse,
                      beyondFloor(p.error.rgb.rmse, run->floor.rgb.rmse), p.error.y.rmse,
                      beyondFloor(p.error.y.rmse, run->floor.y.rmse));
        out << row;
      }
    for (const auto& [name, e] : {std::pair<const char*, const EqualError&>{"RGB", r.rgb},
                                  std::pair<const char*, const EqualError&>{"Y", r.y}})
      out << "  equal error on " << name << ": Cycles "
          << (r.cycles.ladder.empty() ? 0 : r.cycles.ladder.back().spp) << " spp error* "
          << sci(e.target) << " in " << formatFixed(e.cyclesSeconds, 3)
          << " s; camsim reaches it in " << formatFixed(e.camsimSeconds, 3) << " s"
          << (e.extrapolated ? " (extrapolated beyond its ladder)" : "")
          << ": time ratio camsim/Cycles " << formatFixed(e.ratio(), 3) << "\n";
    if (r.rounds > 1 && !r.cycles.ladder.empty() && !r.camsim.ladder.empty()) {
      // Over the rounds that reached the target (a ratio is NaN where camsim's ladder did not).
      const auto range = [](const std::vector<double>& v) {
        std::vector<double> reached;
        for (const double x : v)
          if (std::isfinite(x)) reached.push_back(x);
        if (reached.empty()) return std::string("not reached");
        const auto [lo, hi] = std::minmax_element(reached.begin(), reached.end());
        std::string text = formatFixed(*lo, 3) + "–" + formatFixed(*hi, 3);
        if (reached.size() < v.size())
          text += " (" + std::to_string(v.size() - reached.size()) + " not reached)";
        return text;
      };
      out << "  rounds: " << r.rounds << " (each rung's time the fastest of its " << r.rounds
          << " renders; slowest: Cycles " << r.cycles.ladder.back().spp << " spp "
          << formatFixed(r.cycles.ladder.back().slowest, 3) << " s, camsim "
          << r.camsim.ladder.back().spp << " spp " << formatFixed(r.camsim.ladder.back().slowest, 3)
          << " s); each round's own ratio: RGB " << range(r.rgbRoundRatios) << ", Y "
          << range(r.yRoundRatios) << "\n";
    }
    out << "  approximated:";
    for (const std::string& a : r.approximations) out << "\n    - " << a;
    out << "\n";
  }
  if (!results.empty()) {
    out << "\nsummary (time ratio camsim/Cycles at Cycles' top-spp error):\n";
    for (const PeerSceneResult& r : results)
      out << "  " << r.scene << ": RGB " << formatFixed(r.rgb.ratio(), 3)
          << (r.rgb.extrapolated ? "*" : "") << ", Y " << formatFixed(r.y.ratio(), 3)
          << (r.y.extrapolated ? "*" : "") << "\n";
    for (const PeerSceneResult& r : results)
      if (r.rgb.extrapolated || r.y.extrapolated) {
        out << "  (* extrapolated beyond camsim's ladder)\n";
        break;
      }
  }
  return out.str();
}

std::string formatPeerCsv(const std::vector<PeerSceneResult>& results) {
  std::ostringstream out;
  out << "scene,renderer,width,height,max_depth,spp,seconds,rmse_rgb,floor_rmse_rgb,mrae_rgb,"
         "rmse_y,floor_rmse_y,mrae_y\n";
  for (const PeerSceneResult& r : results)
    for (const PeerRun* run : {&r.cycles, &r.camsim})
      for (const PeerLadderPoint& p : run->ladder)
        out << csvField(r.scene) << "," << run->renderer << "," << r.width << "," << r.height << ","
            << r.maxDepth << "," << p.spp << "," << formatShortest(p.seconds) << ","
            << formatShortest(p.error.rgb.rmse) << "," << formatShortest(run->floor.rgb.rmse) << ","
            << formatShortest(p.error.rgb.mrae) << "," << formatShortest(p.error.y.rmse) << ","
            << formatShortest(run->floor.y.rmse) << "," << formatShortest(p.error.y.mrae) << "\n";
  return out.str();
}

std::string formatPeerEqualCsv(const std::vector<PeerSceneResult>& results) {
  std::ostringstream out;
  out << "scene,channel,target,cycles_spp,cycles_seconds,camsim_seconds,extrapolated,ratio\n";
  for (const PeerSceneResult& r : results)
    for (const auto& [name, e] : {std::pair<const char*, const EqualError&>{"rgb", r.rgb},
                                  std::pair<const char*, const EqualError&>{"y", r.y}}) {
      // Not reached: NaN (outside camsim's ladder), or no Cycles ladder at all (defaults).
      const bool reached = !r.cycles.ladder.empty() && std::isfinite(e.camsimSeconds);
      out << csvField(r.scene) << "," << name << "," << formatShortest(e.target) << ","
          << (r.cycles.ladder.empty() ? 0 : r.cycles.ladder.back().spp) << ","
          << formatShortest(e.cyclesSeconds) << ","
          << (reached ? formatShortest(e.camsimSeconds) : "") << "," << (e.extrapolated ? 1 : 0)
          << "," << (reached ? formatShortest(e.ratio()) : "") << "\n";
    }
  return out.str();
}

}  // namespace camsim
