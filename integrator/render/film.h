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

#include "sensor/base/image.h"
#include "sensor/model/spectral_response.h"
#include "sensor/spectra/sampled_spectrum.h"

namespace camsim {

class Film {
 public:
  Film(glm::ivec2 resolution, std::vector<const SpectralResponse*> responses);

  // q: the sample's weighted spectral quantity (radiance × camera weight). Returns false
  // (and adds nothing) if it is not finite.
  bool addSample(glm::ivec2 pixel, const SampledSpectrum& q, const SampledWavelengths& lambda) {
    if (!q.isFinite()) return false;
    // q(λᵢ)/p(λᵢ) once per sample: every channel of every response weights the same values.
    const SampledSpectrum w = safeDiv(q, lambda.pdfs());
    double* sums = &sums_[(static_cast<size_t>(pixel.y) * static_cast<size_t>(resolution_.x) +
                           static_cast<size_t>(pixel.x)) *
                          stride_];
    for (const SpectralResponse* r : responses_) {
      if (r->isMosaic()) {
        *sums++ += r->estimate(r->mosaic().channelAt(pixel.x, pixel.y), w, lambda);
      } else {
        for (int c = 0; c < r->channelCount(); ++c) *sums++ += r->estimate(c, w, lambda);
      }
    }
    return true;
  }

  glm::ivec2 resolution() const { return resolution_; }
  // One image per response: its channels named after the response's, or one channel
  // named after the response for a mosaic.
  std::vector<Image> toImages(int samplesPerPixel) const;

 private:
  glm::ivec2 resolution_;
  std::vector<const SpectralResponse*> responses_;
  size_t stride_ = 0;
  std::vector<double> sums_;
};

}  // namespace camsim
