// RGB colour spaces defined by their primaries and white point (xy chromaticities).
//
//   xyzFromRgb = [ Xr Xg Xb ; Yr Yg Yb ; Zr Zg Zb ] with each primary's XYZ scaled so that
//   xyzFromRgb · (1,1,1) = XYZ(white, Y = 1);   rgbFromXyz = xyzFromRgb⁻¹.
// The matrices are derived from the chromaticities, never typed in.
//
// Chromatic adaptation is Bradford's (von Kries scaling in the Bradford "sharpened" cone
// space, as in ICC v4 and Lindbloom):
//   B(s → d) = M_BFD⁻¹ diag(M_BFD X_d / M_BFD X_s) M_BFD,
//   M_BFD = [0.8951 0.2664 −0.1614; −0.7502 1.7135 0.0367; 0.0389 −0.0685 1.0296]
// camsim's scene-linear XYZ is D65-adapted; a working space with another white (ACEScg's
// ≈D60) is reached through B(D65 → its white), then rgbFromXyz. B(D65 → D65) is the
// identity. The D65 white X_D65 is the tabulated D65 spectrum through the CIE 1931
// observer, Y = 1 (xy ≈ 0.3127, 0.3290).
#pragma once

#include <string>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "sensor/spectra/cie.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

class RgbColorSpace {
 public:
  RgbColorSpace(std::string name, Chromaticity r, Chromaticity g, Chromaticity b,
                Chromaticity white, Spectrum illuminant);

  const std::string& name() const { return name_; }
  Chromaticity red() const { return r_; }
  Chromaticity green() const { return g_; }
  Chromaticity blue() const { return b_; }
  Chromaticity white() const { return w_; }
  // The spectrum of the white point (used to uplift RGB to spectra), relative units.
  const Spectrum& illuminant() const { return illuminant_; }

  glm::dvec3 toXyz(const glm::dvec3& rgb) const { return xyzFromRgb_ * rgb; }
  glm::dvec3 fromXyz(const glm::dvec3& xyz) const { return rgbFromXyz_ * xyz; }
  const glm::dmat3& xyzFromRgb() const { return xyzFromRgb_; }
  const glm::dmat3& rgbFromXyz() const { return rgbFromXyz_; }

  static const RgbColorSpace& linearRec709();  // = linear sRGB, D65 white
  static const RgbColorSpace& acesCg();        // AP1 primaries, ACES white (≈D60)
  static const RgbColorSpace& aces2065();      // AP0 primaries, ACES white

 private:
  std::string name_;
  Chromaticity r_, g_, b_, w_;
  Spectrum illuminant_;
  glm::dmat3 xyzFromRgb_, rgbFromXyz_;
};

// Bradford adaptation matrix from one white's XYZ to another's (any common scale).
glm::dmat3 bradfordAdaptation(const glm::dvec3& sourceWhite, const glm::dvec3& destinationWhite);
// XYZ of the D65 white, Y = 1 (the tabulated spectrum through the observer).
glm::dvec3 d65WhiteXyz();
// D65-adapted XYZ → the space's RGB (Bradford D65 → its white, then rgbFromXyz).
glm::dmat3 xyzD65ToWorkingSpace(const RgbColorSpace& space);

// sRGB transfer function (IEC 61966-2-1), linear [0,1] → encoded [0,1].
double srgbEncode(double linear);
double srgbDecode(double encoded);

}  // namespace camsim
