#include "sensor/model/exposure_control.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace camsim {

std::string meteringName(AutoExposure::Metering m) {
  return std::string(enumName(m));
}

double meterElectrons(const Image& electrons, const AutoExposure& ae) {
  const int n = electrons.channelCount();
  if (ae.metering == AutoExposure::Metering::kPercentile) {
    std::vector<float> values(electrons.pixels);
    if (values.empty()) return 0.0;
    const double rank =
        std::clamp(ae.percentile / 100.0, 0.0, 1.0) * static_cast<double>(values.size() - 1);
    const auto k = static_cast<size_t>(std::lround(rank));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return static_cast<double>(values[k]);
  }
  const double sigma = 0.25 * std::min(electrons.width, electrons.height);
  const double cx = 0.5 * electrons.width, cy = 0.5 * electrons.height;
  double sum = 0.0, weights = 0.0;
  for (int y = 0; y < electrons.height; ++y)
    for (int x = 0; x < electrons.width; ++x) {
      double w = 1.0;
      if (ae.metering == AutoExposure::Metering::kCentreWeighted) {
        const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
        w = std::exp(-(dx * dx + dy * dy) / (2.0 * sigma * sigma));
      }
      for (int c = 0; c < n; ++c) sum += w * static_cast<double>(electrons.at(x, y, c));
      weights += w * n;
    }
  return weights > 0.0 ? sum / weights : 0.0;
}

double autoExposureScale(const Image& electrons, const AutoExposure& ae,
                         double saturationElectrons) {
  const double m = meterElectrons(electrons, ae);
  if (!(m > 0.0) || !std::isfinite(m)) return 1.0;
  return ae.target * saturationElectrons / m;
}

}  // namespace camsim
