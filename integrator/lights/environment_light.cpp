#include "integrator/lights/environment_light.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <tbb/parallel_for.h>

#include "integrator/geometry/math.h"
#include "integrator/lights/rgb_emission_table.h"
#include "sensor/base/check.h"
#include "sensor/spectra/cie.h"
#include "sensor/spectra/color_space.h"

namespace camsim {
namespace {

constexpr int kBinNm = 3;  // wavelength bins for the per-texel normalisation integrals

glm::dvec3 luminanceWeights() {
  const glm::dmat3& m = RgbColorSpace::linearRec709().xyzFromRgb();
  return {m[0][1], m[1][1], m[2][1]};  // the Y row
}

struct TexelRgb {
  glm::dvec3 rgb{0.0};
  double y = 0.0;  // Rec.709 luminance (relative, Y of (1,1,1) = 1)
};

std::vector<TexelRgb> readTexels(const Image& image) {
  const int r = image.channelIndex("R"), g = image.channelIndex("G"), b = image.channelIndex("B");
  CAMSIM_CHECK(r >= 0 && g >= 0 && b >= 0 && image.width > 0 && image.height > 0);
  const glm::dvec3 yw = luminanceWeights();
  std::vector<TexelRgb> out(static_cast<size_t>(image.width) * static_cast<size_t>(image.height));
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      TexelRgb& t =
          out[static_cast<size_t>(y) * static_cast<size_t>(image.width) + static_cast<size_t>(x)];
      t.rgb = glm::max(glm::dvec3(image.at(x, y, r), image.at(x, y, g), image.at(x, y, b)),
                       glm::dvec3(0.0));
      CAMSIM_CHECK(std::isfinite(t.rgb.x) && std::isfinite(t.rgb.y) && std::isfinite(t.rgb.z));
      t.y = glm::dot(yw, t.rgb);
    }
  return out;
}

// Wavelength bins of kBinNm samples of the 1 nm grid: per bin Σ D65 ȳ Δλ (luminance) and
// Σ D65 · scale Δλ (radiant power), and t at the luminance weights' centroid, so that the
// bin sum Σ s(t_bin) · weight matches the 1 nm sum to second order in the bin width
// (measured: within 1e-4 of the luminance for most colours, 4e-4 for the blue primary).
struct Bins {
  std::vector<float> t, luminance, radiant;
};

Bins makeBins(const Spectrum& luminanceWeight, const Spectrum& radiantWeight) {
  Bins bins;
  for (int start = 0; start < kSpectrumSamples; start += kBinNm) {
    const int end = std::min(start + kBinNm, kSpectrumSamples);
    double y = 0.0, e = 0.0, moment = 0.0;
    for (int i = start; i < end; ++i) {
      y += static_cast<double>(luminanceWeight.sample(i));
      e += static_cast<double>(radiantWeight.sample(i));
      moment += static_cast<double>(luminanceWeight.sample(i)) * i;
    }
    const double centre = y > 0.0 ? moment / y : 0.5 * (start + end - 1);
    bins.t.push_back(static_cast<float>(centre / (kLambdaMaxNm - kLambdaMinNm)));
    bins.luminance.push_back(static_cast<float>(y));
    bins.radiant.push_back(static_cast<float>(e));
  }
  return bins;
}

// Σ s(λ) · weight over the bins, for the luminance and the radiant power of a shape.
void integrate(const Bins& bins, const SigmoidCoefficients& c, double& luminance, double& radiant) {
  float y = 0.0f, e = 0.0f;
  for (size_t i = 0; i < bins.t.size(); ++i) {
    const float s = c.at(bins.t[i]);
    y += s * bins.luminance[i];
    e += s * bins.radiant[i];
  }
  luminance = static_cast<double>(y);
  radiant = static_cast<double>(e);
}

// Solid angle of the texels of row j (each) in a map of width × height.
double rowSolidAngle(int j, int width, int height) {
  const double t0 = M_PI * j / height, t1 = M_PI * (j + 1) / height;
  return 2.0 * M_PI / width * (std::cos(t0) - std::cos(t1));
}

}  // namespace

glm::vec3 EnvironmentLight::directionOf(glm::vec2 uv) {
  const float theta = kPi * uv.y, phi = 2.0f * kPi * uv.x;
  const float s = std::sin(theta);
  return {s * std::cos(phi), -s * std::sin(phi), std::cos(theta)};
}

