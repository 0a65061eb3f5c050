// SpectralResponse: what the film integrates per pixel. Each channel c has a response
// curve r_c(λ); a pixel's value for channel c is the measurement
//
//   v_c = ∫ r_c(λ) · Q(λ) dλ
//
// where Q is the spectral quantity the camera delivers (in this version spectral
// radiance, W·m⁻²·sr⁻¹·nm⁻¹). The film estimates it from the path's wavelengths as
// (1/N) Σᵢ r_c(λᵢ) Q(λᵢ) / p(λᵢ).
//
// cieXyz(): r = Km · (x̄, ȳ, z̄), Km = 683 lm/W, so Y is luminance in cd/m² and X, Z are
// on the same absolute scale. A sensor (later) supplies QE(λ)·λ/(hc) curves per CFA
// channel through the same interface; sensor/ never needs to know about the integrator.
#pragma once

#include <string>
#include <vector>

#include "sensor/sampled_spectrum.h"
#include "sensor/spectrum.h"

namespace camsim {

struct ResponseChannel {
  std::string name;  // EXR channel name
  Spectrum curve;    // r_c(λ)
};

class SpectralResponse {
 public:
  SpectralResponse(std::string name, std::string unit, std::vector<ResponseChannel> channels);

  static SpectralResponse cieXyz();

  const std::string& name() const { return name_; }
  // Unit of the integrated value, e.g. "cd/m^2".
  const std::string& unit() const { return unit_; }
  int channelCount() const { return static_cast<int>(channels_.size()); }
  const ResponseChannel& channel(int c) const { return channels_[c]; }

  // (1/N) Σᵢ r_c(λᵢ) · q[i] / p(λᵢ): the Monte Carlo estimate of channel c for one path.
  double estimate(int c, const SampledSpectrum& q, const SampledWavelengths& lambda) const {
    const Spectrum& r = channels_[c].curve;
    double sum = 0.0;
    for (int i = 0; i < kWavelengthSamples; ++i)
      if (lambda.pdf(i) > 0.0f) sum += static_cast<double>(r(lambda[i]) * q[i] / lambda.pdf(i));
    return sum / kWavelengthSamples;
  }

 private:
  std::string name_;
  std::string unit_;
  std::vector<ResponseChannel> channels_;
};

}  // namespace camsim
