// Film: per-pixel accumulators of what the spectral response asks for.
//
//   pixel value v_c = (1/n) Σ_samples (1/N) Σᵢ r_c(λᵢ) W(λᵢ) L(λᵢ) / p(λᵢ)
//
// with n the samples per pixel, W the camera's measurement weight (radiance → energy on
// the photosite, see PhysicalCamera) and r_c the response curve of channel c
// (sensor::SpectralResponse). With W in m²·s·sr the value is the response-weighted energy
// on the photosite. Each pixel is written by one tile only,
// so no locking is needed. Samples with NaN/Inf radiance are rejected and counted.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "sensor/image.h"
#include "sensor/sampled_spectrum.h"
#include "sensor/spectral_response.h"

namespace camsim {

class Film {
 public:
  Film(glm::ivec2 resolution, const SpectralResponse& response);

  // q: the sample's weighted spectral quantity (radiance × camera weight). Returns false
  // (and adds nothing) if it is not finite.
  bool addSample(glm::ivec2 pixel, const SampledSpectrum& q, const SampledWavelengths& lambda) {
    if (!q.isFinite()) return false;
    double* sums = &sums_[(static_cast<size_t>(pixel.y) * static_cast<size_t>(resolution_.x) +
                           static_cast<size_t>(pixel.x)) * channels_];
    for (size_t c = 0; c < channels_; ++c) sums[c] += response_.estimate(static_cast<int>(c), q, lambda);
    return true;
  }

  glm::ivec2 resolution() const { return resolution_; }
  const SpectralResponse& response() const { return response_; }
  // The pixel means, one channel per response channel, named after them.
  Image toImage(int samplesPerPixel) const;

 private:
  glm::ivec2 resolution_;
  const SpectralResponse& response_;
  size_t channels_;
  std::vector<double> sums_;
};

}  // namespace camsim
