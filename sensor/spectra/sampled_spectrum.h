// SampledSpectrum / SampledWavelengths: the spectral values one path carries.
//
// Hero-wavelength sampling (Wilkie et al. 2014): one uniform number u picks the hero
// wavelength; the other kWavelengthSamples−1 are its rotations u + k/N (mod 1) in the
// sampling CDF, so the N wavelengths of a path are stratified over 360–830 nm.
//
// Visible-wavelength pdf (shaped like the photopic response, so XYZ/RGB estimates have
// low variance):   p(λ) = a / (Z · cosh²(a (λ − 538 nm))),  a = 0.0072 nm⁻¹,
//   Z = tanh(a (830 − 538)) − tanh(a (360 − 538)),   inverted in closed form with atanh.
#pragma once

#include <bit>
#include <cmath>
#include <type_traits>

#include "sensor/base/float_math.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

// N = kWavelengthSamples is a build setting (CMake CAMSIM_WAVELENGTHS, 4 or 8): every
// spectral value of the tracer is one vector of N floats (FloatW). 8 halves the spectral
// part of the colour noise for about 15 % more time per sample (docs/performance.md,
// "Wavelengths per path").
#ifndef CAMSIM_WAVELENGTHS
#define CAMSIM_WAVELENGTHS 4
#endif
inline constexpr int kWavelengthSamples = CAMSIM_WAVELENGTHS;
static_assert(kWavelengthSamples == 4 || kWavelengthSamples == 8, "4 or 8 wavelengths per path");
// One vector of the path's wavelengths' values.
using FloatW = std::conditional_t<kWavelengthSamples == 4, Float4, Float8>;
using IntW = std::conditional_t<kWavelengthSamples == 4, Int4, Int8>;
// Bins of equal probability under the visible pdf (spectral_bins.h): each sampled
// wavelength knows its bin.
inline constexpr int kSpectralBins = 16;

// The values live in one vector (FloatW: a 16-byte Float4 for N = 4): the arithmetic is
// one SSE instruction per operation, and a SampledSpectrum is passed and returned in one
// xmm register instead of two halves (which the x86-64 ABI gives a struct of four floats,
// and which cost a store-forwarding stall each time they were joined again). Every
// operation is the same IEEE operation per wavelength as a loop would do: same bits.
class SampledSpectrum {
 public:
  SampledSpectrum() : v_{} {}
  explicit SampledSpectrum(float c) : v_(FloatW{} + c) {}
  explicit SampledSpectrum(const FloatW& v) : v_(v) {}

  float operator[](int i) const { return v_[i]; }
  // Vector types alias their element type (GCC, Clang), so this reference is well defined.
  float& operator[](int i) { return reinterpret_cast<float*>(&v_)[i]; }

#define CAMSIM_SS_OP(op)                                                            \
  SampledSpectrum& operator op##=(const SampledSpectrum& o) {                       \
    v_ op## = o.v_;                                                                 \
    return *this;                                                                   \
  }                                                                                 \
  SampledSpectrum& operator op##=(float s) {                                        \
    v_ op## = s;                                                                    \
    return *this;                                                                   \
  }                                                                                 \
  friend SampledSpectrum operator op(SampledSpectrum a, const SampledSpectrum& b) { \
    return a op## = b;                                                              \
  }                                                                                 \
  friend SampledSpectrum operator op(SampledSpectrum a, float s) {                  \
    return a op## = s;                                                              \
  }
  CAMSIM_SS_OP(+)
  CAMSIM_SS_OP(-)
  CAMSIM_SS_OP(*)
