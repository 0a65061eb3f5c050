#include "integrator/render/error_estimate.h"

#include <algorithm>
#include <vector>

#include "sensor/base/check.h"

namespace camsim {

ErrorMetrics estimateFromHalves(const float* values, std::size_t stride, const float* oddMeans,
                                int width, int height, int samplesPerPixel) {
  CAMSIM_CHECK(samplesPerPixel >= 2 && width > 0 && height > 0);
  const double n = samplesPerPixel;
  const double nB = static_cast<double>(samplesPerPixel / 2), nA = n - nB;
  const double scale = 1.0 / std::sqrt(n * (1.0 / nA + 1.0 / nB));
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<double> value(count);  // I, the pixel's mean
  double total = 0.0;
  for (std::size_t i = 0; i < count; ++i)
    total += value[i] = static_cast<double>(values[i * stride]);
  // r̂: the median of the pixel's 3×3 neighbourhood (inside the image).
  std::vector<double> local(count);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double window[9];
      int k = 0;
      for (int j = std::max(y - 1, 0); j <= std::min(y + 1, height - 1); ++j)
        for (int i = std::max(x - 1, 0); i <= std::min(x + 1, width - 1); ++i)
          window[k++] = value[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) +
                              static_cast<std::size_t>(i)];
      std::nth_element(window, window + k / 2, window + k);
      local[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
            static_cast<std::size_t>(x)] = window[k / 2];
    }
  return relativeErrors(
      count,
      [&](std::size_t i) {
        // The even samples' mean a = (n I − n_B b)/n_A, so a − b = n (I − b)/n_A.
        const double b = static_cast<double>(oddMeans[i]);
        return n * (value[i] - b) / nA * scale;
      },
      [&](std::size_t i) { return local[i]; }, total / static_cast<double>(count));
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
