#include "integrator/render/error_estimate.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "sensor/base/check.h"

namespace camsim {
namespace {

// The windows' radii in pixels (docs in error_estimate.h).
constexpr int kReferenceRadius = 7;  // 15 × 15: the rare paths' share of r̂
constexpr int kMissedRadius = 3;     // 7 × 7: what a pixel's halves both missed
// The rare share's window: the smallest that holds this many other pixels with h > 0.
constexpr std::uint32_t kRarePixels = 4;
// A pixel is carried by its rare part h when h is more than this share of its value.
constexpr double kCarried = 0.9;
// The missed share's bound: this many times the least half-window mean.
constexpr double kSided = 3.0;

std::size_t index(int x, int y, int width) {
  return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
         static_cast<std::size_t>(x);
}

double median3(double a, double b, double c) {
  return std::max(std::min(a, b), std::min(std::max(a, b), c));
}

// Sorts three values (branch-free: min and max).
void sort3(double& a, double& b, double& c) {
  const double lo = std::min(a, b), hi = std::max(a, b);
  a = std::min(lo, c);
  b = std::max(lo, std::min(hi, c));
  c = std::max(hi, c);
}

// The median of at(i) over the pixel's 3×3 neighbourhood (the part inside the image).
// Inside, with each column of three sorted, the median of nine is the median of the
// columns' largest low, median middle and smallest high (exact and branch-free; each column
// is sorted once per row and serves three pixels); at the border, nth_element.
template <typename At>
std::vector<float> median3x3(At at, int width, int height) {
  std::vector<float> out(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  auto border = [&](int x, int y) {
    double window[9];
    int k = 0;
    for (int j = std::max(y - 1, 0); j <= std::min(y + 1, height - 1); ++j)
      for (int i = std::max(x - 1, 0); i <= std::min(x + 1, width - 1); ++i)
        window[k++] = at(index(i, j, width));
    std::nth_element(window, window + k / 2, window + k);
    out[index(x, y, width)] = static_cast<float>(window[k / 2]);
  };
  for (int y = 0; y < height; ++y) {
    if (y == 0 || y + 1 == height || width < 3) {
      for (int x = 0; x < width; ++x) border(x, y);
      continue;
    }
    border(0, y);
    border(width - 1, y);
    double lo[3], mid[3], hi[3];  // columns x − 1, x, x + 1, each sorted
    auto column = [&](int slot, int x) {
      lo[slot] = at(index(x, y - 1, width));
      mid[slot] = at(index(x, y, width));
      hi[slot] = at(index(x, y + 1, width));
      sort3(lo[slot], mid[slot], hi[slot]);
    };
    column(0, 0);
    column(1, 1);
    for (int x = 1; x + 1 < width; ++x) {
      column((x + 1) % 3, x + 1);
      out[index(x, y, width)] = static_cast<float>(median3(std::max({lo[0], lo[1], lo[2]}),
                                                           median3(mid[0], mid[1], mid[2]),
                                                           std::min({hi[0], hi[1], hi[2]})));
    }
  }
  return out;
}

// Window sums of an image from its summed-area table: O(1) per pixel and window. Sum is
// the table's type (double for values, std::uint32_t for counts: exact, half the memory);
// at(i) is pixel i's value.
template <typename Sum, typename At>
class WindowSums {
 public:
  WindowSums(At at, int width, int height)
      : at_(at),
        width_(width),
        height_(height),
        sat_((static_cast<std::size_t>(width) + 1) * (static_cast<std::size_t>(height) + 1),
             Sum(0)) {
    const std::size_t w1 = static_cast<std::size_t>(width) + 1;
    for (int y = 0; y < height; ++y) {
      Sum row(0);
      for (int x = 0; x < width; ++x) {
        row += at(index(x, y, width));
        sat_[(static_cast<std::size_t>(y) + 1) * w1 + static_cast<std::size_t>(x) + 1] =
            sat_[static_cast<std::size_t>(y) * w1 + static_cast<std::size_t>(x) + 1] + row;
      }
    }
  }
  // The sum over the pixels (x + dx, y + dy) with dx in [left, right], dy in [top, bottom]
  // (left, top ≤ 0 ≤ right, bottom: the window holds the pixel; the part inside the image)
  // without the pixel itself, and how many pixels that is.
  Sum othersSum(int x, int y, int left, int right, int top, int bottom,
                std::size_t* others = nullptr) const {
    const std::size_t w1 = static_cast<std::size_t>(width_) + 1;
    const std::size_t y0 = static_cast<std::size_t>(std::max(y + top, 0));
    const std::size_t y1 = static_cast<std::size_t>(std::min(y + bottom, height_ - 1)) + 1;
    const std::size_t x0 = static_cast<std::size_t>(std::max(x + left, 0));
    const std::size_t x1 = static_cast<std::size_t>(std::min(x + right, width_ - 1)) + 1;
    if (others) *others = (y1 - y0) * (x1 - x0) - 1;
    return sat_[y1 * w1 + x1] - sat_[y0 * w1 + x1] - sat_[y1 * w1 + x0] + sat_[y0 * w1 + x0] -
           at_(index(x, y, width_));
  }
  Sum othersSum(int x, int y, int radius, std::size_t* others = nullptr) const {
    return othersSum(x, y, -radius, radius, -radius, radius, others);
  }
  // Their mean; 0 when the window holds no other pixel.
  double othersMean(int x, int y, int left, int right, int top, int bottom) const {
    std::size_t others = 0;
    const double sum = static_cast<double>(othersSum(x, y, left, right, top, bottom, &others));
    return others > 0 ? sum / static_cast<double>(others) : 0.0;
  }
  double othersMean(int x, int y, int radius) const {
    return othersMean(x, y, -radius, radius, -radius, radius);
  }
  // The least of the means over the window's four halves (left, right, top, bottom, each
  // with the pixel's column or row): small unless the pixel has its like on every side.
  double leastHalfMean(int x, int y, int radius) const {
    return std::min({othersMean(x, y, -radius, 0, -radius, radius),
                     othersMean(x, y, 0, radius, -radius, radius),
                     othersMean(x, y, -radius, radius, -radius, 0),
                     othersMean(x, y, -radius, radius, 0, radius)});
  }

 private:
  At at_;
  int width_, height_;
  std::vector<Sum> sat_;  // (width + 1) × (height + 1), row 0 and column 0 zero
};

template <typename Sum, typename At>
WindowSums<Sum, At> windowSums(At at, int width, int height) {
  return WindowSums<Sum, At>(at, width, height);
}

// The mean of at(i) over the pixel's 8 neighbours (those inside the image).
template <typename At>
double neighbourMean(At at, int x, int y, int width, int height) {
  double sum = 0.0;
  int n = 0;
  for (int j = std::max(y - 1, 0); j <= std::min(y + 1, height - 1); ++j)
    for (int i = std::max(x - 1, 0); i <= std::min(x + 1, width - 1); ++i)
      if (i != x || j != y) {
        sum += at(index(i, j, width));
        ++n;
      }
  return n > 0 ? sum / n : 0.0;
}

}  // namespace

ErrorMetrics estimateFromHalves(const float* values, std::size_t stride, const float* oddMeans,
                                int width, int height, int samplesPerPixel) {
  CAMSIM_CHECK(samplesPerPixel >= 2 && width > 0 && height > 0);
  const double n = samplesPerPixel;
  const double nB = static_cast<double>(samplesPerPixel / 2), nA = n - nB;
  const double scale = 1.0 / std::sqrt(n * (1.0 / nA + 1.0 / nB));
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  auto value = [&](std::size_t i) { return static_cast<double>(values[i * stride]); };  // I
  // ê. The even samples' mean a = (n I − n_B b)/n_A, so a − b = n (I − b)/n_A.
  const double factor = n / nA * scale;
  auto error = [&](std::size_t i) {
    return factor * (value(i) - static_cast<double>(oddMeans[i]));
  };
  double total = 0.0;
  for (std::size_t i = 0; i < count; ++i) total += value(i);
  // Stored as float (the film's precision): with the two summed-area tables 24 bytes per
  // pixel.
  std::vector<float> typical = median3x3(value, width, height);  // m
  std::vector<float> noise =
      median3x3([&](std::size_t i) { return std::abs(error(i)); }, width, height);  // s
  // h: the pixel's departure from m, as far as its halves disagree beyond the local noise.
  std::vector<float> rare(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double d = value(i) - static_cast<double>(typical[i]);
    const double h =
        std::max(std::min(std::abs(d), std::abs(error(i))) - static_cast<double>(noise[i]), 0.0);
    rare[i] = static_cast<float>(d < 0.0 ? -h : h);
  }
  const auto rareSums = windowSums<double>(
      [&](std::size_t i) { return static_cast<double>(rare[i]); }, width, height);
  const auto rareCounts = windowSums<std::uint32_t>(
      [&](std::size_t i) { return rare[i] > 0.0f ? 1u : 0u; }, width, height);
  // The rare share: over the 15 × 15 window, or where that is more over the smallest window
  // that holds kRarePixels others with h > 0 (a cluster of rare paths: a bokeh disc).
  auto rareShare = [&](int x, int y) {
    const double wide = rareSums.othersMean(x, y, kReferenceRadius);
    for (int radius = 1; radius < kReferenceRadius; ++radius)
      if (rareCounts.othersSum(x, y, radius) >= kRarePixels)
        return std::max(rareSums.othersMean(x, y, radius), wide);
    return wide;
  };
  // r̂ and the MRAE's |e| per pixel, in place of m and s (each pixel reads only its own).
  std::vector<float>& reference = typical;
  std::vector<float>& missed = noise;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t i = index(x, y, width);
      double r = static_cast<double>(typical[i]) + rareShare(x, y);
      // A pixel carried by a rare path of its own, at the edge of their cluster: its
      // neighbours' mean, where that is more.
      if (rare[i] > 0.0f && static_cast<double>(rare[i]) > kCarried * value(i))
        r = std::max(r, neighbourMean(value, x, y, width, height));
      reference[i] = static_cast<float>(std::max(r, 0.0));
      // What both halves missed: the rare share nearby, but not beyond the edge of a
      // cluster (at most kSided × the least of the wide window's half means).
      const double share = std::min(rareSums.othersMean(x, y, kMissedRadius),
                                    kSided * rareSums.leastHalfMean(x, y, kReferenceRadius));
      missed[i] = static_cast<float>(std::max(std::abs(error(i)), share));
    }
  const double mean = total / static_cast<double>(count);
  auto at = [&](std::size_t i) { return static_cast<double>(reference[i]); };
  const ErrorMetrics squared = relativeErrors(count, error, at, mean);
  const ErrorMetrics absolute = relativeErrors(
      count, [&](std::size_t i) { return static_cast<double>(missed[i]); }, at, mean);
  return {squared.rmse, absolute.mrae};
}

ErrorMetrics estimateFromHalves(const Image& image, int channel, const Image& oddMeans,
                                int samplesPerPixel) {
  CAMSIM_CHECK(channel >= 0 && channel < image.channelCount() && oddMeans.channelCount() == 1 &&
               oddMeans.width == image.width && oddMeans.height == image.height);
  return estimateFromHalves(image.pixels.data() + channel,
                            static_cast<std::size_t>(image.channelCount()), oddMeans.pixels.data(),
                            image.width, image.height, samplesPerPixel);
}

}  // namespace camsim
