// Test support: slanted-edge images synthesised analytically, and the MTFs they should
// measure (tests of sensor/measure/slanted_edge.h and `camsim mtf`).
//
//   u = (x − cx)·cosθ − (y − cy)·sinθ        distance to a vertical edge tilted by θ (px;
//                                            x, y image coordinates, pixel i spans [i, i+1])
//   (a horizontal edge: x and y swapped)
//   Gaussian blur σ (px):   ESF E(u) = Φ(u/σ),  MTF exp(−2π²σ²f²)
//   defocus disc of diameter d (px), R = d/2: LSF ∝ √(R² − u²),
//       E(u) = ½ + (u√(R² − u²) + R² asin(u/R))/(πR²),  MTF 2J₁(πdf)/(πdf)
//   value = dark + (bright − dark)·E
// Point-sampled: E at the pixel's centre. Pixel-area-integrated: E averaged over the
// pixel, exactly across the edge (F, the antiderivative of E) and with a 16-point
// midpoint rule along it; its MTF is the optics' times the square pixel's aperture along
// the normal, |sinc(f cosθ)·sinc(f sinθ)| (sinc x = sin πx/πx).
#pragma once

#include <cmath>
#include <numbers>

#include "sensor/base/image.h"

namespace camsim::test {

enum class EdgeBlur { kGaussian, kDisc };

struct SyntheticEdge {
  int width = 64, height = 128;           // px
  double centreX = 32.0, centreY = 64.0;  // a point of the edge (px)
  double angleDeg = 5.0;
  bool vertical = true;
  EdgeBlur blur = EdgeBlur::kGaussian;
  double size = 0.5;  // σ (Gaussian) or d (disc), px; 0: a perfect step
  bool areaIntegrated = false;
  double dark = 0.1, bright = 0.9;
};

inline double edgeEsf(const SyntheticEdge& e, double u) {
  if (e.size <= 0.0) return u > 0.0 ? 1.0 : (u < 0.0 ? 0.0 : 0.5);
  if (e.blur == EdgeBlur::kGaussian) return 0.5 * std::erfc(-u / (e.size * std::numbers::sqrt2));
  const double r = 0.5 * e.size;
  if (u <= -r) return 0.0;
  if (u >= r) return 1.0;
  return 0.5 +
         (u * std::sqrt(r * r - u * u) + r * r * std::asin(u / r)) / (std::numbers::pi * r * r);
}

// ∫ E du, zero far on the dark side.
inline double edgeEsfIntegral(const SyntheticEdge& e, double u) {
  if (e.size <= 0.0) return std::max(u, 0.0);
  if (e.blur == EdgeBlur::kGaussian) {
    const double z = u / e.size;
    return u * edgeEsf(e, u) + e.size * std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi);
  }
  const double r = 0.5 * e.size;
  if (u <= -r) return 0.0;
  if (u >= r) return u;
  const double s = std::sqrt(r * r - u * u);
  return 0.5 * u +
         (-s * s * s / 3.0 + r * r * (u * std::asin(u / r) + s)) / (std::numbers::pi * r * r);
}

inline Image syntheticEdgeImage(const SyntheticEdge& e, const char* name = "Y") {
  Image img(e.width, e.height, {name});
  const double t = e.angleDeg * std::numbers::pi / 180.0, c = std::cos(t), s = std::sin(t);
  constexpr int kAlong = 16;
  for (int py = 0; py < e.height; ++py)
    for (int px = 0; px < e.width; ++px) {
      // across: the coordinate the edge varies with; along: the other.
      const double across0 = e.vertical ? px - e.centreX : py - e.centreY;
      const double along0 = e.vertical ? py - e.centreY : px - e.centreX;
      double v = 0.0;
      if (!e.areaIntegrated) {
        v = edgeEsf(e, (across0 + 0.5) * c - (along0 + 0.5) * s);
      } else {
        for (int k = 0; k < kAlong; ++k) {
          const double along = along0 + (k + 0.5) / kAlong;
          const double u0 = across0 * c - along * s, u1 = u0 + c;
          v += (edgeEsfIntegral(e, u1) - edgeEsfIntegral(e, u0)) / c;
        }
        v /= kAlong;
      }
      img.at(px, py, 0) = static_cast<float>(e.dark + (e.bright - e.dark) * v);
    }
  return img;
}

inline double sincPi(double x) {
  return x == 0.0 ? 1.0 : std::sin(std::numbers::pi * x) / (std::numbers::pi * x);
}

// The MTF the edge should measure at f cycles/px (the optics, × the pixel aperture if
// area-integrated).
inline double expectedEdgeMtf(const SyntheticEdge& e, double f) {
  double optics = 1.0;
  if (e.size > 0.0 && e.blur == EdgeBlur::kGaussian) {
    optics = std::exp(-2.0 * std::numbers::pi * std::numbers::pi * e.size * e.size * f * f);
  } else if (e.size > 0.0 && f > 0.0) {
    const double x = std::numbers::pi * e.size * f;
    optics = 2.0 * std::cyl_bessel_j(1.0, x) / x;
  }
  if (e.areaIntegrated) {
    const double t = e.angleDeg * std::numbers::pi / 180.0;
    optics *= sincPi(f * std::cos(t)) * sincPi(f * std::sin(t));
  }
  return std::abs(optics);
}

}  // namespace camsim::test
