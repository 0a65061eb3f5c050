// Rolling shutter against its closed form.
//
// A thin vertical emissive bar, taller than the field of view, moves horizontally at v
// across the line of sight at distance Z (pinhole camera, focal length f, pixel pitch p).
// With a rolling shutter row j is exposed over [j·t_row, j·t_row + T], so the bar's
// x-centroid in row j is where the bar was at j·t_row + T/2: it shifts by
//
//   Δx = f · v · t_row / (Z · p)   pixels per row
//
// (towards image −x here: the bar moves along world +x, and with look_at along +z and up
// +y image right is world −x). With a global shutter every row sees the same interval and
// the bar stays vertical.
#include <gtest/gtest.h>

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

constexpr double kRollingFocal = 0.050;  // m
constexpr double kRollingPitch = 20e-6;  // m
constexpr double kZ = 1.0;               // m
constexpr double kV = 2.0;               // m/s
constexpr double kRowTime = 1e-4;        // s per row
constexpr double kExposure = 1e-3;       // s per row (box)
constexpr int kWidth = 96, kHeight = 64;

double pixelsPerMetre() {
  return kRollingFocal / (kZ * kRollingPitch);
}

struct RowFit {
  double slope = 0.0;      // px per row, image x
  double intercept = 0.0;  // px, x-centroid of row 0 (pixel centres at i + ½)
  double rms = 0.0;        // residual, px
  ModelledDimensions modelled;
};

// Renders the bar (0.8 mm = 2 px wide, 40 mm tall, centred on the axis at mid-readout) and
// fits a line to the per-row x-centroids.
RowFit renderBar(bool rolling, int spp, std::uint64_t seed) {
  const double readoutEnd = (kHeight - 1) * kRowTime + kExposure;  // the rolling exposure's end
  const double x0 = -0.5 * kV * readoutEnd;                        // world x of the bar at t = 0
  const std::string shutter = rolling ? "{type: rolling, row_time: " + num(kRowTime) +
                                            ", open: 0, close: " + num(kExposure) + "}"
                                      : "{open: 0, close: " + num(kExposure) + "}";
  const std::string yaml =
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], sensor_width_mm: " +
      num(kWidth * kRollingPitch * 1e3) +
      ", sensor_height_mm: " + num(kHeight * kRollingPitch * 1e3) + ",\n  resolution: [" +
      std::to_string(kWidth) + ", " + std::to_string(kHeight) +
      "], focal_length_mm: " + num(kRollingFocal * 1e3) + ", shutter: " + shutter +
      "}\n"
      "render: {max_depth: 0}\n"
      "shapes:\n"
      "  - {type: rectangle, corner: [-0.0004, -0.02, " +
      num(kZ) +
      "], edge_u: [0.0008, 0, 0], edge_v: [0, 0.04, 0],\n"
      "     emission: {luminance: 10000, spectrum: 1, two_sided: true},\n"
      "     motion: [{time: 0, translate: [" +
      num(x0) + ", 0, 0]}, {time: " + num(readoutEnd) + ", translate: [" + num(-x0) +
      ", 0, 0]}]}\n";
  const Scene scene(loadSceneFromText(yaml, "rolling.yaml", "."));
  RenderOptions options;
  options.spp = spp;
  options.seed = seed;
  const RenderResult result = render(scene, SpectralResponse::cieXyz(), options);
  EXPECT_EQ(result.stats.rejectedSamples, 0u);
  RowFit fit;
  fit.modelled = result.stats.modelled;
  const int c = result.image.channelIndex("Y");
  std::vector<double> centroid(kHeight);
  for (int y = 0; y < kHeight; ++y) {
    double s = 0.0, sx = 0.0;
    for (int x = 0; x < kWidth; ++x) {
      const double v = static_cast<double>(result.image.at(x, y, c));
      s += v;
      sx += v * (x + 0.5);
    }
    EXPECT_GT(s, 0.0) << "row " << y << " is dark";
    centroid[static_cast<size_t>(y)] = sx / s;
  }
  double sy = 0.0, syy = 0.0, sc = 0.0, syc = 0.0;
  for (int y = 0; y < kHeight; ++y) {
    const double cy = centroid[static_cast<size_t>(y)];
    sy += y, syy += double(y) * y, sc += cy, syc += y * cy;
  }
  fit.slope = (kHeight * syc - sy * sc) / (kHeight * syy - sy * sy);
  fit.intercept = (sc - fit.slope * sy) / kHeight;
  double ss = 0.0;
  for (int y = 0; y < kHeight; ++y) {
    const double r = centroid[static_cast<size_t>(y)] - (fit.intercept + fit.slope * y);
    ss += r * r;
  }
  fit.rms = std::sqrt(ss / kHeight);
  return fit;
}

// Predicted: −2 m/s · 0.1 ms · 50 mm / (1 m · 20 µm) = −0.5 px per row (32 px over the
// 64 rows). Tolerances: the 5 % on the rolling slope (per-row centroid noise
// ≈ 0.09 px at 128 spp with independent samples, 0.04 px with Sobol, gives σ(slope)
// ≤ 0.001 px/row = 0.2 %) and |global slope| < 5 % of the rolling one. Row 0's centroid
// is where the bar was at T/2 (rolling) — checked to 0.5 px — and the global bar is there
// in every row.
TEST(RollingShutter, BarCentroidShiftsByVelocityTimesRowTime) {
  const double predicted = -kV * kRowTime * pixelsPerMetre();
  const double readoutEnd = (kHeight - 1) * kRowTime + kExposure;
  const double xAtHalfExposure =
      0.5 * kWidth - pixelsPerMetre() * kV * (0.5 * kExposure - 0.5 * readoutEnd);

  const RowFit rolling = renderBar(true, 128, 7);
  EXPECT_TRUE(rolling.modelled.time);
  EXPECT_TRUE(rolling.modelled.rollingShutter);
  EXPECT_EQ(rolling.modelled.movingObjects, 1);
  const RowFit global = renderBar(false, 128, 8);
  EXPECT_TRUE(global.modelled.time);
  EXPECT_FALSE(global.modelled.rollingShutter);

  std::printf(
      "rolling: slope %.4f px/row (predicted %.4f, ratio %.4f), row 0 at %.2f px (predicted %.2f), "
      "rms %.3f px\nglobal: slope %.5f px/row (%.2f %% of the rolling), at %.2f px, rms %.3f px\n",
      rolling.slope, predicted, rolling.slope / predicted, rolling.intercept, xAtHalfExposure,
      rolling.rms, global.slope, 100.0 * std::abs(global.slope / rolling.slope), global.intercept,
      global.rms);
  EXPECT_NEAR(rolling.slope / predicted, 1.0, 0.05);
  EXPECT_NEAR(rolling.intercept, xAtHalfExposure, 0.5);
  EXPECT_LT(std::abs(global.slope), 0.05 * std::abs(rolling.slope));
  EXPECT_NEAR(global.intercept, xAtHalfExposure, 0.5);
}

}  // namespace
}  // namespace camsim
