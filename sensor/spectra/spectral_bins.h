// SpectralBins: a spectrum as one value per bin of equal probability under the visible
// wavelength pdf p(λ) (sampled_spectrum.h), for the spectral control variate
// (integrator/render/spectral_control_variate.h).
//
// | quantity          | unit | meaning                                                    |
// |-------------------|------|------------------------------------------------------------|
// | kSpectralBins = B | —    | 16 bins over 360–830 nm                                    |
// | bin b             | nm   | [λ_b, λ_b+1) with P(λ_b) = b/B, P the CDF of p             |
// | binEdgeNm(b)      | nm   | λ_b = P⁻¹(b/B), double precision (λ_0 = 360, λ_B = 830)    |
// | binCentreNm(b)    | nm   | P⁻¹((b + ½)/B): where a texture is evaluated for its bins  |
// | binOf(λ)          | —    | ⌊B·P(λ)⌋, at most B − 1                                    |
//
// The bins are narrow where p is large (15.9 nm about 538 nm) and wide in the tails
// (360–405.2 and 715.7–830 nm). A path's sampled wavelengths know their bins
// (SampledWavelengths::bin), so a binned spectrum is read at them with one lookup per
// wavelength (at()).
//
// binIntegrals(a, b) = ∫_bin a(λ)·b(λ) dλ for each bin, with a and b the piecewise-linear
// spectra Spectrum::operator() evaluates: exact (Simpson's rule on each piece between grid
// points and bin edges, where the product is a quadratic), in double precision.
#pragma once

#include <array>
#include <bit>
#include <cstdint>

#include "sensor/base/simd.h"
#include "sensor/spectra/sampled_spectrum.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

class SpectralBins {
 public:
  SpectralBins() : q_{} {}
  explicit SpectralBins(float c) : q_{Float4{} + c, Float4{} + c, Float4{} + c, Float4{} + c} {}

  float operator[](int b) const { return q_[b >> 2][b & 3]; }
  // Vector types alias their element type (GCC, Clang), so this reference is well defined.
  float& operator[](int b) { return reinterpret_cast<float*>(q_)[b]; }

  SpectralBins& operator*=(const SpectralBins& o) {
    for (int k = 0; k < 4; ++k) q_[k] *= o.q_[k];
    return *this;
  }
  SpectralBins& operator*=(float s) {
    for (Float4& q : q_) q *= s;
    return *this;
  }
  SpectralBins& operator+=(const SpectralBins& o) {
    for (int k = 0; k < 4; ++k) q_[k] += o.q_[k];
    return *this;
  }
  friend SpectralBins operator*(SpectralBins a, const SpectralBins& b) { return a *= b; }
  friend SpectralBins operator*(SpectralBins a, float s) { return a *= s; }

  // a += b·s, bin by bin.
  void addScaled(const SpectralBins& b, float s) {
    for (int k = 0; k < 4; ++k) q_[k] += b.q_[k] * s;
  }
  bool isZero() const {
    return !simd::anyLane((q_[0] != 0.0f) | (q_[1] != 0.0f) | (q_[2] != 0.0f) | (q_[3] != 0.0f));
  }
  // No bin has the exponent of ±∞ and NaN.
  bool isFinite() const {
    const auto special = [](Float4 q) {
      return (std::bit_cast<Int4>(q) & 0x7f800000) == 0x7f800000;
    };
    return !simd::anyLane(special(q_[0]) | special(q_[1]) | special(q_[2]) | special(q_[3]));
  }
  float maxComponent() const {
    const auto max4 = [](Float4 a, Float4 b) { return a > b ? a : b; };
    const Float4 m = max4(max4(q_[0], q_[1]), max4(q_[2], q_[3]));
    const float a = m[0] > m[1] ? m[0] : m[1], b = m[2] > m[3] ? m[2] : m[3];
    return a > b ? a : b;
  }
  // Σ_b v_b, in a fixed order (the four quarters lane by lane, then across).
  float sum() const {
    const Float4 s = (q_[0] + q_[1]) + (q_[2] + q_[3]);
    return (s[0] + s[1]) + (s[2] + s[3]);
  }
  // The values at a path's wavelengths: lane i holds the value of λᵢ's bin.
  SampledSpectrum at(const SampledWavelengths& lambda) const {
    SampledSpectrum s;
    for (int i = 0; i < kWavelengthSamples; ++i) s[i] = (*this)[lambda.bin(i)];
    return s;
  }

 private:
  static_assert(kSpectralBins == 16, "four quarters of four bins");
  Float4 q_[4];
};

double binEdgeNm(int b);
float binCentreNm(int b);
int binOf(float lambdaNm);
// ∫ over each bin of a(λ)·b(λ) dλ (exact for the piecewise-linear spectra).
std::array<double, kSpectralBins> binIntegrals(const Spectrum& a, const Spectrum& b);
// s averaged over each bin: ∫_bin s dλ / (λ_b+1 − λ_b).
SpectralBins binAverages(const Spectrum& s);

}  // namespace camsim
