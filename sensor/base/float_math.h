// Single-precision functions on bounded ranges for the per-sample hot path, in plain
// arithmetic: no call into libm, the same bits whatever libm the binary runs with.
// logOfNormal also takes a Float4 (four lanes in one vector register), so the four
// wavelengths of a pixel sample are computed in one pass. Accuracy is checked against libm
// in tests/sensor/base/float_math_test.cpp.
//
//   logOfNormal(x)      ln x for normal, finite x > 0:
//                       x = m·2^e with m in [√½, √2), s = (m − 1)/(m + 1), |s| ≤ 0.1716:
//                       ln x = e·ln 2 + 2 atanh(s) = e·ln 2 + 2(s + s³/3 + s⁵/5 + s⁷/7 + s⁹/9)
//                       (truncation ≤ 2 s¹¹/11 ≈ 7e-10); measured within 1.07 ulp of ln x
//                       (libm's logf: 0.50), or 1.5e-7 absolute near x = 1
//   sinCosQuarterPi(x)  sin x and cos x for |x| ≤ π/4: Taylor polynomials to x⁹ and x¹⁰
//                       (truncation ≤ (π/4)¹¹/11! ≈ 1.8e-9 and (π/4)¹²/12! ≈ 1.2e-10) by
//                       Estrin's scheme; measured within 0.70 and 0.98 ulp (libm's
//                       sinf/cosf: 0.56 and 0.50)
#pragma once

#include <bit>
#include <cstdint>

#include "sensor/base/simd.h"

namespace camsim {

// Float4 / Int4 (sensor/base/simd.h): four floats / ints in one vector. Code written once
// for F = float and F = Float4 uses the helpers in lanes:: (the int type of the same
// shape, conversions), so its scalar and four-lane forms do the same IEEE operations.

namespace lanes {
// The int type of F's shape (logOfNormal works on the bits).
template <typename F>
struct IntOf {
  using type = std::int32_t;
};
template <>
struct IntOf<Float4> {
  using type = Int4;
};
template <>
struct IntOf<Float8> {
  using type = Int8;
};
inline float toFloat(std::int32_t i) {
  return static_cast<float>(i);
}
inline Float4 toFloat(Int4 i) {
  return __builtin_convertvector(i, Float4);
}
inline Float8 toFloat(Int8 i) {
  return __builtin_convertvector(i, Float8);
}
inline std::int32_t toInt(float x) {  // truncation
  return static_cast<std::int32_t>(x);
}
inline Int4 toInt(Float4 x) {
  return __builtin_convertvector(x, Int4);
}
inline Int8 toInt(Float8 x) {
  return __builtin_convertvector(x, Int8);
}
// Whether any lane of a comparison's result (−1 true, 0 false) is true.
inline bool any(Int4 mask) {
  return simd::anyLane(mask);
}
inline bool any(Int8 mask) {
  return simd::anyLane(mask);
}
}  // namespace lanes

// F: float or Float4; the same operations per lane, so the same bits either way.
template <typename F>
inline F logOfNormal(F x) {
  using I = typename lanes::IntOf<F>::type;
  const auto bits = std::bit_cast<I>(x);
  const I e = (bits - 0x3f3504f3) >> 23;  // 0x3f3504f3: the bits of √½
  const F m = std::bit_cast<F>(bits - e * (1 << 23));
  const F s = (m - 1.0f) / (m + 1.0f);
  const F s2 = s * s;
  const F series =
      s *
      (2.0f + s2 * (2.0f / 3.0f + s2 * (2.0f / 5.0f + s2 * (2.0f / 7.0f + s2 * (2.0f / 9.0f)))));
  return lanes::toFloat(e) * 0.693147182f + series;
}

struct SinCos {
  float sin, cos;
};

inline SinCos sinCosQuarterPi(float x) {
  // Estrin's scheme: the terms pair up on x², x⁴, x⁸, so the chain is four multiplies and
  // three adds deep instead of Horner's five multiply-adds (it ends a bounce's direction).
  const float x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
  // The small terms are summed first and 1 (or x) added last: within 0.70 / 0.98 ulp (Horner
  // with 1 inside: 1.12).
  const float sinTail = x2 * (-1.0f / 6.0f) +
                        (x4 * (1.0f / 120.0f + x2 * (-1.0f / 5040.0f)) + x8 * (1.0f / 362880.0f));
  const float cosTail = x2 * -0.5f + (x4 * (1.0f / 24.0f + x2 * (-1.0f / 720.0f)) +
                                      x8 * (1.0f / 40320.0f + x2 * (-1.0f / 3628800.0f)));
  const float sin = x + x * sinTail;
  const float cos = 1.0f + cosTail;
  return {sin, cos};
}

}  // namespace camsim
