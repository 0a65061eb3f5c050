#include "integrator/environment_light.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <tbb/parallel_for.h>

#include "integrator/math.h"
#include "sensor/check.h"
#include "sensor/cie.h"
#include "sensor/color_space.h"
#include "sensor/rgb_uplift.h"

namespace camsim {
namespace {

// Fit table: a colour c with maximum m is uplifted through the reflectance c/(2m)
// (rgbToEmissionShape), whose largest component is ½; the other two, in channel order,
// lie in [0, ½] and index a kNodes × kNodes grid for each of the three largest channels.
constexpr int kNodes = 17;
constexpr int kBinNm = 5;  // wavelength bins for the per-texel normalisation integrals

float sigmoid(float x) {
  return 0.5f + x / (2.0f * std::sqrt(1.0f + x * x));
}

float sigmoidPolynomial(float c0, float c1, float c2, float lambdaNm) {
  const float t = (lambdaNm - static_cast<float>(kLambdaMinNm)) /
                  static_cast<float>(kLambdaMaxNm - kLambdaMinNm);
  return sigmoid((c0 * t + c1) * t + c2);
}

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

// Where a colour falls in the fit table: the largest channel and the two others' grid
// cell (ia, ib) with fractions (fa, fb).
struct TableCell {
  int channel = 0, ia = 0, ib = 0;
  double fa = 0.0, fb = 0.0;
};

TableCell locate(const glm::dvec3& rgb) {
  TableCell c;
  const double m = std::max({rgb.x, rgb.y, rgb.z});
  c.channel = rgb.x == m ? 0 : (rgb.y == m ? 1 : 2);
  const int others[3][2] = {{1, 2}, {0, 2}, {0, 1}};
  auto place = [&](double v, int& i, double& f) {
    const double x = std::clamp(v / (2.0 * m) * 2.0 * (kNodes - 1), 0.0, double{kNodes - 1});
    i = std::min(static_cast<int>(x), kNodes - 2);
    f = x - i;
  };
  place(rgb[others[c.channel][0]], c.ia, c.fa);
  place(rgb[others[c.channel][1]], c.ib, c.fb);
  return c;
}

size_t nodeIndex(int channel, int ia, int ib) {
  return (static_cast<size_t>(channel) * kNodes + static_cast<size_t>(ia)) * kNodes +
         static_cast<size_t>(ib);
}

// The reflectance c/(2m) at a node, fitted (grey exactly: c = 0 is the constant ½).
SigmoidPolynomial fitNode(size_t index) {
  const int ib = static_cast<int>(index % kNodes), ia = static_cast<int>(index / kNodes % kNodes);
  const int channel = static_cast<int>(index / (kNodes * kNodes));
  if (ia == kNodes - 1 && ib == kNodes - 1) return SigmoidPolynomial{};
  const int others[3][2] = {{1, 2}, {0, 2}, {0, 1}};
  glm::dvec3 rgb(0.0);
  rgb[channel] = 0.5;
  rgb[others[channel][0]] = 0.5 * ia / (kNodes - 1);
  rgb[others[channel][1]] = 0.5 * ib / (kNodes - 1);
  return fitSigmoidPolynomial(rgb, RgbColorSpace::linearRec709());
}

// Wavelength bins of kBinNm samples of the 1 nm grid: centre and Σ weight·Δλ per bin.
struct Bins {
  std::vector<float> centre;
  std::vector<double> weight;
};

Bins makeBins(const Spectrum& w) {
  Bins bins;
  for (int start = 0; start < kSpectrumSamples; start += kBinNm) {
    const int end = std::min(start + kBinNm, kSpectrumSamples);
    double sum = 0.0;
    for (int i = start; i < end; ++i) sum += static_cast<double>(w.sample(i));
    bins.centre.push_back(static_cast<float>(kLambdaMinNm) +
                          0.5f * static_cast<float>(start + end - 1));
    bins.weight.push_back(sum);
  }
  return bins;
}

double integrate(const Bins& bins, float c0, float c1, float c2) {
  double sum = 0.0;
  for (size_t i = 0; i < bins.centre.size(); ++i)
    sum += static_cast<double>(sigmoidPolynomial(c0, c1, c2, bins.centre[i])) * bins.weight[i];
  return sum;
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
  // 1. The table nodes the texels need, fitted once each.
  std::vector<char> needed(3 * kNodes * kNodes, 0);
  std::vector<TableCell> cells(colours.size());
  for (size_t t = 0; t < colours.size(); ++t) {
    if (!(colours[t].y > 0.0)) continue;
    cells[t] = locate(colours[t].rgb);
    for (int da = 0; da < 2; ++da)
      for (int db = 0; db < 2; ++db)
        needed[nodeIndex(cells[t].channel, cells[t].ia + da, cells[t].ib + db)] = 1;
  }
  std::vector<size_t> toFit;
  for (size_t n = 0; n < needed.size(); ++n)
    if (needed[n]) toFit.push_back(n);
  std::vector<SigmoidPolynomial> nodes(needed.size());
  tbb::parallel_for(size_t{0}, toFit.size(),
                    [&](size_t k) { nodes[toFit[k]] = fitNode(toFit[k]); });

  // 2. Per texel: interpolated coefficients, the luminance normalisation k, the sampling
  // weight Y · sin θ and the radiant integral for power().
  const Bins yBins = makeBins(RgbColorSpace::linearRec709().illuminant() * Cie1931::get().y);
  const Bins eBins = makeBins(illuminant_);
  texels_.resize(colours.size());
  std::vector<double> weights(colours.size(), 0.0);
  for (int j = 0; j < height_; ++j) {
    const double sinCentre = std::sin(M_PI * (j + 0.5) / height_);
    const double solidAngle = rowSolidAngle(j, width_, height_);
    for (int i = 0; i < width_; ++i) {
      const size_t t =
          static_cast<size_t>(j) * static_cast<size_t>(width_) + static_cast<size_t>(i);
      if (!(colours[t].y > 0.0)) continue;
      const TableCell& c = cells[t];
      std::array<double, 3> coeff{};
      for (int da = 0; da < 2; ++da)
        for (int db = 0; db < 2; ++db) {
          const double w = (da ? c.fa : 1.0 - c.fa) * (db ? c.fb : 1.0 - c.fb);
          const SigmoidPolynomial& p = nodes[nodeIndex(c.channel, c.ia + da, c.ib + db)];
          coeff[0] += w * p.c0;
          coeff[1] += w * p.c1;
          coeff[2] += w * p.c2;
        }
      Texel& tx = texels_[t];
      tx.c0 = static_cast<float>(coeff[0]);
      tx.c1 = static_cast<float>(coeff[1]);
      tx.c2 = static_cast<float>(coeff[2]);
      const double shapeY = integrate(yBins, tx.c0, tx.c1, tx.c2);
      tx.k = static_cast<float>(colours[t].y / shapeY);
      weights[t] = colours[t].y * sinCentre;
      radiantIntegral_ +=
          solidAngle * static_cast<double>(tx.k) * integrate(eBins, tx.c0, tx.c1, tx.c2);
    }
  }
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
    out[i] = t.k * sigmoidPolynomial(t.c0, t.c1, t.c2, lambda[i]) * illuminant_(lambda[i]);
  return out;
}

std::optional<LightSample> EnvironmentLight::sample(const glm::vec3& /*ref*/, float /*time*/,
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
