#include "sensor/model/spectral_response.h"

#include "sensor/base/check.h"
#include "sensor/spectra/cie.h"

namespace camsim {

SpectralResponse::SpectralResponse(std::string name, std::string unit,
                                   std::vector<ResponseChannel> channels)
    : name_(std::move(name)), unit_(std::move(unit)), channels_(std::move(channels)) {
  CAMSIM_CHECK(!channels_.empty());
}

SpectralResponse::SpectralResponse(std::string name, std::string unit,
                                   std::vector<ResponseChannel> channels, CfaLayout mosaic)
    : SpectralResponse(std::move(name), std::move(unit), std::move(channels)) {
  for (int c : mosaic.tile) CAMSIM_CHECK(c >= 0 && c < channelCount());
  mosaic_ = std::move(mosaic);
}

std::vector<std::string> SpectralResponse::storedChannelNames() const {
  if (mosaic_) return {name_};
  std::vector<std::string> names;
  for (const ResponseChannel& c : channels_) names.push_back(c.name);
  return names;
}

SpectralResponse SpectralResponse::electrons(const std::vector<std::string>& names,
                                             const std::vector<Spectrum>& qe,
                                             const CfaLayout* mosaic) {
  CAMSIM_CHECK(names.size() == qe.size() && !qe.empty());
  constexpr double h = 6.62607015e-34, c = 299792458.0;
  std::vector<ResponseChannel> channels;
  for (size_t k = 0; k < qe.size(); ++k) {
    Spectrum perJoule;  // electrons per joule at each wavelength: QE · λ / (h c)
    for (int i = 0; i < kSpectrumSamples; ++i)
      perJoule.sample(i) = static_cast<float>(static_cast<double>(qe[k].sample(i)) *
                                              (kLambdaMinNm + i) * 1e-9 / (h * c));
    channels.push_back({names[k], perJoule});
  }
  if (mosaic) return SpectralResponse("electrons", "e-", std::move(channels), *mosaic);
  return SpectralResponse("electrons", "e-", std::move(channels));
}

SpectralResponse SpectralResponse::cieXyz() {
  const Cie1931& cie = Cie1931::get();
  return SpectralResponse("cie1931_xyz", "lm*s",
                          {{"X", cie.x * kMaxLuminousEfficacy},
                           {"Y", cie.y * kMaxLuminousEfficacy},
                           {"Z", cie.z * kMaxLuminousEfficacy}});
}

}  // namespace camsim
