// SpectralResponse: what the film integrates per pixel. Each channel c has a response
// curve r_c(λ); a pixel's value for channel c is the measurement
//
//   v_c = ∫ r_c(λ) · Q(λ) dλ
//
// where Q is the spectral quantity the camera delivers (in this version spectral
// radiance, W·m⁻²·sr⁻¹·nm⁻¹). The film estimates it from the path's wavelengths as
// (1/N) Σᵢ r_c(λᵢ) Q(λᵢ) / p(λᵢ).
//
// cieXyz(): r = Km · (x̄, ȳ, z̄), Km = 683 lm/W: with Q the spectral energy on the
// photosite (J/nm), Y is luminous energy in lm·s.
// sensorElectrons(): r_c = QE_c(λ) · λ/(h c), so v_c is the expected number of
// photo-electrons (photons = energy / (h c / λ), times the quantum efficiency). A mosaic
// response (a CFA) gives each photosite only its own channel: the film stores one value
// per pixel and a Bayer sensor costs no more than a monochrome one.
// sensor/ never needs to know about the integrator.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sensor/model/cfa.h"
#include "sensor/spectra/sampled_spectrum.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

struct ResponseChannel {
  std::string name;  // EXR channel name
  Spectrum curve;    // r_c(λ)
};

class SpectralResponse {
 public:
  SpectralResponse(std::string name, std::string unit, std::vector<ResponseChannel> channels);
  // A mosaic: photosite (x, y) sees only channel mosaic.channelAt(x, y).
  SpectralResponse(std::string name, std::string unit, std::vector<ResponseChannel> channels,
                   CfaLayout mosaic);

  static SpectralResponse cieXyz();
  // Expected photo-electrons per channel from absolute QE curves (one per channel).
  static SpectralResponse electrons(const std::vector<std::string>& names,
                                    const std::vector<Spectrum>& qe, const CfaLayout* mosaic);

  bool isMosaic() const { return mosaic_.has_value(); }
  const CfaLayout& mosaic() const { return *mosaic_; }
  // Channels stored per pixel: 1 for a mosaic, else channelCount().
  int storedChannels() const { return mosaic_ ? 1 : channelCount(); }
  // Their names, as a film's image of this response is written: the response's own name
  // for a mosaic (one value per photosite), else the channels' names.
  std::vector<std::string> storedChannelNames() const;

  const std::string& name() const { return name_; }
  // Unit of the integrated value, e.g. "cd/m^2".
  const std::string& unit() const { return unit_; }
  int channelCount() const { return static_cast<int>(channels_.size()); }
  const ResponseChannel& channel(int c) const { return channels_[c]; }

  // (1/N) Σᵢ r_c(λᵢ) wᵢ: the Monte Carlo estimate of channel c for one path, given its
  // weighted quantity already divided by the wavelength pdfs, wᵢ = q(λᵢ)/p(λᵢ) (safeDiv: 0
  // where p = 0) — divided once by the caller for all channels.
  double estimate(int c, const SampledSpectrum& w, const SampledWavelengths& lambda) const {
    const SampledSpectrum rw = sampleSpectrum(channels_[c].curve, lambda) * w;
    double sum = 0.0;
    for (int i = 0; i < kWavelengthSamples; ++i) sum += static_cast<double>(rw[i]);
    return sum / kWavelengthSamples;
  }

 private:
  std::string name_;
  std::string unit_;
  std::vector<ResponseChannel> channels_;
  std::optional<CfaLayout> mosaic_;
};

}  // namespace camsim
