#include "sensor/spectra/cie.h"

#include "sensor/spectra/spectral_data.h"

namespace camsim {

const Cie1931& Cie1931::get() {
  static const Cie1931 cie = [] {
    const SpectralTable t = parseSpectralCsv(embeddedSpectralFile("cie1931_2deg_xyz.csv"),
                                             "luts/spectra/cie1931_2deg_xyz.csv");
    return Cie1931{t.spectrum(t.columnIndex("x_bar"), Extrapolation::kZero),
                   t.spectrum(t.columnIndex("y_bar"), Extrapolation::kZero),
                   t.spectrum(t.columnIndex("z_bar"), Extrapolation::kZero)};
  }();
  return cie;
}

glm::dvec3 spectrumToXyz(const Spectrum& s) {
  const Cie1931& cie = Cie1931::get();
  return {innerProduct(s, cie.x), innerProduct(s, cie.y), innerProduct(s, cie.z)};
}

double luminance(const Spectrum& spectralRadiance) {
  return kMaxLuminousEfficacy * innerProduct(spectralRadiance, Cie1931::get().y);
}

glm::dvec3 reflectanceToXyz(const Spectrum& reflectance, const Spectrum& illuminant) {
  const double norm = innerProduct(illuminant, Cie1931::get().y);
  return spectrumToXyz(reflectance * illuminant) / norm;
}

Chromaticity xyzToChromaticity(const glm::dvec3& xyz) {
  const double sum = xyz.x + xyz.y + xyz.z;
  if (sum == 0.0) return {};
  return {xyz.x / sum, xyz.y / sum};
}

glm::dvec3 chromaticityToXyz(Chromaticity c, double Y) {
  if (c.y == 0.0) return {0.0, 0.0, 0.0};
  return {c.x * Y / c.y, Y, (1.0 - c.x - c.y) * Y / c.y};
}

}  // namespace camsim
