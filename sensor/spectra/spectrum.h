// Spectrum: a function of wavelength, stored densely at 1 nm over [360, 830] nm.
//
// Every spectral quantity in camsim (reflectance, spectral radiance, colour-matching
// function, quantum efficiency) is converted to this one representation when it is
// loaded, so evaluation on the hot path is one lookup and one lerp, with no virtual call.
// The unit is the caller's: reflectance is dimensionless, spectral radiance is
// W·m⁻²·sr⁻¹·nm⁻¹, and so on; the type carries numbers, the field names carry units.
#pragma once

#include <algorithm>
#include <array>
#include <cstring>
#include <span>

#include "sensor/base/float_math.h"

namespace camsim {

inline constexpr int kLambdaMinNm = 360;
inline constexpr int kLambdaMaxNm = 830;
inline constexpr int kSpectrumSamples = kLambdaMaxNm - kLambdaMinNm + 1;  // 471

// What a tabulated spectrum does outside its table's wavelength range.
enum class Extrapolation {
  kZero,   // 0 outside (emission, sensitivities)
  kClamp,  // hold the end values (reflectance measured over a shorter range)
};

class Spectrum {
 public:
  Spectrum() { values_.fill(0.0f); }

  static Spectrum constant(double value);
  // Planck's law: spectral radiance of a blackbody, W·m⁻²·sr⁻¹·nm⁻¹.
  static Spectrum blackbody(double kelvin);
  // Piecewise-linear through (lambdaNm[i], values[i]); lambdaNm strictly increasing.
  static Spectrum fromSamples(std::span<const double> lambdaNm, std::span<const double> values,
                              Extrapolation outside);

  // Linear interpolation; 0 outside [360, 830] nm.
  float operator()(float lambdaNm) const {
    const float x = lambdaNm - static_cast<float>(kLambdaMinNm);
    if (!(x >= 0.0f) || x > static_cast<float>(kSpectrumSamples - 1)) return 0.0f;
    const GridPosition g = gridPosition(lambdaNm);
    return interpolate(g.index, g.fraction);
  }

  // Where λ falls on the 1 nm grid, clamped to [360, 830] nm: index = ⌊λ − 360⌋ (at most
  // 469) and fraction = λ − 360 − index. SampledWavelengths computes it once per path, so
  // that each of the many lookups a path makes at the same wavelengths is one lerp.
  struct GridPosition {
    int index;
    float fraction;
  };
  static GridPosition gridPosition(float lambdaNm) {
    GridPosition g;
    gridPositionLanes(lambdaNm, g.index, g.fraction);
    return g;
  }
  // The same for F = float (I = int) or F = Float4 (I = Int4, float_math.h), lane by lane.
  template <typename F, typename I>
  static void gridPositionLanes(F lambdaNm, I& index, F& fraction) {
    constexpr auto top = static_cast<float>(kSpectrumSamples - 1);
    F x = lambdaNm - static_cast<float>(kLambdaMinNm);
    x = x < 0.0f ? 0.0f : x;  // std::clamp(x, 0, top)
    x = top < x ? top : x;
    I i = lanes::toInt(x);  // x ≥ 0: truncation is ⌊x⌋
    i = i >= kSpectrumSamples - 1 ? kSpectrumSamples - 2 : i;
    index = i;
    fraction = x - lanes::toFloat(i);
  }
  // The interpolation at a grid position (index, fraction).
  float interpolate(int i, float t) const { return values_[i] + t * (values_[i + 1] - values_[i]); }
  // Four interpolations at once (the same bits as four calls): each lane's two neighbouring
  // values in one 8-byte load, two shuffles, a vector lerp (fewer than half the
  // instructions of a scalar load per value).
  Float4 interpolateLanes(const Int4& i, const Float4& t) const {
    using Float2 = float __attribute__((vector_size(8)));
    const auto pairAt = [this](int index) {
      Float2 p;
      std::memcpy(&p, values_.data() + index, sizeof p);  // values index, index + 1
      return p;
    };
    const Float4 p01 = __builtin_shufflevector(pairAt(i[0]), pairAt(i[1]), 0, 1, 2, 3);
    const Float4 p23 = __builtin_shufflevector(pairAt(i[2]), pairAt(i[3]), 0, 1, 2, 3);
    const Float4 a = __builtin_shufflevector(p01, p23, 0, 2, 4, 6);
    const Float4 b = __builtin_shufflevector(p01, p23, 1, 3, 5, 7);
    return a + t * (b - a);
  }
  Float8 interpolateLanes(const Int8& i, const Float8& t) const {
    const Float4 lo =
        interpolateLanes(Int4{i[0], i[1], i[2], i[3]}, Float4{t[0], t[1], t[2], t[3]});
    const Float4 hi =
        interpolateLanes(Int4{i[4], i[5], i[6], i[7]}, Float4{t[4], t[5], t[6], t[7]});
    return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
  }

  // Value at sample i, i.e. at (360 + i) nm.
  float sample(int i) const { return values_[i]; }
  float& sample(int i) { return values_[i]; }

  Spectrum& operator*=(double s);
  Spectrum& operator*=(const Spectrum& s);
  friend Spectrum operator*(Spectrum a, double s) { return a *= s; }
  friend Spectrum operator*(Spectrum a, const Spectrum& b) { return a *= b; }

  double maxValue() const;
  double minValue() const;
  // Σ value·1 nm over the grid (rectangle rule on the 1 nm grid, the CIE convention).
  double sum() const;

 private:
  std::array<float, kSpectrumSamples> values_;
};

// Σ a(λ)·b(λ)·1 nm over the grid.
double innerProduct(const Spectrum& a, const Spectrum& b);

}  // namespace camsim
