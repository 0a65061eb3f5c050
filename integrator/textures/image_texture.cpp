// Image textures (see image_texture.h): decoding PNG/EXR files to linear texel values,
// the per-texel uplift at load, and bilinear lookups with repeat addressing.
#include "integrator/textures/image_texture.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cctype>
#include <cmath>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <glm/matrix.hpp>

#include "integrator/textures/reflectance_uplift.h"
#include "sensor/base/file_status.h"
#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "sensor/io/png_io.h"
#include "sensor/spectra/color_space.h"

namespace camsim {
namespace {

constexpr std::uint64_t kMaxTexels = std::uint64_t{1} << 28;

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& message) {
  throw InputError({file.string(), 0, 0}, "", message);
}

std::string lowerExtension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

float decode(double e, TextureEncoding encoding) {
  return static_cast<float>(encoding == TextureEncoding::kSrgb ? srgbDecode(e) : e);
}

TextureImage fromPng(const std::filesystem::path& file, TextureEncoding encoding) {
  const PngImage png = readPng(file);
  std::vector<float> lut(size_t{1} << png.bitDepth);  // sample → value
  const double maxCode = static_cast<double>(lut.size() - 1);
  for (size_t q = 0; q < lut.size(); ++q)
    lut[q] = decode(static_cast<double>(q) / maxCode, encoding);
  TextureImage image;
  image.width = png.width;
  image.height = png.height;
  image.channels = png.channels >= 3 ? 3 : 1;
  const size_t texels = static_cast<size_t>(png.width) * static_cast<size_t>(png.height);
  image.values.assign(texels * static_cast<size_t>(image.channels), 0.0f);
  for (size_t t = 0; t < texels; ++t)
    for (size_t c = 0; c < static_cast<size_t>(image.channels); ++c)
      image.values[t * static_cast<size_t>(image.channels) + c] =
          lut[png.samples[t * static_cast<size_t>(png.channels) + c]];
  if (png.channels == 2 || png.channels == 4) {  // alpha: the last sample, linear
    const size_t a = static_cast<size_t>(png.channels) - 1;
    image.alpha.resize(texels);
    for (size_t t = 0; t < texels; ++t)
      image.alpha[t] = static_cast<float>(
          static_cast<double>(png.samples[t * static_cast<size_t>(png.channels) + a]) / maxCode);
  }
  return image;
}

// Linear RGB in the file's primaries → linear Rec.709 (identity for Rec.709 files).
glm::dmat3 toRec709(const std::optional<ExrChromaticities>& c) {
  const RgbColorSpace& rec709 = RgbColorSpace::linearRec709();
  auto near = [](Chromaticity a, Chromaticity b) {
    return std::abs(a.x - b.x) + std::abs(a.y - b.y) < 1e-4;
  };
  if (!c || (near(c->red, rec709.red()) && near(c->green, rec709.green()) &&
             near(c->blue, rec709.blue()) && near(c->white, rec709.white())))
    return glm::dmat3(1.0);
  const RgbColorSpace fileSpace("exr", c->red, c->green, c->blue, c->white,
                                Spectrum::constant(1.0));
  return xyzD65ToWorkingSpace(rec709) * glm::inverse(xyzD65ToWorkingSpace(fileSpace));
}

TextureImage fromExr(const std::filesystem::path& file, TextureEncoding encoding) {
  const ExrFile exr = readExr(file);
  const Image& in = exr.image;
  std::vector<int> source = {in.channelIndex("R"), in.channelIndex("G"), in.channelIndex("B")};
  if (source[0] < 0 || source[1] < 0 || source[2] < 0) {
    const int grey =
        in.channelIndex("Y") >= 0 ? in.channelIndex("Y") : (in.channelCount() == 1 ? 0 : -1);
    if (grey < 0) {
      std::string names;
      for (const std::string& n : in.channels) names += (names.empty() ? "" : ", ") + n;
      fail(file,
           "unsupported EXR channels (" + names + "): need R, G, B, or Y, or a single channel");
    }
    source = {grey};
  }
  // A NaN or infinite texel has no reflectance, roughness or normal to give (NaN read as 0,
  // +inf as 1 or an infinite roughness, silently): refused, named by texel and channel.
  std::vector<int> used = source;
  if (const int a = in.channelIndex("A"); a >= 0) used.push_back(a);
  const size_t texelCount = static_cast<size_t>(in.width) * static_cast<size_t>(in.height);
  for (size_t t = 0; t < texelCount; ++t)
    for (const int c : used)
      if (const float v = in.pixels[t * in.channels.size() + static_cast<size_t>(c)];
          !std::isfinite(v))
        fail(file, "texel (" + std::to_string(t % static_cast<size_t>(in.width)) + ", " +
                       std::to_string(t / static_cast<size_t>(in.width)) + ") of channel " +
                       in.channels[static_cast<size_t>(c)] + " is " +
                       (std::isnan(v) ? "NaN" : "infinite") +
                       ": a texture's values must be finite");
  TextureImage image;
  image.width = in.width;
  image.height = in.height;
  image.channels = static_cast<int>(source.size());
  const glm::dmat3 m = image.channels == 3 && encoding != TextureEncoding::kRaw
                           ? toRec709(exr.chromaticities)
                           : glm::dmat3(1.0);
  const bool convert = m != glm::dmat3(1.0);
  const size_t texels = static_cast<size_t>(in.width) * static_cast<size_t>(in.height);
  image.values.assign(texels * source.size(), 0.0f);
  for (size_t t = 0; t < texels; ++t) {
    glm::dvec3 v(0.0);
    for (size_t c = 0; c < source.size(); ++c)
      v[static_cast<int>(c)] =
          static_cast<double>(in.pixels[t * in.channels.size() + static_cast<size_t>(source[c])]);
    if (convert) v = m * v;
    for (size_t c = 0; c < source.size(); ++c)
      image.values[t * source.size() + c] = decode(v[static_cast<int>(c)], encoding);
  }
  if (const int a = in.channelIndex("A"); a >= 0) {
    image.alpha.resize(texels);
    for (size_t t = 0; t < texels; ++t)
      image.alpha[t] = in.pixels[t * in.channels.size() + static_cast<size_t>(a)];
  }
  return image;
}

// Largest value of S(c₀t² + c₁t + c₂) over t ∈ [0, 1]: S is increasing, so the largest
// value of the quadratic (at an end or at its vertex).
double maxOverWavelength(const SigmoidPolynomial& p) {
  auto x = [&](double t) { return (p.c0 * t + p.c1) * t + p.c2; };
  double best = std::max(x(0.0), x(1.0));
  if (p.c0 < 0.0) {
    const double vertex = -p.c1 / (2.0 * p.c0);
    if (vertex > 0.0 && vertex < 1.0) best = std::max(best, x(vertex));
  }
  return 0.5 + best / (2.0 * std::sqrt(1.0 + best * best));
}

struct TexelKey {
  std::array<std::uint32_t, 3> rgb;
  std::uint32_t texel;
  bool operator<(const TexelKey& o) const { return rgb != o.rgb ? rgb < o.rgb : texel < o.texel; }
};

}  // namespace

