// Film: per-pixel accumulators of what one or more spectral responses ask for.
//
//   pixel value v_c = (1/n) Σ_samples (1/N) Σᵢ r_c(λᵢ) W(λᵢ) L(λᵢ) / p(λᵢ)
//
// with n the samples per pixel, W the camera's measurement weight (radiance → energy on
// the photosite, see PhysicalCamera) and r_c the response curve of channel c
// (sensor::SpectralResponse): the response-weighted energy on the photosite. A mosaic
// response (a CFA) stores only the photosite's own channel. Several responses (e.g. CIE
// XYZ and a sensor's QE) are filled by the same samples in one pass. Each pixel is written
// by one tile only, so no locking is needed. Non-finite samples are rejected and counted.
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
  Film(glm::ivec2 resolution, std::vector<const SpectralResponse*> responses);

  // q: the sample's weighted spectral quantity (radiance × camera weight). Returns false
  // (and adds nothing) if it is not finite.
  bool addSample(glm::ivec2 pixel, const SampledSpectrum& q, const SampledWavelengths& lambda) {
    if (!q.isFinite()) return false;
    // q(λᵢ)/p(λᵢ) once per sample: every channel of every response weights the same values
    // (SpectralResponse::estimate, with the division hoisted out of the channel loop).
    SampledSpectrum w;
    for (int i = 0; i < kWavelengthSamples; ++i)
      w[i] = lambda.pdf(i) > 0.0f ? q[i] / lambda.pdf(i) : 0.0f;
    double* sums = &sums_[(static_cast<size_t>(pixel.y) * static_cast<size_t>(resolution_.x) +
                           static_cast<size_t>(pixel.x)) *
                          stride_];
    for (const SpectralResponse* r : responses_) {
      if (r->isMosaic()) {
        *sums++ += estimate(r->channel(r->mosaic().channelAt(pixel.x, pixel.y)).curve, w, lambda);
      } else {
        for (int c = 0; c < r->channelCount(); ++c)
          *sums++ += estimate(r->channel(c).curve, w, lambda);
      }
    }
    return true;
  }

  glm::ivec2 resolution() const { return resolution_; }
  // One image per response: its channels named after the response's, or one channel
  // named after the response for a mosaic.
  std::vector<Image> toImages(int samplesPerPixel) const;

 private:
  // (1/N) Σᵢ r(λᵢ) wᵢ with wᵢ = q(λᵢ)/p(λᵢ) (0 where p = 0).
  static double estimate(const Spectrum& r, const SampledSpectrum& w,
                         const SampledWavelengths& lambda) {
    double sum = 0.0;
    for (int i = 0; i < kWavelengthSamples; ++i)
      sum += static_cast<double>(r.interpolate(lambda.gridIndex(i), lambda.gridFraction(i)) * w[i]);
    return sum / kWavelengthSamples;
  }

  glm::ivec2 resolution_;
  std::vector<const SpectralResponse*> responses_;
  size_t stride_ = 0;
  std::vector<double> sums_;
};

}  // namespace camsim
