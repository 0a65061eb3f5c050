// Colour difference: CIE 1976 L*a*b* and the CIEDE2000 colour-difference formula.
//
// CIELAB (CIE 15:2018), relative to a reference white (Xn, Yn, Zn):
//   L* = 116 f(Y/Yn) − 16,  a* = 500 [f(X/Xn) − f(Y/Yn)],  b* = 200 [f(Y/Yn) − f(Z/Zn)]
//   f(t) = t^(1/3)                    for t > (6/29)³
//        = t / (3 (6/29)²) + 4/29     otherwise
//
// CIEDE2000 (CIE 142-2001), implemented from G. Sharma, W. Wu, E. N. Dalal, "The CIEDE2000
// color-difference formula: implementation notes, supplementary test data, and
// mathematical observations", Color Res. Appl. 30(1), 2005, eqs. (1)–(22):
//   C*ᵢ = √(a*ᵢ² + b*ᵢ²),  G = ½ (1 − √(C̄*⁷ / (C̄*⁷ + 25⁷))),  a′ᵢ = (1 + G) a*ᵢ
//   C′ᵢ = √(a′ᵢ² + b*ᵢ²),  h′ᵢ = atan2(b*ᵢ, a′ᵢ) ∈ [0°, 360°) (0 when a′ = b* = 0)
//   ΔL′ = L*₂ − L*₁,  ΔC′ = C′₂ − C′₁,  ΔH′ = 2 √(C′₁C′₂) sin(Δh′/2)
//   Δh′ = h′₂ − h′₁ wrapped into [−180°, 180°] (0 if C′₁C′₂ = 0)
//   h̄′ = mean hue, +180° when |h′₁ − h′₂| > 180° (sum h′₁ + h′₂ if C′₁C′₂ = 0)
//   T = 1 − 0.17 cos(h̄′ − 30°) + 0.24 cos 2h̄′ + 0.32 cos(3h̄′ + 6°) − 0.20 cos(4h̄′ − 63°)
//   S_L = 1 + 0.015 (L̄′ − 50)² / √(20 + (L̄′ − 50)²),  S_C = 1 + 0.045 C̄′,  S_H = 1 + 0.015 C̄′ T
//   R_T = −sin(2Δθ) R_C,  Δθ = 30° exp(−((h̄′ − 275°)/25°)²),  R_C = 2 √(C̄′⁷ / (C̄′⁷ + 25⁷))
//   ΔE₀₀ = √((ΔL′/k_L S_L)² + (ΔC′/k_C S_C)² + (ΔH′/k_H S_H)² + R_T (ΔC′/k_C S_C)(ΔH′/k_H S_H))
//
// | parameter       | unit         | default | meaning                                   |
// |-----------------|--------------|---------|-------------------------------------------|
// | white (Xn,Yn,Zn)| XYZ (Y rel.) | —       | reference white of the Lab conversion     |
// | k_L, k_C, k_H   | —            | 1, 1, 1 | parametric factors (reference conditions) |
#pragma once

#include <glm/vec3.hpp>

#include "sensor/base/image.h"

namespace camsim {

struct Ciede2000Weights {
  double kL = 1.0, kC = 1.0, kH = 1.0;
};

// (L*, a*, b*) of xyz relative to white (same scale as xyz, e.g. both with white Y = 1).
glm::dvec3 xyzToLab(const glm::dvec3& xyz, const glm::dvec3& white);
// CIEDE2000 colour difference between two (L*, a*, b*) colours; symmetric.
double deltaE2000(const glm::dvec3& lab1, const glm::dvec3& lab2, const Ciede2000Weights& k = {});

// Image versions. xyzToLab: 3 channels (X, Y, Z in that order) → channels "L", "a", "b".
// deltaE2000: two Lab images of the same size → one channel "dE00".
// Throws InputError for a wrong channel count or mismatched sizes.
Image xyzToLab(const Image& xyz, const glm::dvec3& white);
Image deltaE2000(const Image& lab1, const Image& lab2, const Ciede2000Weights& k = {});

}  // namespace camsim
