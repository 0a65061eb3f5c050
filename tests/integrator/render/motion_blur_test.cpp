// Motion blur against closed forms.
//
// A small emitter (a sphere of uniform radiance, image radius r_e, black background,
// max_depth 0) moving at constant velocity v across the line of sight at distance Z, seen
// by a pinhole camera (focal length f, pixel pitch p), paints during the exposure a streak
// whose profile along the motion is the shutter curve s(t) mapped to the image by
// x = x₀ − f·v·t/(Z·p) (the image's x is the world's −x here), convolved with the emitter's
// own column profile (symmetric, half-width r_e) and the pixel box. So:
//  - box shutter of length T: a plateau whose FWHM is L = f·v·T/(Z·p) exactly (a symmetric
//    kernel halves the plateau at the box's ends), and whose integral is L × plateau;
//  - trapezoid shutter: linear ramps of length f·v·t_ramp/(Z·p), 10–90 % over 0.8 of that;
//  - a moving camera and a static emitter with the same relative motion: the same streak.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "tests/support/scene_text.h"

namespace camsim {
namespace {

using test::num;

constexpr double kBlurFocal = 0.050;  // m
constexpr double kBlurPitch = 20e-6;  // m
constexpr double kBlurZ = 1.0;        // m, emitter distance
constexpr double kT = 0.01;           // s, exposure (open 0 → close T)
constexpr double kBlurV = 2.4;        // m/s: v·T = 24 mm, 60 px
constexpr double kEmitterPx = 3.0;
constexpr int kBlurWidth = 80, kBlurHeight = 16;

double blurPixelsPerMetre() {
  return kBlurFocal / (kBlurZ * kBlurPitch);
}

struct Streak {
  std::vector<double> profile;  // Σ over rows of Y, per column
  ModelledDimensions modelled;
};

// shutter: the YAML shutter mapping. Either the emitter moves from world x = −vT/2 to
// +vT/2 over [0, T], or (cameraMoves) the camera moves from +vT/2 to −vT/2.
Streak renderStreak(const std::string& shutter, bool cameraMoves, int spp, std::uint64_t seed) {
  const double half = 0.5 * kBlurV * kT;
  const std::string keys = [&](double from, double to) {
    return "[{time: 0, translate: [" + num(from) + ", 0, 0]}, {time: " + num(kT) +
           ", translate: [" + num(to) + ", 0, 0]}]";
  }(cameraMoves ? half : -half, cameraMoves ? -half : half);
  const std::string yaml =
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], sensor_width_mm: " +
      num(kBlurWidth * kBlurPitch * 1e3) +
      ", sensor_height_mm: " + num(kBlurHeight * kBlurPitch * 1e3) + ",\n  resolution: [" +
      std::to_string(kBlurWidth) + ", " + std::to_string(kBlurHeight) +
      "], focal_length_mm: " + num(kBlurFocal * 1e3) + ",\n  shutter: " + shutter +
      (cameraMoves ? ",\n  motion: " + keys : std::string()) +
      "}\n"
      "render: {max_depth: 0}\n"
      "shapes:\n"
      "  - {type: sphere, centre: [0, 0, " +
      num(kBlurZ) + "], radius: " + num(kEmitterPx / blurPixelsPerMetre()) +
      ",\n     emission: {luminance: 10000, spectrum: 1, two_sided: true}" +
      (cameraMoves ? std::string() : ",\n     motion: " + keys) + "}\n";
  const Scene scene(loadSceneFromText(yaml, "motion.yaml", "."));
  RenderOptions options;
  options.spp = spp;
  options.seed = seed;
  const RenderResult result = render(scene, SpectralResponse::cieXyz(), options);
  EXPECT_EQ(result.stats.rejectedSamples, 0u);
  Streak s;
  s.modelled = result.stats.modelled;
  s.profile.assign(kBlurWidth, 0.0);
  const int c = result.image.channelIndex("Y");
  for (int y = 0; y < kBlurHeight; ++y)
    for (int x = 0; x < kBlurWidth; ++x)
      s.profile[static_cast<size_t>(x)] += static_cast<double>(result.image.at(x, y, c));
  return s;
}

struct PlateauStats {
  double mean = 0.0, cv = 0.0;
  double trend = 0.0;  // fitted relative change from one end of the range to the other
};

// Mean, coefficient of variation and linear trend of the profile over columns [a, b].
PlateauStats plateauStats(const std::vector<double>& p, int a, int b) {
  double s = 0.0, sx = 0.0, sxx = 0.0, sxy = 0.0, syy = 0.0;
  const int n = b - a + 1;
  for (int x = a; x <= b; ++x) {
    const double v = p[static_cast<size_t>(x)];
    s += v, sx += x, sxx += double(x) * x, sxy += x * v, syy += v * v;
  }
  PlateauStats st;
  st.mean = s / n;
  st.cv = std::sqrt(std::max(0.0, syy / n - st.mean * st.mean)) / st.mean;
  const double slope = (n * sxy - sx * s) / (n * sxx - sx * sx);
  st.trend = slope * (b - a) / st.mean;
  return st;
}

// Where the profile crosses `level`, searching inwards from the left or the right end
// (linear interpolation between column centres x + ½).
double crossing(const std::vector<double>& p, double level, bool fromLeft) {
  const int n = static_cast<int>(p.size());
  for (int k = 0; k + 1 < n; ++k) {
    const int i = fromLeft ? k : n - 1 - k, j = fromLeft ? i + 1 : i - 1;
    const double a = p[static_cast<size_t>(i)], b = p[static_cast<size_t>(j)];
    if (a < level && b >= level) return i + 0.5 + (j - i) * (level - a) / (b - a);
  }
  return NAN;
}

// A rising edge of the streak: the shutter ramp clamp((x − a)/len, 0, 1) convolved with
// the emitter's column profile (∝ √(r_e² − u²)) and the pixel box, by quadrature.
double edgeModel(double x, double a, double len) {
  constexpr int kBox = 8, kKernel = 16;
  double sum = 0.0, weights = 0.0;
  for (int i = 0; i < kBox; ++i)
    for (int k = 0; k < kKernel; ++k) {
      const double t = -1.0 + (2.0 * k + 1.0) / kKernel;  // in (−1, 1)
      const double w = std::sqrt(1.0 - t * t);
      const double xi = x - 0.5 + (i + 0.5) / kBox + kEmitterPx * t;
      sum += w * std::clamp((xi - a) / len, 0.0, 1.0);
      weights += w;
    }
  return sum / weights;
}

struct EdgeFit {
  double start = 0.0, length = 0.0, level = 0.0;
};

// Least-squares fit of level · edgeModel to the profile over columns [first, last] (column
// centres x + ½); the profile is mirrored (x → −x) for a falling edge. Grid search on the
// ramp's start and length (0.02 px steps near the optimum), level solved in closed form.
EdgeFit fitEdge(const std::vector<double>& p, int first, int last, bool falling, double guessStart,
                double guessLength) {
  std::vector<double> xs, vs;
  for (int x = first; x <= last; ++x) {
    xs.push_back(falling ? -(x + 0.5) : x + 0.5);
    vs.push_back(p[static_cast<size_t>(x)]);
  }
  if (falling) guessStart = -guessStart;
  EdgeFit best;
  double bestErr = INFINITY;
  auto search = [&](double a0, double a1, double l0, double l1, double step) {
    for (double a = a0; a <= a1; a += step)
      for (double len = std::max(l0, 0.5); len <= l1; len += step) {
        double se = 0.0, ee = 0.0, vv = 0.0;
        std::vector<double> e(xs.size());
        for (size_t i = 0; i < xs.size(); ++i) {
          e[i] = edgeModel(xs[i], a, len);
          se += vs[i] * e[i], ee += e[i] * e[i], vv += vs[i] * vs[i];
        }
        const double err = vv - se * se / ee;  // residual with the best level se/ee
        if (err < bestErr) bestErr = err, best = {a, len, se / ee};
      }
  };
  search(guessStart - 4.0, guessStart + 4.0, 0.5 * guessLength, 1.5 * guessLength, 0.25);
  const EdgeFit coarse = best;
  search(coarse.start - 0.3, coarse.start + 0.3, coarse.length - 0.3, coarse.length + 0.3, 0.02);
  if (falling) best.start = -best.start;
  return best;
}

// (a) + (d): box shutter, moving emitter. L = 2.4 m/s · 10 ms · 50 mm / (1 m · 20 µm) = 60 px.
// Tolerances: FWHM and equivalent width (integral / plateau) within the 1 px
// (σ ≈ 0.2 px from the per-column noise); plateau CV < 10 % (Poisson: ≈ 500 emitter
// photons per column, expected ≈ 5 %; measured 4.6 % with independent samples, 1.5 % with
// the stratified Sobol sampler) and fitted trend across the plateau < 5 % (σ ≈ 2 %).
TEST(MotionBlur, BoxShutterStreakLengthAndUniformity) {
  const Streak s = renderStreak("{open: 0, close: " + num(kT) + "}", false, 1024, 3);
  EXPECT_TRUE(s.modelled.time);
  EXPECT_EQ(s.modelled.movingObjects, 1);
  EXPECT_FALSE(s.modelled.cameraMoves);
  EXPECT_FALSE(s.modelled.rollingShutter);
  const double predicted = kBlurV * kT * blurPixelsPerMetre();
  const int centre = kBlurWidth / 2;
  const int inner = static_cast<int>(0.5 * predicted - kEmitterPx - 2.0);
  const PlateauStats st = plateauStats(s.profile, centre - inner, centre + inner - 1);
  const double fwhm =
      crossing(s.profile, 0.5 * st.mean, false) - crossing(s.profile, 0.5 * st.mean, true);
  double total = 0.0;
  for (double v : s.profile) total += v;
  std::printf(
      "box shutter: streak predicted %.2f px, FWHM %.2f px, integral/plateau %.2f px;\n"
      "  plateau CV %.3f, trend %+.3f\n",
      predicted, fwhm, total / st.mean, st.cv, st.trend);
  EXPECT_NEAR(fwhm, predicted, 1.0);
  EXPECT_NEAR(total / st.mean, predicted, 1.0);
  EXPECT_LT(st.cv, 0.10);
  EXPECT_LT(std::abs(st.trend), 0.05);
}

// (b): trapezoid shutter, ramp_open 3 ms, ramp_close 2 ms over the same 10 ms. The emitter
// moves towards image −x, so the opening ramp is on the right: 18 px long, 10–90 % over
// 14.4 px; the closing ramp on the left, 12 px, 10–90 % over 9.6 px. Each rise distance is
// 0.8 · plateau / slope of a line fitted to the columns between 30 % and 70 % (≥ 3.6 px
// from the ramp's ends, beyond the 3 px emitter blur). Tolerance: the 1 px
// (σ ≈ 0.25 px with independent samples, measured on four seeds).
TEST(MotionBlur, TrapezoidShutterRampLengths) {
  const double rampOpen = 0.3 * kT, rampClose = 0.2 * kT;
  const Streak s = renderStreak("{open: 0, close: " + num(kT) + ", ramp_open: " + num(rampOpen) +
                                    ", ramp_close: " + num(rampClose) + "}",
                                false, 2048, 4);
  const double ppm = blurPixelsPerMetre();
  const double full = kBlurV * kT * ppm;
  // Plateau (s = 1 from t = 3 ms to 8 ms): image x = centre + L/2 − v·t·ppm.
  const double xOpen =
      0.5 * kBlurWidth + 0.5 * full - kBlurV * rampOpen * ppm;  // plateau's right end
  const double xClose =
      0.5 * kBlurWidth + 0.5 * full - kBlurV * (kT - rampClose) * ppm;  // plateau's left end
  const PlateauStats st = plateauStats(s.profile, static_cast<int>(xClose + kEmitterPx + 1.0),
                                       static_cast<int>(xOpen - kEmitterPx - 1.0));
  // Fit each edge from beyond its outer end to the middle of the plateau.
  const double mid = 0.5 * (xOpen + xClose);
  const double rampOpenPx = kBlurV * rampOpen * ppm, rampClosePx = kBlurV * rampClose * ppm;
  const EdgeFit left =
      fitEdge(s.profile, 0, static_cast<int>(mid), false, xClose - rampClosePx, rampClosePx);
  const EdgeFit right = fitEdge(s.profile, static_cast<int>(mid), kBlurWidth - 1, true,
                                xOpen + rampOpenPx, rampOpenPx);
  const double riseOpen = 0.8 * right.length, riseClose = 0.8 * left.length;
  const double predictedOpen = 0.8 * rampOpenPx, predictedClose = 0.8 * rampClosePx;
  std::printf(
      "trapezoid: 10–90 %% rise predicted %.2f px (open) / %.2f px (close), fitted %.2f / %.2f px "
      "(ramps start at x = %.2f / %.2f, predicted %.2f / %.2f); plateau CV %.3f\n",
      predictedOpen, predictedClose, riseOpen, riseClose, right.start, left.start,
      xOpen + rampOpenPx, xClose - rampClosePx, st.cv);
  EXPECT_NEAR(riseOpen, predictedOpen, 1.0);
  EXPECT_NEAR(riseClose, predictedClose, 1.0);
  // The ramps are where the shutter times put them: opening on the right (the emitter
  // moves towards image −x), closing on the left.
  EXPECT_NEAR(right.start, xOpen + rampOpenPx, 1.0);
  EXPECT_NEAR(left.start, xClose - rampClosePx, 1.0);
  // FWHM of a trapezoid: the half-level points lie mid-ramp, i.e. L − (ramp_open+ramp_close)/2 of
  // motion.
  const double fwhm =
      crossing(s.profile, 0.5 * st.mean, false) - crossing(s.profile, 0.5 * st.mean, true);
  EXPECT_NEAR(fwhm, kBlurV * (kT - 0.5 * (rampOpen + rampClose)) * ppm, 1.0);
}

// (c) + (d): the camera moves instead, by the opposite displacement: the same 60 px
// streak, in the same place. Tolerances as in (a).
TEST(MotionBlur, MovingCameraGivesTheSameStreak) {
  const Streak moving = renderStreak("{open: 0, close: " + num(kT) + "}", true, 1024, 5);
  EXPECT_TRUE(moving.modelled.time);
  EXPECT_EQ(moving.modelled.movingObjects, 0);
  EXPECT_TRUE(moving.modelled.cameraMoves);
  const double predicted = kBlurV * kT * blurPixelsPerMetre();
  const int centre = kBlurWidth / 2;
  const int inner = static_cast<int>(0.5 * predicted - kEmitterPx - 2.0);
  const PlateauStats st = plateauStats(moving.profile, centre - inner, centre + inner - 1);
  const double left = crossing(moving.profile, 0.5 * st.mean, true);
  const double right = crossing(moving.profile, 0.5 * st.mean, false);
  std::printf(
      "moving camera: streak predicted %.2f px, FWHM %.2f px (from %.2f to %.2f); CV %.3f\n",
      predicted, right - left, left, right, st.cv);
  EXPECT_NEAR(right - left, predicted, 1.0);
  EXPECT_NEAR(0.5 * (left + right), 0.5 * kBlurWidth, 0.5);
  EXPECT_LT(st.cv, 0.10);
}

}  // namespace
}  // namespace camsim
