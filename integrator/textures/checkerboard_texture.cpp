// Checkerboard textures (see checkerboard_texture.h).
#include "integrator/textures/checkerboard_texture.h"

#include <algorithm>
#include <cmath>

#include "sensor/base/check.h"

namespace camsim {

bool checkerboardIsA(glm::vec2 uv, float checks, glm::vec2 uvScale, glm::vec2 uvOffset) {
  const glm::vec2 p = (uv * uvScale + uvOffset) * checks;
  // In double: ⌊·⌋ of any float is exact there, and the sum's parity needs no integer
  // conversion (no overflow for huge or non-finite coordinates: NaN gives b).
  const double i = std::floor(static_cast<double>(p.x)), j = std::floor(static_cast<double>(p.y));
  return std::fmod(i + j, 2.0) == 0.0;
}

CheckerboardSpectrumTexture::CheckerboardSpectrumTexture(Spectrum a, Spectrum b, float checks,
                                                         glm::vec2 uvScale, glm::vec2 uvOffset)
    : a_(std::move(a)), b_(std::move(b)), checks_(checks), scale_(uvScale), offset_(uvOffset) {
  CAMSIM_CHECK(checks_ > 0.0f && std::isfinite(checks_));
}

SampledSpectrum CheckerboardSpectrumTexture::evaluate(glm::vec2 uv,
                                                      const SampledWavelengths& lambda) const {
  return sampleSpectrum(checkerboardIsA(uv, checks_, scale_, offset_) ? a_ : b_, lambda);
}

double CheckerboardSpectrumTexture::maxValue() const {
  return std::max(a_.maxValue(), b_.maxValue());
}

CheckerboardFloatTexture::CheckerboardFloatTexture(float a, float b, float checks,
                                                   glm::vec2 uvScale, glm::vec2 uvOffset)
    : a_(a), b_(b), checks_(checks), scale_(uvScale), offset_(uvOffset) {
  CAMSIM_CHECK(checks_ > 0.0f && std::isfinite(checks_));
}

float CheckerboardFloatTexture::evaluate(glm::vec2 uv) const {
  return checkerboardIsA(uv, checks_, scale_, offset_) ? a_ : b_;
}

}  // namespace camsim
