#include "integrator/render/error_estimate.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "sensor/base/check.h"

namespace camsim {
namespace {

// The windows' radii in pixels (docs in error_estimate.h).
constexpr int kReferenceRadius = 7;  // 15 × 15: the rare paths' share of r̂
constexpr int kMissedRadius = 3;     // 7 × 7: what a pixel's halves both missed

std::size_t index(int x, int y, int width) {
  return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
         static_cast<std::size_t>(x);
}

double median3(double a, double b, double c) {
  return std::max(std::min(a, b), std::min(std::max(a, b), c));
}

// Sorts a row of three in place.
void sort3(double& a, double& b, double& c) {
  if (b < a) std::swap(a, b);
  if (c < b) std::swap(b, c);
  if (b < a) std::swap(a, b);
}

// The median of each pixel's 3×3 neighbourhood (the part inside the image). Inside, with
// each row of three sorted, the median of nine is the median of the rows' largest low,
// median middle and smallest high (exact, branch-free; nth_element at the border).
std::vector<double> median3x3(const std::vector<double>& v, int width, int height) {
  std::vector<double> out(v.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (x > 0 && y > 0 && x + 1 < width && y + 1 < height) {
        double lo[3], mid[3], hi[3];
        for (int j = 0; j < 3; ++j) {
          const std::size_t row = index(x - 1, y - 1 + j, width);
          lo[j] = v[row];
          mid[j] = v[row + 1];
          hi[j] = v[row + 2];
          sort3(lo[j], mid[j], hi[j]);
        }
        out[index(x, y, width)] =
            median3(std::max({lo[0], lo[1], lo[2]}), median3(mid[0], mid[1], mid[2]),
                    std::min({hi[0], hi[1], hi[2]}));
        continue;
      }
      double window[9];
      int k = 0;
      for (int j = std::max(y - 1, 0); j <= std::min(y + 1, height - 1); ++j)
        for (int i = std::max(x - 1, 0); i <= std::min(x + 1, width - 1); ++i)
          window[k++] = v[index(i, j, width)];
      std::nth_element(window, window + k / 2, window + k);
      out[index(x, y, width)] = window[k / 2];
    }
  return out;
}

// Each pixel's mean of v over the (2 radius + 1)² window around it (the part inside the
// image) without the pixel itself, from a summed-area table: O(1) per pixel.
std::vector<double> othersMean(const std::vector<double>& v, int width, int height, int radius) {
  const std::size_t w1 = static_cast<std::size_t>(width) + 1;
  std::vector<double> sat(w1 * (static_cast<std::size_t>(height) + 1), 0.0);
  for (int y = 0; y < height; ++y) {
    double row = 0.0;
    for (int x = 0; x < width; ++x) {
      row += v[index(x, y, width)];
      sat[(static_cast<std::size_t>(y) + 1) * w1 + static_cast<std::size_t>(x) + 1] =
          sat[static_cast<std::size_t>(y) * w1 + static_cast<std::size_t>(x) + 1] + row;
    }
  }
  std::vector<double> out(v.size());
  for (int y = 0; y < height; ++y) {
    const std::size_t y0 = static_cast<std::size_t>(std::max(y - radius, 0));
    const std::size_t y1 = static_cast<std::size_t>(std::min(y + radius, height - 1)) + 1;
    for (int x = 0; x < width; ++x) {
      const std::size_t x0 = static_cast<std::size_t>(std::max(x - radius, 0));
      const std::size_t x1 = static_cast<std::size_t>(std::min(x + radius, width - 1)) + 1;
      const double sum = sat[y1 * w1 + x1] - sat[y0 * w1 + x1] - sat[y1 * w1 + x0] +
                         sat[y0 * w1 + x0] - v[index(x, y, width)];
      const std::size_t others = (y1 - y0) * (x1 - x0) - 1;
      out[index(x, y, width)] = others > 0 ? sum / static_cast<double>(others) : 0.0;
    }
  }
  return out;
}

}  // namespace

ErrorMetrics estimateFromHalves(const float* values, std::size_t stride, const float* oddMeans,
                                int width, int height, int samplesPerPixel) {
  CAMSIM_CHECK(samplesPerPixel >= 2 && width > 0 && height > 0);
  const double n = samplesPerPixel;
  const double nB = static_cast<double>(samplesPerPixel / 2), nA = n - nB;
  const double scale = 1.0 / std::sqrt(n * (1.0 / nA + 1.0 / nB));
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<double> value(count), error(count), spread(count);
  double total = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    total += value[i] = static_cast<double>(values[i * stride]);
    // The even samples' mean a = (n I − n_B b)/n_A, so a − b = n (I − b)/n_A.
    error[i] = n * (value[i] - static_cast<double>(oddMeans[i])) / nA * scale;
    spread[i] = std::abs(error[i]);
  }
  const std::vector<double> typical = median3x3(value, width, height);  // m
  const std::vector<double> noise = median3x3(spread, width, height);   // s
  // h: the pixel's departure from m, as far as its halves disagree beyond the local noise.
  std::vector<double> rare(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double d = value[i] - typical[i];
    const double h = std::max(std::min(std::abs(d), spread[i]) - noise[i], 0.0);
    rare[i] = d < 0.0 ? -h : h;
  }
  const std::vector<double> rareWide = othersMean(rare, width, height, kReferenceRadius);
  const std::vector<double> rareNear = othersMean(rare, width, height, kMissedRadius);
  const double mean = total / static_cast<double>(count);
  auto reference = [&](std::size_t i) { return std::max(typical[i] + rareWide[i], 0.0); };
  const ErrorMetrics squared = relativeErrors(
      count, [&](std::size_t i) { return error[i]; }, reference, mean);
  const ErrorMetrics absolute = relativeErrors(
      count, [&](std::size_t i) { return std::max(spread[i], rareNear[i]); }, reference, mean);
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