TextureEncoding defaultTextureEncoding(const std::filesystem::path& file) {
  const std::string ext = lowerExtension(file);
  if (ext != ".png" && ext != ".exr")
    fail(file, "unsupported texture file type '" + file.extension().string() +
                   "' (expected .png or .exr)");
  return ext == ".png" ? TextureEncoding::kSrgb : TextureEncoding::kLinear;
}

namespace {
std::atomic<std::uint64_t> texturesRead{0};  // textureFilesRead()
}  // namespace

std::uint64_t textureFilesRead() {
  return texturesRead.load(std::memory_order_relaxed);
}

TextureImage loadTextureImage(const std::filesystem::path& file, TextureEncoding encoding) {
  texturesRead.fetch_add(1, std::memory_order_relaxed);
  if (!isRegularFile(file)) fail(file, "texture file does not exist or is not a regular file");
  const std::string ext = lowerExtension(file);
  TextureImage image;
  if (ext == ".png")
    image = fromPng(file, encoding);
  else if (ext == ".exr")
    image = fromExr(file, encoding);
  else
    fail(file, "unsupported texture file type '" + file.extension().string() +
                   "' (expected .png or .exr)");
  if (image.width <= 0 || image.height <= 0) fail(file, "the texture image is empty");
  if (static_cast<std::uint64_t>(image.width) * static_cast<std::uint64_t>(image.height) >
      kMaxTexels)
    fail(file, "the texture image has more than 2^28 texels");
  return image;
}

