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

#include <array>
#include <cmath>

#include "sensor/spectrum.h"

namespace camsim {

inline constexpr int kWavelengthSamples = 4;

class SampledSpectrum {
 public:
  SampledSpectrum() { v_.fill(0.0f); }
  explicit SampledSpectrum(float c) { v_.fill(c); }

  float operator[](int i) const { return v_[i]; }
  float& operator[](int i) { return v_[i]; }

#define CAMSIM_SS_OP(op)                                                            \
  SampledSpectrum& operator op##=(const SampledSpectrum& o) {                       \
    for (int i = 0; i < kWavelengthSamples; ++i) v_[i] op## = o.v_[i];              \
    return *this;                                                                   \
  }                                                                                 \
  SampledSpectrum& operator op##=(float s) {                                        \
    for (int i = 0; i < kWavelengthSamples; ++i) v_[i] op## = s;                    \
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
    for (int i = 0; i < kWavelengthSamples; ++i)
      a.v_[i] = b.v_[i] != 0.0f ? a.v_[i] / b.v_[i] : 0.0f;
    return a;
  }

  bool isZero() const {
    for (float x : v_)
      if (x != 0.0f) return false;
    return true;
  }
  bool isFinite() const {
    for (float x : v_)
      if (!std::isfinite(x)) return false;
    return true;
  }
  float maxComponent() const {
    float m = v_[0];
    for (float x : v_) m = x > m ? x : m;
    return m;
  }
  float average() const {
    float s = 0.0f;
    for (float x : v_) s += x;
    return s / kWavelengthSamples;
  }

 private:
  std::array<float, kWavelengthSamples> v_;
};

class SampledWavelengths {
 public:
  // Stratified visible-range sampling from one uniform u in [0, 1).
  static SampledWavelengths sampleVisible(float u);
  // Stratified uniform sampling over [360, 830] nm (pdf 1/470 nm⁻¹), for tests.
  static SampledWavelengths sampleUniform(float u);

  float operator[](int i) const { return lambda_[i]; }
  float pdf(int i) const { return pdf_[i]; }
  // λᵢ's position on Spectrum's 1 nm grid (see Spectrum::interpolate).
  int gridIndex(int i) const { return gridIndex_[i]; }
  float gridFraction(int i) const { return gridFraction_[i]; }
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
  SampledSpectrum pdfs() const {
    SampledSpectrum p;
    for (int i = 0; i < kWavelengthSamples; ++i) p[i] = pdf_[i];
    return p;
  }

 private:
  void locateOnGrid();  // fills gridIndex_/gridFraction_ from lambda_

  std::array<float, kWavelengthSamples> lambda_{};
  std::array<float, kWavelengthSamples> pdf_{};
  std::array<int, kWavelengthSamples> gridIndex_{};
  std::array<float, kWavelengthSamples> gridFraction_{};
};

float visibleWavelengthPdf(float lambdaNm);
float sampleVisibleWavelength(float u);

// The spectrum's values at the path's wavelengths (equal to s(lambda[i])).
inline SampledSpectrum sampleSpectrum(const Spectrum& s, const SampledWavelengths& lambda) {
  SampledSpectrum out;
  for (int i = 0; i < kWavelengthSamples; ++i)
    out[i] = s.interpolate(lambda.gridIndex(i), lambda.gridFraction(i));
  return out;
}

}  // namespace camsim
