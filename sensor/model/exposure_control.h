// Exposure control on the noise-free signal (expected electrons), before noise: metering
// and auto-exposure. Electrons scale linearly with exposure time, so the exposure that
// puts the metered value at the target is t' = t · k with
//
//   k = target · μ_e.sat / m(electrons)
//
// where μ_e.sat is the sensor's saturation (full well or ADC range at the ISO) and m is:
//   mean            the mean over all photosites
//   centre_weighted the mean weighted by exp(−r²/(2σ²)), r from the image centre,
//                   σ = ¼ of the shorter image side
//   percentile      the p-th percentile of the photosites (e.g. p = 99 with target 0.9 keeps
//                   highlights just below clipping)
// Defaults: mean with target 0.18 (mid-grey at 18 % of saturation).
#pragma once

#include <string>

#include "sensor/base/enum_names.h"
#include "sensor/base/image.h"

namespace camsim {

struct AutoExposure {
  enum class Metering { kMean, kCentreWeighted, kPercentile };
  Metering metering = Metering::kMean;
  double target = 0.18;      // fraction of the saturation electrons
  double percentile = 99.0;  // for kPercentile, in (0, 100]
};

// The scene's `sensor.auto_exposure.metering` names (sensor/base/enum_names.h).
template <>
struct EnumNames<AutoExposure::Metering> {
  using M = AutoExposure::Metering;
  static constexpr EnumName<M> kTable[] = {
      {M::kMean, "mean"}, {M::kCentreWeighted, "centre_weighted"}, {M::kPercentile, "percentile"}};
};
std::string meteringName(AutoExposure::Metering m);  // enumName, as a std::string

// The metered value of an image (all channels pooled).
double meterElectrons(const Image& electrons, const AutoExposure& ae);
// k such that metering k·electrons gives target·saturationElectrons; 1 if the image is dark.
double autoExposureScale(const Image& electrons, const AutoExposure& ae,
                         double saturationElectrons);

}  // namespace camsim
