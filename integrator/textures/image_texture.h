// Image textures: texel values from an EXR or PNG file, bilinearly filtered, repeating.
//
// | parameter | unit | default                                      | meaning                   |
// |-----------|------|----------------------------------------------|---------------------------|
// | file      | —    | required                                     | `.exr` or `.png`          |
// | encoding  | —    | reflectance: png `srgb`, exr `linear`; scalar: `raw` | how numbers become values |
// | scale     | —    | (1, 1)                                       | uv' = uv · scale + offset |
// | offset    | —    | (0, 0)                                       |                           |
// | rotation  | rad  | 0                                            | uv' = R(θ)(uv · scale) + offset (uv_transform.h; glTF KHR_texture_transform) |
//
// Decoding (PNG sample q of n bits, EXR float f):  e = q / (2ⁿ − 1)  or  e = f
//   srgb:   value = srgbDecode(e) (IEC 61966-2-1: e ≤ 0.04045 ? e/12.92 : ((e + 0.055)/1.055)^2.4)
//   linear: value = e, linear Rec.709 RGB (an EXR with other `chromaticities` is converted
//           to Rec.709: its RGB → XYZ, Bradford to D65, → Rec.709)
//   raw:    value = e, used as it is (roughness maps)
// Channels: EXR R, G, B (by name) or one grey channel (Y, or the only channel), and A if
//   present; PNG grey, grey+alpha, RGB, RGBA or palette. Anything else is an InputError.
//   Alpha is kept apart (TextureImage::alpha, never sRGB-decoded: PNG and EXR store it
//   linear); only a scalar texture's `channel` 3 reads it.
//
// Reflectance (ImageSpectrumTexture): RGB (grey: r = g = b) clamped to [0, 1]; every texel is
// uplifted once, at load, to a Jakob–Hanika sigmoid polynomial (integrator/textures/reflectance_uplift.h)
//   ρ_texel(λ) = S(c₀ t² + c₁ t + c₂),  t = (λ − 360 nm)/470 nm,   in (0, 1), smooth
// (UpliftedTexels; the Scene's materials share one per file and encoding: TextureCache in
// integrator/scene/factory.h).
// Scalar (ImageFloatTexture): channel −1 (default): the grey value, or the mean of R, G, B;
//   channel 0, 1, 2: R, G, B (a grey image: its grey for each); channel 3: alpha (1 for an
//   image without one), as a GPU samples a texture. Negative or NaN → 0.
//
// Addressing: texel (x, y) of a w × h image, row y = 0 at the TOP of the picture, has its
// centre at u = (x + ½)/w, v = 1 − (y + ½)/h: v = 0 is the image's bottom edge (the OBJ /
// OpenGL convention; a `rectangle` shows the image upright when edge_v points up).
//   X = u'·w − ½,  Y = (1 − v')·h − ½
//   value = Σ bilinear weights (1 − fx, fx) × (1 − fy, fy) over texels ⌊X⌋, ⌊X⌋ + 1 and
//           ⌊Y⌋, ⌊Y⌋ + 1, indices taken modulo w and h (repeat), fx = X − ⌊X⌋
// Spectra are filtered, not coefficients: the four texels' ρ(λ) are blended. No mip-mapping:
// a minified texture aliases unless the pixel's samples average it.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "integrator/textures/texture.h"
#include "integrator/textures/texture_encoding.h"
#include "integrator/textures/uv_transform.h"
#include "sensor/spectra/rgb_uplift.h"

namespace camsim {

// A decoded texture image: 1 (grey) or 3 (R, G, B) channels, rows top to bottom, and the
// alpha channel apart when the file has one.
struct TextureImage {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> values;  // width·height·channels, interleaved
  std::vector<float> alpha;   // width·height (linear, as stored), or empty: no alpha

  bool operator==(const TextureImage&) const = default;
};

// The default encoding of a colour texture of this file type (png: srgb, exr: linear).
// Throws InputError naming the file for another type.
TextureEncoding defaultTextureEncoding(const std::filesystem::path& file);
// Reads and decodes an image. Throws InputError naming the file (missing, unreadable,
// unsupported type or channels, empty).
TextureImage loadTextureImage(const std::filesystem::path& file, TextureEncoding encoding);
// Texture files loadTextureImage has read in this process so far (the scene loader's reads
// and any a Scene build makes): a statistic, as pbrt's counters are, for tests.
std::uint64_t textureFilesRead();

// The four texels a lookup blends (indices into width·height, row-major from the top)
// and their weights (sum 1).
struct TexelFootprint {
  std::array<std::uint32_t, 4> texel{};  // (x0, y0), (x1, y0), (x0, y1), (x1, y1)
  std::array<float, 4> weight{};
  glm::vec2 fraction{0.0f};  // (fx, fy): weight = products of (1 − fx, fx) and (1 − fy, fy)
};
TexelFootprint bilinearFootprint(glm::vec2 uv, int width, int height);

// A reflectance image uplifted to spectra: one sigmoid polynomial per texel (each distinct
// colour fitted once) and the largest reflectance over texels and wavelengths. Several
// textures of one image (other uv transforms, other materials) can share it.
struct UpliftedTexels {
  int width = 0;
  int height = 0;
  std::vector<SigmoidCoefficients> coefficients;  // width·height, as the image's texels
  double maxValue = 0.0;
};
UpliftedTexels upliftTexels(const TextureImage& image);

class ImageSpectrumTexture final : public SpectrumTexture {
 public:
  ImageSpectrumTexture(const TextureImage& image, glm::vec2 uvScale, glm::vec2 uvOffset,
                       float uvRotation = 0.0f);
  ImageSpectrumTexture(std::shared_ptr<const UpliftedTexels> texels, glm::vec2 uvScale,
                       glm::vec2 uvOffset, float uvRotation = 0.0f);
  SampledSpectrum evaluate(glm::vec2 uv, const SampledWavelengths& lambda) const override;
  double maxValue() const override { return texels_->maxValue; }
  // The texel's fitted reflectance at λ (x, y as in the image, row 0 at the top).
  float texelValue(int x, int y, float lambdaNm) const;
  const std::shared_ptr<const UpliftedTexels>& texels() const { return texels_; }

 private:
  std::shared_ptr<const UpliftedTexels> texels_;
  UvTransform uvTransform_;
};

class ImageFloatTexture final : public FloatTexture {
 public:
  // channel: −1 (the default reading), 0 … 3 (R, G, B, A), see above.
  ImageFloatTexture(const TextureImage& image, glm::vec2 uvScale, glm::vec2 uvOffset,
                    int channel = -1, float uvRotation = 0.0f);
  float evaluate(glm::vec2 uv) const override;

 private:
  int width_, height_;
  UvTransform uvTransform_;
  std::vector<float> values_;
};

}  // namespace camsim