TexelFootprint bilinearFootprint(glm::vec2 uv, int width, int height) {
  TexelFootprint f;
  const double x = std::isfinite(uv.x) ? static_cast<double>(uv.x) * width - 0.5 : 0.0;
  const double y = std::isfinite(uv.y) ? (1.0 - static_cast<double>(uv.y)) * height - 0.5 : 0.0;
  const double fx = std::floor(x), fy = std::floor(y);
  auto wrap = [](double i, int n) {
    const double r = std::fmod(i, static_cast<double>(n));
    return static_cast<std::uint32_t>(r < 0.0 ? r + n : r) % static_cast<std::uint32_t>(n);
  };
  const std::uint32_t x0 = wrap(fx, width), x1 = (x0 + 1) % static_cast<std::uint32_t>(width);
  const std::uint32_t y0 = wrap(fy, height), y1 = (y0 + 1) % static_cast<std::uint32_t>(height);
  const float ax = static_cast<float>(x - fx), ay = static_cast<float>(y - fy);
  const std::uint32_t w = static_cast<std::uint32_t>(width);
  f.texel = {y0 * w + x0, y0 * w + x1, y1 * w + x0, y1 * w + x1};
  f.weight = {(1.0f - ax) * (1.0f - ay), ax * (1.0f - ay), (1.0f - ax) * ay, ax * ay};
  f.fraction = {ax, ay};
  return f;
}

UpliftedTexels upliftTexels(const TextureImage& image) {
  CAMSIM_CHECK(image.width > 0 && image.height > 0 && (image.channels == 1 || image.channels == 3));
  UpliftedTexels out;
  out.width = image.width;
  out.height = image.height;
  const size_t texels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  CAMSIM_CHECK(image.values.size() == texels * static_cast<size_t>(image.channels));
  out.coefficients.assign(texels, SigmoidCoefficients{});
  // Each distinct colour is fitted once: texels sorted by their clamped RGB (bit patterns of
  // non-negative floats order like the values), the distinct colours fitted in parallel.
  const size_t n = static_cast<size_t>(image.channels);
  std::vector<TexelKey> keys(texels);
  for (size_t t = 0; t < texels; ++t) {
    for (size_t c = 0; c < 3; ++c) {
      const float v = image.values[t * n + (n == 3 ? c : 0)];
      keys[t].rgb[c] =
          std::bit_cast<std::uint32_t>(v > 0.0f ? std::min(v, 1.0f) : 0.0f);  // NaN → 0
    }
    keys[t].texel = static_cast<std::uint32_t>(t);
  }
  tbb::parallel_sort(keys.begin(), keys.end());
  std::vector<size_t> firsts;  // index in keys of each distinct colour's first texel
  for (size_t k = 0; k < texels; ++k)
    if (k == 0 || keys[k].rgb != keys[k - 1].rgb) firsts.push_back(k);
  firsts.push_back(texels);
  std::vector<double> maxima(firsts.size() - 1, 0.0);
  const ReflectanceUplift& uplift = ReflectanceUplift::linearRec709();
  tbb::parallel_for(size_t{0}, firsts.size() - 1, [&](size_t d) {
    const std::array<std::uint32_t, 3>& bits = keys[firsts[d]].rgb;
    const SigmoidPolynomial p =
        uplift.fit(glm::dvec3(std::bit_cast<float>(bits[0]), std::bit_cast<float>(bits[1]),
                              std::bit_cast<float>(bits[2])));
    maxima[d] = maxOverWavelength(p);
    for (size_t k = firsts[d]; k < firsts[d + 1]; ++k)
      out.coefficients[keys[k].texel] = SigmoidCoefficients::from(p);
  });
  out.maxValue = *std::max_element(maxima.begin(), maxima.end());
  return out;
}

