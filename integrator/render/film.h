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
//
// The film also sums, per pixel, the odd-indexed samples of one channel — the error channel:
// the "Y" of the first response that has one, else the first response's first stored
// channel — so the render can estimate its own error from the two half-sample images
// (error_estimate.h): one double more per pixel. And it keeps each pixel's sample count n
// (the render loop sets it), which adaptive sampling makes differ between pixels.
//
// With a spectral reference E (setSpectralReference) a sample may bring the control
// variate's bins B (integrator/render/spectral_control_variate.h): the film then adds
//   (1/N) Σᵢ r_c(λᵢ) (q(λᵢ) − B[bin(λᵢ)] E(λᵢ)) / p(λᵢ)  +  Σ_b B_b ∫_bin b r_c E dλ,
// whose expectation over the wavelengths is the same v_c; the integrals are computed once.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "integrator/render/error_estimate.h"
#include "sensor/base/image.h"
#include "sensor/model/spectral_response.h"
#include "sensor/spectra/sampled_spectrum.h"
#include "sensor/spectra/spectral_bins.h"

namespace camsim {

class Film {
 public:
  Film(glm::ivec2 resolution, std::vector<const SpectralResponse*> responses);

  // q: the sample's weighted spectral quantity (radiance × camera weight); sampleIndex: the
  // sample's index in its pixel (its parity picks the half). Returns false (and adds
  // nothing) if q is not finite.
  // cv: the sample's control-variate bins (null: none; ignored without a reference).
  bool addSample(glm::ivec2 pixel, int sampleIndex, const SampledSpectrum& q,
                 const SampledWavelengths& lambda, const SpectralBins* cv = nullptr) {
    if (!q.isFinite()) return false;
    if (cv && cvWeights_.empty()) cv = nullptr;
    if (cv && !cv->isFinite()) return false;
    // q(λᵢ)/p(λᵢ) once per sample: every channel of every response weights the same values.
    const SampledSpectrum w =
        safeDiv(cv ? q - cv->at(lambda) * sampleSpectrum(reference_, lambda) : q, lambda.pdfs());
    if (cv && !w.isFinite()) return false;
    const size_t p = index(pixel);
    const double errorValue = addResponses(&sums_[p * stride_], w, lambda, pixel, cv);
    if (sampleIndex & 1) oddSums_[p] += errorValue;
    return true;
  }
  // Enables the control variate's term above with reference emission E.
  void setSpectralReference(const Spectrum& reference);
  bool hasSpectralReference() const { return !cvWeights_.empty(); }

  glm::ivec2 resolution() const { return resolution_; }
  // A pixel's samples so far (rejected ones too: they count as 0): set after adding them.
  void setSamples(glm::ivec2 pixel, int n) { samples_[index(pixel)] = n; }
  // The error channel's mean over a pixel's samples, I, and over its odd-indexed ones, b
  // (0 below 2 samples): what adaptive sampling checks.
  double errorValue(glm::ivec2 pixel) const;
  double errorOddMean(glm::ivec2 pixel) const;
  // The error channel's mean over the image (its pixels' I).
  double errorMean() const;
  // One image per response (pixel means over each pixel's own samples): its channels named
  // after the response's, or one channel named after the response for a mosaic.
  std::vector<Image> toImages() const;
  // The error channel's name ("Y", or the response's channel or mosaic name); it is
  // channel errorImageChannel() of toImages()[errorImage()].
  const std::string& errorChannel() const { return errorChannelName_; }
  std::size_t errorImage() const { return errorImage_; }
  int errorImageChannel() const { return errorImageChannel_; }
  // The mean of the error channel over each pixel's odd-indexed samples (⌊n/2⌋ of n ≥ 2),
  // one channel named errorChannel().
  Image oddHalfImage() const;
  // Each pixel's n, one channel named "spp".
  Image sampleCountImage() const;
  // The render's estimate of its error on the error channel (error_estimate.h), from
  // toImages() and oddHalfImage(); samplesPerPixel ≥ 2: the most any pixel has (its k).
  ErrorMetrics estimateError(int samplesPerPixel) const;

 private:
  size_t index(glm::ivec2 pixel) const {
    return static_cast<size_t>(pixel.y) * static_cast<size_t>(resolution_.x) +
           static_cast<size_t>(pixel.x);
  }
  // Adds the sample to a pixel's sums; returns its value on the error channel.
  double addResponses(double* sums, const SampledSpectrum& w, const SampledWavelengths& lambda,
                      glm::ivec2 pixel, const SpectralBins* cv) const {
    const double* const errorSum = sums + errorOffset_;
    double errorValue = 0.0;
    const auto add = [&](double v) {
      if (sums == errorSum) errorValue = v;
      *sums++ += v;
    };
    // The control variate's weights of channel c of response k: cvWeights_[cvFirst_[k] + c].
    const auto term = [&](std::size_t k, int c) {
      return cv ? static_cast<double>(
                      (*cv * cvWeights_[cvFirst_[k] + static_cast<std::size_t>(c)]).sum())
                : 0.0;
    };
    for (std::size_t k = 0; k < responses_.size(); ++k) {
      const SpectralResponse* r = responses_[k];
      if (r->isMosaic()) {
        const int c = r->mosaic().channelAt(pixel.x, pixel.y);
        add(r->estimate(c, w, lambda) + term(k, c));
      } else {
        for (int c = 0; c < r->channelCount(); ++c) add(r->estimate(c, w, lambda) + term(k, c));
      }
    }
    return errorValue;
  }

  glm::ivec2 resolution_;
  std::vector<const SpectralResponse*> responses_;
  size_t stride_ = 0;
  std::vector<double> sums_;
  size_t errorOffset_ = 0;  // the error channel's place in a pixel's sums
  std::size_t errorImage_ = 0;
  int errorImageChannel_ = 0;
  std::string errorChannelName_;
  std::vector<double> oddSums_;  // per pixel: Σ of the error channel over odd-indexed samples
  std::vector<int> samples_;     // per pixel: n
  // The control variate (empty: off): E, and ∫_bin r_c E dλ per bin for every channel.
  Spectrum reference_;
  std::vector<SpectralBins> cvWeights_;
  std::vector<std::size_t> cvFirst_;  // per response: its first channel's place in cvWeights_
};

}  // namespace camsim
