// The e-SFR's refusals (sensor/measure/slanted_edge.h): each bad ROI or edge ends in an
// InputError naming the image, the key and the problem; random images end in an error or
// in finite numbers, never NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "sensor/base/counter_rng.h"
#include "sensor/base/input_error.h"
#include "sensor/measure/slanted_edge.h"
#include "tests/support/slanted_edge_image.h"

namespace camsim {
namespace slanted_edge_errors_test {

using test::SyntheticEdge;

// The InputError measureSfr throws (its key and message), or a failure if none.
std::string refusal(const Image& image, const EdgeRoi& roi, const SfrOptions& o = {},
                    const std::string& key = "") {
  try {
    measureSfr(image, roi, o);
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, o.source);
    if (!key.empty()) {
      EXPECT_EQ(e.key(), key) << e.what();
    }
    return e.message();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(SlantedEdgeErrors, RoiOutsideTheImageOrTooSmall) {
  const Image img = test::syntheticEdgeImage(SyntheticEdge{});  // 64 × 128
  SfrOptions o;
  o.source = "edge.exr";
  EXPECT_TRUE(contains(refusal(img, {60, 0, 10, 128}, o, "roi"), "not inside the 64×128 px"));
  EXPECT_TRUE(contains(refusal(img, {0, 120, 64, 10}, o, "roi"), "not inside"));
  EXPECT_TRUE(contains(refusal(img, {-1, 0, 10, 10}, o, "roi"), "not inside"));
  EXPECT_TRUE(contains(refusal(img, {28, 60, 6, 6}, o, "roi"), "smaller than 8 × 8"));
}

TEST(SlantedEdgeErrors, NonFinitePixelsAndWrongChannelCountOrFitOrder) {
  Image img = test::syntheticEdgeImage(SyntheticEdge{});
  img.at(3, 4, 0) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(contains(refusal(img, {0, 0, 64, 128}, {}, "roi"), "pixel (3, 4)"));
  EXPECT_TRUE(
      contains(refusal(Image(64, 128, {"R", "G"}), {0, 0, 64, 128}, {}, "channel"), "one channel"));
  SfrOptions cubic;
  cubic.fitOrder = 3;
  refusal(test::syntheticEdgeImage(SyntheticEdge{}), {0, 0, 64, 128}, cubic, "fit_order");
}

TEST(SlantedEdgeErrors, NoContrast) {
  Image flat(64, 128, {"Y"});
  for (float& p : flat.pixels) p = 0.5f;
  EXPECT_TRUE(contains(refusal(flat, {0, 0, 64, 128}, {}, "roi"), "no contrast"));
  SyntheticEdge faint;  // 1 % contrast
  faint.dark = 0.5;
  faint.bright = 0.51;
  EXPECT_TRUE(contains(refusal(test::syntheticEdgeImage(faint), {0, 0, 64, 128}), "no contrast"));
  SyntheticEdge weak;  // 10 %: measured, with sfrmat4's warning
  weak.dark = 0.45;
  weak.bright = 0.55;
  const SfrResult r = measureSfr(test::syntheticEdgeImage(weak), {0, 0, 64, 128});
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_TRUE(contains(r.warnings[0], "below 20 %"));
}

TEST(SlantedEdgeErrors, EdgeTooNearTheAxisOr45Degrees) {
  SyntheticEdge straight;  // 0.3°: too near the axis for the phases to cover a pixel
  straight.angleDeg = 0.3;
  EXPECT_TRUE(contains(refusal(test::syntheticEdgeImage(straight), {0, 0, 64, 128}, {}, "edge"),
                       "0.30° from the vertical"));
  SyntheticEdge steep;  // 43° in a square ROI: the sides differ alike both ways
  steep.angleDeg = 43.0;
  steep.width = steep.height = 64;
  steep.centreY = 32.0;
  EXPECT_TRUE(contains(refusal(test::syntheticEdgeImage(steep), {0, 0, 64, 64}, {}, "edge"),
                       "too near 45°"));
  SyntheticEdge tall = steep;  // 42° in a tall ROI whose sides do tell: refused by its angle
  tall.width = 96;
  tall.height = 48;
  tall.centreX = 48.0;
  tall.centreY = 24.0;
  EXPECT_TRUE(
      contains(refusal(test::syntheticEdgeImage(tall), {0, 0, 96, 48}, {}, "edge"), "1° to 40°"));
}

TEST(SlantedEdgeErrors, NoEdgeCrossingTheRoi) {
  Image corner(64, 64, {"Y"});  // a bright top-right quadrant: the ROI holds a corner
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) corner.at(x, y, 0) = x >= 32 && y < 32 ? 0.9f : 0.1f;
  EXPECT_TRUE(contains(refusal(corner, {0, 0, 64, 64}, {}, "edge"), "does not cross the ROI"));
}

TEST(SlantedEdgeErrors, SlopeOfASimpleRatioLeavesBinsEmpty) {
  SyntheticEdge half;  // slope ½: two phases per pixel, half the ¼-px bins empty
  half.angleDeg = std::atan(0.5) * 180.0 / std::numbers::pi;
  half.width = 96;
  half.height = 64;
  half.centreX = 48.0;
  half.centreY = 32.0;
  EXPECT_TRUE(contains(refusal(test::syntheticEdgeImage(half), {0, 0, 96, 64}, {}, "edge"),
                       "simple ratio"));
  SyntheticEdge third;  // slope ≈ ⅓ (18.5°): three phases per pixel, bunched in the bins
  third.angleDeg = 18.5;
  third.height = 96;
  third.centreY = 48.0;
  EXPECT_TRUE(contains(refusal(test::syntheticEdgeImage(third), {0, 0, 64, 96}, {}, "edge"),
                       "ratio of small integers"));
  SyntheticEdge near411;  // slope ≈ 4/11 (20°): 15 distinct phases per pixel, measured, flagged
  near411.angleDeg = 20.0;
  near411.height = 96;
  near411.centreY = 48.0;
  const SfrResult r = measureSfr(test::syntheticEdgeImage(near411), {0, 0, 64, 96});
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_TRUE(contains(r.warnings[0], "distinct positions per pixel")) << r.warnings[0];
  EXPECT_LT(r.phasesPerPixel, 16.0);
}

TEST(SlantedEdgeErrors, OrientationOtherThanAsked) {
  SyntheticEdge horizontal;
  horizontal.vertical = false;
  horizontal.width = 128;
  horizontal.height = 64;
  horizontal.centreX = 64.0;
  horizontal.centreY = 32.0;
  SfrOptions o;
  o.orientation = EdgeOrientation::kVertical;
  EXPECT_TRUE(contains(refusal(test::syntheticEdgeImage(horizontal), {0, 0, 128, 64}, o, "edge"),
                       "left to right (horizontal)"));
  o.orientation = EdgeOrientation::kHorizontal;
  EXPECT_FALSE(measureSfr(test::syntheticEdgeImage(horizontal), {0, 0, 128, 64}, o).vertical);
}

TEST(SlantedEdgeErrors, TooFewRowsOrAnEdgeLeavingTheRoi) {
  SyntheticEdge shallow;  // 2°: 29 rows per pixel of shift; a 16-row ROI moves 0.56 px
  shallow.angleDeg = 2.0;
  EXPECT_TRUE(contains(refusal(test::syntheticEdgeImage(shallow), {16, 56, 32, 16}, {}, "roi"),
                       "too few rows"));
  // The edge (x = 32 ± 5.6 px over the rows) runs out of a ROI ending at x = 34.
  EXPECT_TRUE(
      contains(refusal(test::syntheticEdgeImage(SyntheticEdge{}), {0, 0, 34, 128}, {}, "edge"),
               "leaves the ROI"));
}

TEST(SlantedEdgeErrors, RoiText) {
  const EdgeRoi r = parseEdgeRoi("10,20,30,40");
  EXPECT_EQ(r.x, 10);
  EXPECT_EQ(r.y, 20);
  EXPECT_EQ(r.width, 30);
  EXPECT_EQ(r.height, 40);
  for (const char* bad : {"", "1,2,3", "1,2,3,4,5", "a,b,c,d", "1,2,0,4", "-1,2,3,4", "1,,3,4",
                          "1,2,3,4,", "1.5,2,3,4", "1,2,3,99999999999"}) {
    try {
      parseEdgeRoi(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "roi");
      EXPECT_EQ(e.where().file, "--roi");
    }
  }
}

TEST(SlantedEdgeErrors, RandomImagesGiveAnErrorOrFiniteNumbers) {
  int measured = 0;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    CounterRng rng(streamKey(seed, 39));
    const int w = 8 + static_cast<int>(rng.next() % 25), h = 8 + static_cast<int>(rng.next() % 25);
    Image img(w, h, {"Y"});
    // Half the images: a random step (angle, offset) plus noise; the others plain noise.
    const bool step = seed % 2 == 0;
    const double a = (rng.uniformOpen() - 0.5) * 2.0, off = rng.uniformOpen() * w;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        img.at(x, y, 0) =
            static_cast<float>((step && x - off > a * y ? 1.0 : 0.0) + 0.05 * rng.normal());
    try {
      const SfrResult r = measureSfr(img, {0, 0, w, h});
      ++measured;
      for (double m : r.mtf) ASSERT_TRUE(std::isfinite(m)) << seed;
      ASSERT_TRUE(std::isfinite(r.angleDeg) && std::isfinite(r.mtfAtNyquist)) << seed;
      if (r.mtf50) {
        ASSERT_TRUE(std::isfinite(*r.mtf50));
      }
    } catch (const InputError&) {
    }
  }
  EXPECT_GT(measured, 10);  // the steps that suit the method are measured
}

}  // namespace slanted_edge_errors_test
}  // namespace camsim