ImageSpectrumTexture::ImageSpectrumTexture(const TextureImage& image, glm::vec2 uvScale,
                                           glm::vec2 uvOffset, float uvRotation)
    : ImageSpectrumTexture(std::make_shared<const UpliftedTexels>(upliftTexels(image)), uvScale,
                           uvOffset, uvRotation) {}

ImageSpectrumTexture::ImageSpectrumTexture(std::shared_ptr<const UpliftedTexels> texels,
                                           glm::vec2 uvScale, glm::vec2 uvOffset, float uvRotation)
    : texels_(std::move(texels)), uvTransform_(uvScale, uvOffset, uvRotation) {
  CAMSIM_CHECK(texels_ && texels_->width > 0 && texels_->height > 0);
}

SampledSpectrum ImageSpectrumTexture::evaluate(glm::vec2 uv,
                                               const SampledWavelengths& lambda) const {
  const TexelFootprint f = bilinearFootprint(uvTransform_(uv), texels_->width, texels_->height);
  SampledSpectrum out;
  for (int k = 0; k < 4; ++k) {
    if (f.weight[static_cast<size_t>(k)] == 0.0f) continue;
    const SigmoidCoefficients& c = texels_->coefficients[f.texel[static_cast<size_t>(k)]];
    for (int i = 0; i < kWavelengthSamples; ++i)
      out[i] += f.weight[static_cast<size_t>(k)] * c(lambda[i]);
  }
  return out;
}

float ImageSpectrumTexture::texelValue(int x, int y, float lambdaNm) const {
  CAMSIM_CHECK(x >= 0 && x < texels_->width && y >= 0 && y < texels_->height);
  return texels_->coefficients[static_cast<size_t>(y) * static_cast<size_t>(texels_->width) +
                               static_cast<size_t>(x)](lambdaNm);
}

ImageFloatTexture::ImageFloatTexture(const TextureImage& image, glm::vec2 uvScale,
                                     glm::vec2 uvOffset, int channel, float uvRotation)
    : width_(image.width), height_(image.height), uvTransform_(uvScale, uvOffset, uvRotation) {
  CAMSIM_CHECK(width_ > 0 && height_ > 0 && (image.channels == 1 || image.channels == 3));
  CAMSIM_CHECK(channel >= -1 && channel <= 3);
  const size_t n = static_cast<size_t>(image.channels);
  CAMSIM_CHECK(image.values.size() % n == 0);
  values_.assign(image.values.size() / n, 0.0f);
  CAMSIM_CHECK(image.alpha.empty() || image.alpha.size() == values_.size());
  for (size_t t = 0; t < values_.size(); ++t) {
    float v = 0.0f;
    if (channel == 3) {
      v = image.alpha.empty() ? 1.0f : image.alpha[t];
    } else if (channel >= 0) {  // R, G or B; a grey image's grey for each
      v = image.values[t * n + (n == 3 ? static_cast<size_t>(channel) : 0)];
    } else {
      float sum = 0.0f;
      for (size_t c = 0; c < n; ++c) sum += image.values[t * n + c];
      v = sum / static_cast<float>(n);
    }
    values_[t] = v > 0.0f ? v : 0.0f;  // negative and NaN → 0
  }
}

float ImageFloatTexture::evaluate(glm::vec2 uv) const {
  const TexelFootprint f = bilinearFootprint(uvTransform_(uv), width_, height_);
  float out = 0.0f;
  for (size_t k = 0; k < 4; ++k) out += f.weight[k] * values_[f.texel[k]];
  return out;
}

}  // namespace camsim
