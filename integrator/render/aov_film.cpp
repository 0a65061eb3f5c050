#include "integrator/render/aov_film.h"

#include <glm/geometric.hpp>

#include "sensor/spectra/color_space.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {
namespace {

std::vector<std::string> channelsOf(Aov aov) {
  switch (aov) {
    case Aov::kDepth:
      return {"depth.Z"};
    case Aov::kDistance:
      return {"distance.Z"};
    case Aov::kPosition:
      return {"P.X", "P.Y", "P.Z"};
    case Aov::kNormal: {
      std::vector<std::string> c;
      for (const char* layer : {"N", "Ng", "N_cam", "Ng_cam"})
        for (const char* axis : {".X", ".Y", ".Z"}) c.push_back(std::string(layer) + axis);
      return c;
    }
    case Aov::kAlbedo:
      return {"albedo.R", "albedo.G", "albedo.B"};
    case Aov::kRoughness:
      return {"roughness.Y"};
  }
  return {};
}

// World axes → camera axes in the OpenCV convention (x right, y down, z forward).
glm::dvec3 toCameraCv(const glm::dmat4& worldFromCamera, const glm::dvec3& v) {
  return {glm::dot(v, glm::dvec3(worldFromCamera[0])), -glm::dot(v, glm::dvec3(worldFromCamera[1])),
          glm::dot(v, glm::dvec3(worldFromCamera[2]))};
}

}  // namespace

AovFilm::AovFilm(glm::ivec2 resolution, const std::vector<Aov>& aovs)
    : resolution_(resolution), aovs_(aovs) {
  const SpectralResponse xyz = SpectralResponse::cieXyz();
  const Spectrum d65 = cieIlluminant("D65");
  for (int c = 0; c < 3; ++c) whiteXyz_[static_cast<std::size_t>(c)] = xyz.channel(c).curve * d65;
  if (aovs_.empty()) return;
  channels_ = {"coverage.A"};
  for (Aov a : aovs_)
    for (std::string& c : channelsOf(a)) channels_.push_back(std::move(c));
  stride_ = channels_.size();  // slot 0: the hit count (coverage.A once divided by spp)
  for (std::size_t c = 0; c < channels_.size(); ++c)
    if (channels_[c] == "albedo.R") albedoChannel_ = c;
  if (albedoChannel_ > 0)
    albedoWhite_.assign(
        static_cast<std::size_t>(resolution.x) * static_cast<std::size_t>(resolution.y) * 3, 0.0);
  sums_.assign(
      static_cast<std::size_t>(resolution.x) * static_cast<std::size_t>(resolution.y) * stride_,
      0.0);
}

void AovFilm::addSample(glm::ivec2 pixel, const VisibleSurface& v,
                        const glm::dmat4& worldFromCamera, const glm::dvec3& renderOrigin,
                        const SampledWavelengths& lambda) {
  if (!v.hit) return;
  double* s = &sums_[(static_cast<std::size_t>(pixel.y) * static_cast<std::size_t>(resolution_.x) +
                      static_cast<std::size_t>(pixel.x)) *
                     stride_];
  *s++ += 1.0;
  const glm::dvec3 p(v.p);
  for (Aov a : aovs_) {
    switch (a) {
      case Aov::kDepth:
        *s++ += glm::dot(p - glm::dvec3(worldFromCamera[3]), glm::dvec3(worldFromCamera[2]));
        break;
      case Aov::kDistance:
        *s++ += static_cast<double>(v.distance);
        break;
      case Aov::kPosition:
        for (int i = 0; i < 3; ++i) *s++ += p[i] + renderOrigin[i];
        break;
      case Aov::kNormal: {
        const glm::dvec3 n(v.ns), ng(v.n);
        const glm::dvec3 all[4] = {n, ng, toCameraCv(worldFromCamera, n),
                                   toCameraCv(worldFromCamera, ng)};
        for (const glm::dvec3& d : all)
          for (int i = 0; i < 3; ++i) *s++ += d[i];
        break;
      }
      case Aov::kAlbedo: {
        // Numerators here, the white's denominators beside: divided in toImage (a ratio
        // of the pixel's sums, not a mean of per-sample ratios, which is biased for colour).
        double* den = &albedoWhite_[static_cast<std::size_t>(s - sums_.data()) / stride_ * 3];
        for (int c = 0; c < 3; ++c) {
          // r_c·D65/p at the sample's wavelengths (the 1/N of the estimate cancels).
          const SampledSpectrum white =
              safeDiv(sampleSpectrum(whiteXyz_[c], lambda), lambda.pdfs());
          const SampledSpectrum lit = white * v.albedo;
          for (int i = 0; i < kWavelengthSamples; ++i) {
            *s += static_cast<double>(lit[i]);
            den[c] += static_cast<double>(white[i]);
          }
          ++s;
        }
        break;
      }
      case Aov::kRoughness:
        *s++ += static_cast<double>(v.roughness);
        break;
    }
  }
}

Image AovFilm::toImage(int samplesPerPixel) const {
  Image out(resolution_.x, resolution_.y, channels_);
  const std::size_t n =
      static_cast<std::size_t>(resolution_.x) * static_cast<std::size_t>(resolution_.y);
  for (std::size_t px = 0; px < n; ++px) {
    const double* s = &sums_[px * stride_];
    const double hits = s[0];
    out.pixels[px * stride_] = static_cast<float>(hits / samplesPerPixel);
    for (std::size_t c = 1; c < stride_; ++c)
      out.pixels[px * stride_ + c] = hits > 0.0 ? static_cast<float>(s[c] / hits) : 0.0f;
    if (albedoChannel_ == 0 || hits == 0.0) continue;
    // Albedo: the ratio of each XYZ sum to the D65 white's, times the white's XYZ (Y = 1),
    // to Rec.709 (white (1, 1, 1)).
    const RgbColorSpace& rec709 = RgbColorSpace::linearRec709();
    glm::dvec3 ratio;
    for (int c = 0; c < 3; ++c) {
      const double den = albedoWhite_[px * 3 + static_cast<std::size_t>(c)];
      ratio[c] = den > 0.0 ? s[albedoChannel_ + static_cast<std::size_t>(c)] / den : 0.0;
    }
    const glm::dvec3 rgb = rec709.fromXyz(ratio * rec709.toXyz(glm::dvec3(1.0)));
    for (int c = 0; c < 3; ++c)
      out.pixels[px * stride_ + albedoChannel_ + static_cast<std::size_t>(c)] =
          static_cast<float>(rgb[c]);
  }
  return out;
}

}  // namespace camsim
