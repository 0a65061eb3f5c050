// Checkerboard textures: a procedural pattern of two values in squares of the texture
// coordinates (a test pattern and a calibration target).
//
// | parameter | unit | default | meaning |
// |-----------|------|---------|---------|
// | a, b      | —    | 0.8, 0.2 | the two values (spectra: reflectances in [0, 1]) |
// | checks    | —    | 8       | squares per unit of u and of v (> 0) |
// | scale     | —    | (1, 1)  | uv' = uv · scale + offset |
// | offset    | —    | (0, 0)  | |
//
//   i = ⌊u'·checks⌋,  j = ⌊v'·checks⌋,   value = a if i + j is even, else b
// so the square [0, 1/checks)² (uv' near the origin) holds a. Point-sampled: the edges
// are sharp, anti-aliased only by the pixel's samples.
#pragma once

#include <glm/vec2.hpp>

#include "integrator/textures/texture.h"

namespace camsim {

// True where the pattern shows `a` (see above).
bool checkerboardIsA(glm::vec2 uv, float checks, glm::vec2 uvScale, glm::vec2 uvOffset);

class CheckerboardSpectrumTexture final : public SpectrumTexture {
 public:
  CheckerboardSpectrumTexture(Spectrum a, Spectrum b, float checks,
                              glm::vec2 uvScale = glm::vec2(1.0f),
                              glm::vec2 uvOffset = glm::vec2(0.0f));
  SampledSpectrum evaluate(glm::vec2 uv, const SampledWavelengths& lambda) const override;
  double maxValue() const override;

 private:
  Spectrum a_, b_;
  float checks_;
  glm::vec2 scale_, offset_;
};

class CheckerboardFloatTexture final : public FloatTexture {
 public:
  CheckerboardFloatTexture(float a, float b, float checks, glm::vec2 uvScale = glm::vec2(1.0f),
                           glm::vec2 uvOffset = glm::vec2(0.0f));
  float evaluate(glm::vec2 uv) const override;

 private:
  float a_, b_;
  float checks_;
  glm::vec2 scale_, offset_;
};

}  // namespace camsim