#undef CAMSIM_SS_OP
  friend SampledSpectrum operator*(float s, SampledSpectrum a) {
    return a *= s;
  }
  SampledSpectrum& operator/=(float s) {
    return *this *= 1.0f / s;
  }
  friend SampledSpectrum operator/(SampledSpectrum a, float s) {
    return a /= s;
  }
  // Component-wise division with 0/0 := 0 (a zero pdf never carries energy).
  friend SampledSpectrum safeDiv(SampledSpectrum a, const SampledSpectrum& b) {
    a.v_ = b.v_ != 0.0f ? a.v_ / b.v_ : FloatW{};
    return a;
  }

  // NaN counts as non-zero.
  bool isZero() const {
    return !lanes::any(v_ != 0.0f);
  }
  // No lane has the exponent of ±∞ and NaN.
  bool isFinite() const {
    return !lanes::any((std::bit_cast<IntW>(v_) & 0x7f800000) == 0x7f800000);
  }
  float maxComponent() const {
    float m = v_[0];
    for (int i = 0; i < kWavelengthSamples; ++i) m = v_[i] > m ? v_[i] : m;
    return m;
  }
  float average() const {
    float s = 0.0f;
    for (int i = 0; i < kWavelengthSamples; ++i) s += v_[i];
    return s / kWavelengthSamples;
  }

 private:
  FloatW v_;
};

class SampledWavelengths {
 public:
  // Stratified visible-range sampling from one uniform u in [0, 1).
  static SampledWavelengths sampleVisible(float u);
  // Stratified uniform sampling over [360, 830] nm (pdf 1/470 nm⁻¹), for tests.
  static SampledWavelengths sampleUniform(float u);
  // Every lane at λ (nm, in [360, 830]) with pdf 1: one wavelength, for tests that trace
  // camera rays at a single wavelength (the diffraction PSF at 550 nm alone).
  static SampledWavelengths monochromatic(float lambdaNm);
  // The centres of bins k·N … k·N + N − 1 (spectral_bins.h), pdf 1: a texture evaluated at
  // these, for k = 0 … kSpectralBins/N − 1, gives its values at every bin's centre.
  static const SampledWavelengths& binCentres(int k);

  float operator[](int i) const { return lambda_[i]; }
  float pdf(int i) const { return pdf_[i]; }
  // λᵢ's position on Spectrum's 1 nm grid (see Spectrum::interpolate).
  int gridIndex(int i) const { return gridIndex_[i]; }
  float gridFraction(int i) const { return gridFraction_[i]; }
  const IntW& gridIndices() const { return gridIndex_; }
  const FloatW& gridFractions() const { return gridFraction_; }
  // λᵢ's bin of equal probability under the visible pdf (spectral_bins.h), 0 … 15.
  int bin(int i) const { return bin_[i]; }
  // After a wavelength-dependent scattering event (dispersion) only the hero wavelength
  // can continue: the others get pdf 0 and the hero's pdf is divided by N, so the film's
  // estimate (1/N) Σ r q / p stays unbiased (pbrt-v4 §4.5.4).
  void terminateSecondary() {
    if (secondaryTerminated()) return;
    for (int i = 1; i < kWavelengthSamples; ++i) pdf_[i] = 0.0f;
    pdf_[0] /= static_cast<float>(kWavelengthSamples);
  }
  bool secondaryTerminated() const {
    for (int i = 1; i < kWavelengthSamples; ++i)
      if (pdf_[i] != 0.0f) return false;
    return true;
  }
  SampledSpectrum pdfs() const { return SampledSpectrum(pdf_); }

 private:
  void locateOnGrid();  // fills gridIndex_/gridFraction_ from lambda_

  // One vector each (float_math.h): sampling computes all four lanes at once.
  FloatW lambda_{};
  FloatW pdf_{};
  IntW gridIndex_{};
  FloatW gridFraction_{};
  IntW bin_{};
};

float visibleWavelengthPdf(float lambdaNm);
float sampleVisibleWavelength(float u);
// The visible pdf's CDF P(λ) = (tanh(a(λ − 538)) − tanh(a(360 − 538)))/Z and its inverse, in
// double precision (the bins of spectral_bins.h).
double visibleWavelengthCdf(double lambdaNm);
double visibleWavelengthQuantile(double u);

// The spectrum's values at the path's wavelengths (equal to s(lambda[i])).
inline SampledSpectrum sampleSpectrum(const Spectrum& s, const SampledWavelengths& lambda) {
  return SampledSpectrum(s.interpolateLanes(lambda.gridIndices(), lambda.gridFractions()));
}

}  // namespace camsim
