// Textures: values that vary over a surface with its texture coordinates (u, v) in [0, 1)²
// (meshes: per-vertex uv, or (0,0), (1,0), (1,1) per triangle without them; spheres:
// u = φ/2π about +y, v = 1 − θ/π from the top pole — see docs/scene-format.md).
// Small closed set: constant, image (EXR/PNG), checkerboard.
//   SpectrumTexture  reflectance-like spectra, dimensionless, evaluated at the path's λ
//   FloatTexture     scalars such as roughness
#pragma once

#include <memory>
#include <optional>

#include <glm/vec2.hpp>

#include "sensor/spectra/sampled_spectrum.h"
#include "sensor/spectra/spectral_bins.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

class SpectrumTexture {
 public:
  virtual ~SpectrumTexture() = default;
  virtual SampledSpectrum evaluate(glm::vec2 uv, const SampledWavelengths& lambda) const = 0;
  // Largest value anywhere (0 means the texture is black everywhere).
  virtual double maxValue() const = 0;
  // A constant texture's bins (spectral_bins.h: its averages over them); null: it varies.
  // A plain member, not a virtual call: the path loop asks at every Lambertian bounce.
  const SpectralBins* constantBins() const { return constantBins_ ? &*constantBins_ : nullptr; }

 protected:
  std::optional<SpectralBins> constantBins_;  // set by a constant texture's constructor
};

class FloatTexture {
 public:
  virtual ~FloatTexture() = default;
  virtual float evaluate(glm::vec2 uv) const = 0;
};

class ConstantSpectrumTexture final : public SpectrumTexture {
 public:
  explicit ConstantSpectrumTexture(Spectrum value) : value_(std::move(value)) {
    constantBins_ = binAverages(value_);
  }
  SampledSpectrum evaluate(glm::vec2, const SampledWavelengths& lambda) const override {
    return sampleSpectrum(value_, lambda);
  }
  double maxValue() const override { return value_.maxValue(); }

 private:
  Spectrum value_;
};

class ConstantFloatTexture final : public FloatTexture {
 public:
  explicit ConstantFloatTexture(float value) : value_(value) {}
  float evaluate(glm::vec2) const override { return value_; }

 private:
  float value_;
};

}  // namespace camsim
