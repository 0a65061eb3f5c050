#include "sensor/spectral_response.h"

#include "sensor/check.h"
#include "sensor/cie.h"

namespace camsim {

SpectralResponse::SpectralResponse(std::string name, std::string unit,
                                   std::vector<ResponseChannel> channels)
    : name_(std::move(name)), unit_(std::move(unit)), channels_(std::move(channels)) {
  CAMSIM_CHECK(!channels_.empty());
}

SpectralResponse SpectralResponse::cieXyz() {
  const Cie1931& cie = Cie1931::get();
  return SpectralResponse("cie1931_xyz", "cd/m^2",
                          {{"X", cie.x * kMaxLuminousEfficacy},
                           {"Y", cie.y * kMaxLuminousEfficacy},
                           {"Z", cie.z * kMaxLuminousEfficacy}});
}

}  // namespace camsim