glm::vec2 EnvironmentLight::uvOf(const glm::vec3& d) {
  const float theta = std::atan2(std::sqrt(d.x * d.x + d.y * d.y), d.z);
  float phi = std::atan2(-d.y, d.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  return {phi / (2.0f * kPi), theta / kPi};
}

double EnvironmentLight::zenithIlluminance(const Image& rgb) {
  const std::vector<TexelRgb> texels = readTexels(rgb);
  double sum = 0.0;
  for (int j = 0; j < rgb.height; ++j) {
    const double t0 = M_PI * j / rgb.height, t1 = std::min(M_PI * (j + 1) / rgb.height, 0.5 * M_PI);
    if (t0 >= 0.5 * M_PI) break;
    // ∫ cos θ sin θ dθ dφ over the texel = Δφ (sin²θ₁ − sin²θ₀)/2
    const double w =
        2.0 * M_PI / rgb.width * 0.5 * (std::pow(std::sin(t1), 2.0) - std::pow(std::sin(t0), 2.0));
    for (int i = 0; i < rgb.width; ++i) sum += w * texels[static_cast<size_t>(j * rgb.width + i)].y;
  }
  return kMaxLuminousEfficacy * sum;
}

EnvironmentLight::EnvironmentLight(const Image& rgb, const Spectrum& scale,
                                   const glm::mat3& worldFromLight)
    : width_(rgb.width),
      height_(rgb.height),
      illuminant_(RgbColorSpace::linearRec709().illuminant() * scale),
      worldFromLight_(worldFromLight),
      lightFromWorld_(glm::transpose(worldFromLight)) {
  const std::vector<TexelRgb> colours = readTexels(rgb);
  const RgbEmissionTable& table = RgbEmissionTable::get();
  // Per texel: the tabulated shape, the luminance normalisation k, the sampling weight
  // Y · sin θ and (per row) the radiant integral for power().
  const Bins bins =
      makeBins(RgbColorSpace::linearRec709().illuminant() * Cie1931::get().y, illuminant_);
  texels_.resize(colours.size());
  std::vector<double> weights(colours.size(), 0.0), rowIntegrals(static_cast<size_t>(height_), 0.0);
  tbb::parallel_for(0, height_, [&](int j) {
    const double sinCentre = std::sin(M_PI * (j + 0.5) / height_);
    const double solidAngle = rowSolidAngle(j, width_, height_);
    for (int i = 0; i < width_; ++i) {
      const size_t t =
          static_cast<size_t>(j) * static_cast<size_t>(width_) + static_cast<size_t>(i);
      if (!(colours[t].y > 0.0)) continue;
      const SigmoidCoefficients c = table.lookup(colours[t].rgb);
      Texel& tx = texels_[t];
      tx.shape = c;
      double shapeLuminance = 0.0, shapeRadiant = 0.0;
      integrate(bins, c, shapeLuminance, shapeRadiant);
      tx.k = static_cast<float>(colours[t].y / shapeLuminance);
      weights[t] = colours[t].y * sinCentre;
      rowIntegrals[static_cast<size_t>(j)] += solidAngle * static_cast<double>(tx.k) * shapeRadiant;
    }
  });
  for (double r : rowIntegrals) radiantIntegral_ += r;
  distribution_ = PiecewiseConstant2D(weights, width_, height_);
}

void EnvironmentLight::setSceneBounds(const glm::vec3& /*centre*/, float radius) {
  sceneRadius_ = radius;
}

double EnvironmentLight::power() const {
  const double r = static_cast<double>(sceneRadius_);
  return M_PI * r * r * radiantIntegral_;
}

SampledSpectrum EnvironmentLight::texelRadiance(int column, int row,
                                                const SampledWavelengths& lambda) const {
  const Texel& t = texel(column, row);
  SampledSpectrum out(0.0f);
  if (t.k == 0.0f) return out;
  for (int i = 0; i < kWavelengthSamples; ++i)
    out[i] = t.k * t.shape(lambda[i]) * illuminant_(lambda[i]);
  return out;
}

std::optional<LightSample> EnvironmentLight::sample(const glm::vec3& /*ref*/, double /*time*/,
                                                    float /*u1*/, glm::vec2 u2,
                                                    const SampledWavelengths& lambda) const {
  if (distribution_.empty()) return std::nullopt;
  const Sample2D s = distribution_.sample(u2);
  const glm::vec3 d = directionOf(s.uv);
  const float sinTheta = std::sqrt(d.x * d.x + d.y * d.y);
  if (!(s.pdf > 0.0f) || !(sinTheta > 0.0f)) return std::nullopt;
  LightSample ls;
  ls.wi = glm::normalize(worldFromLight_ * d);
  ls.pdf = s.pdf / (2.0f * kPi * kPi * sinTheta);
  ls.L = texelRadiance(s.column, s.row, lambda);
  ls.infinite = true;
  if (ls.L.isZero() || !std::isfinite(ls.pdf)) return std::nullopt;
  return ls;
}

SampledSpectrum EnvironmentLight::Le(const glm::vec3& direction,
                                     const SampledWavelengths& lambda) const {
  const glm::vec2 uv = uvOf(lightFromWorld_ * direction);
  return texelRadiance(PiecewiseConstant2D::clampIndex(uv.x, width_),
                       PiecewiseConstant2D::clampIndex(uv.y, height_), lambda);
}

float EnvironmentLight::pdfDirection(const glm::vec3& direction) const {
  if (distribution_.empty()) return 0.0f;
  const glm::vec3 d = glm::normalize(lightFromWorld_ * direction);
  const float sinTheta = std::sqrt(d.x * d.x + d.y * d.y);
  if (!(sinTheta > 0.0f)) return 0.0f;
  return distribution_.pdf(uvOf(d)) / (2.0f * kPi * kPi * sinTheta);
}

}  // namespace camsim
