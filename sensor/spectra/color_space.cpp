#include "sensor/spectra/color_space.h"

#include <cmath>

#include <glm/matrix.hpp>

#include "sensor/spectra/spectral_data.h"

namespace camsim {

RgbColorSpace::RgbColorSpace(std::string name, Chromaticity r, Chromaticity g, Chromaticity b,
                             Chromaticity white, Spectrum illuminant)
    : name_(std::move(name)), r_(r), g_(g), b_(b), w_(white), illuminant_(illuminant) {
  // Columns are the primaries' XYZ at Y = 1; scale them so that RGB (1,1,1) is the white.
  const glm::dmat3 primaries(chromaticityToXyz(r), chromaticityToXyz(g), chromaticityToXyz(b));
  const glm::dvec3 scale = glm::inverse(primaries) * chromaticityToXyz(white);
  xyzFromRgb_ = glm::dmat3(primaries[0] * scale.x, primaries[1] * scale.y, primaries[2] * scale.z);
  rgbFromXyz_ = glm::inverse(xyzFromRgb_);
}

const RgbColorSpace& RgbColorSpace::linearRec709() {
  static const RgbColorSpace cs("lin_rec709", {0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06},
                                {0.3127, 0.3290}, cieIlluminant("D65"));
  return cs;
}

const RgbColorSpace& RgbColorSpace::acesCg() {
  static const RgbColorSpace cs("acescg", {0.713, 0.293}, {0.165, 0.830}, {0.128, 0.044},
                                {0.32168, 0.33767}, cieIlluminant("ACES_D60"));
  return cs;
}

const RgbColorSpace& RgbColorSpace::aces2065() {
  static const RgbColorSpace cs("aces2065-1", {0.7347, 0.2653}, {0.0, 1.0}, {0.0001, -0.0770},
                                {0.32168, 0.33767}, cieIlluminant("ACES_D60"));
  return cs;
}

glm::dmat3 bradfordAdaptation(const glm::dvec3& sourceWhite, const glm::dvec3& destinationWhite) {
  // Rows as published; glm is column-major, hence the transpose.
  const glm::dmat3 bfd = glm::transpose(glm::dmat3(0.8951, 0.2664, -0.1614,  //
                                                   -0.7502, 1.7135, 0.0367,  //
                                                   0.0389, -0.0685, 1.0296));
  const glm::dvec3 src = bfd * sourceWhite;
  const glm::dvec3 dst = bfd * destinationWhite;
  glm::dmat3 scale(1.0);
  for (int i = 0; i < 3; ++i) scale[i][i] = dst[i] / src[i];
  return glm::inverse(bfd) * scale * bfd;
}

glm::dvec3 d65WhiteXyz() {
  static const glm::dvec3 white = reflectanceToXyz(Spectrum::constant(1.0), cieIlluminant("D65"));
  return white;
}

glm::dmat3 xyzD65ToWorkingSpace(const RgbColorSpace& space) {
  return space.rgbFromXyz() * bradfordAdaptation(d65WhiteXyz(), chromaticityToXyz(space.white()));
}

double srgbEncode(double linear) {
  if (linear <= 0.0031308) return 12.92 * linear;
  return 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double srgbDecode(double encoded) {
  if (encoded <= 0.04045) return encoded / 12.92;
  return std::pow((encoded + 0.055) / 1.055, 2.4);
}

}  // namespace camsim
