#include "integrator/render/aov_film.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

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
    case Aov::kMotion:
      return {"motion_fw.X", "motion_fw.Y", "motion_bw.X", "motion_bw.Y", "flow_fw.X",
              "flow_fw.Y",   "flow_fw.Z",   "flow_bw.X",   "flow_bw.Y",   "flow_bw.Z"};
    case Aov::kInstanceId:
    case Aov::kClassId:
    case Aov::kMaterialId:
      return {};  // IdFilm's channels
  }
  return {};
}

}  // namespace

AovFilm::AovFilm(const Scene& scene)
    : scene_(scene), resolution_(scene.camera().resolution()), aovs_(scene.settings().aovs) {
  if (aovs_.empty()) return;
  const std::size_t pixels =
      static_cast<std::size_t>(resolution_.x) * static_cast<std::size_t>(resolution_.y);
  channels_ = {"coverage.A"};
  for (Aov a : aovs_) {
    if (const std::optional<IdKind> kind = idKindOf(a)) {
      idFilms_.push_back(std::make_unique<IdFilm>(resolution_, *kind, scene.ids()[*kind]));
      idKinds_.push_back(*kind);
    }
    for (std::string& c : channelsOf(a)) channels_.push_back(std::move(c));
  }
  stride_ = channels_.size();  // slot 0: the hit count (coverage.A once divided by spp)
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    if (channels_[c] == "albedo.R") albedoChannel_ = c;
    if (channels_[c] == "motion_fw.X") motionChannel_ = c;
  }
  if (albedoChannel_ > 0) {
    const SpectralResponse xyz = SpectralResponse::cieXyz();
    const Spectrum d65 = cieIlluminant("D65");
    for (int c = 0; c < 3; ++c) whiteXyz_[static_cast<std::size_t>(c)] = xyz.channel(c).curve * d65;
    albedoWhite_.assign(pixels * 3, 0.0);
  }
  if (motionChannel_ > 0) {
    // The frame times' poses once, not per sample.
    motionCount_.assign(pixels, 0.0);
    const double t = scene.camera().shutter().centre(), dt = scene.frameInterval();
    frameTimes_ = {t - dt, t, t + dt};
    for (std::size_t j = 0; j < 3; ++j)
      cameraAt_[j] = scene.camera().worldFromCameraAt(frameTimes_[j]);
    shapeAt_.resize(scene.shapeCount());
    for (std::size_t s = 0; s < scene.shapeCount(); ++s) {
      const RigidMotion& m = scene.motion(static_cast<int>(s));
      if (!m.empty())
        for (std::size_t j = 0; j < 3; ++j) shapeAt_[s][j] = m.at(frameTimes_[j]);
    }
  }
  for (std::size_t s = 0; s < scene.shapeCount(); ++s)
    for (IdKind k : idKinds_) idEntries_.push_back(scene.ids()[k].ofShape[s]);
  // Whether the camera turns or moves during this frame's exposure: if not, the camera-axes
  // normals are the world means rotated once per pixel.
  cameraTurns_ = scene.camera().moves(scene.exposureStart(), scene.exposureEnd());
  worldFromCamera_ = scene.camera().worldFromCameraAt(scene.exposureStart());
  for (std::size_t c = 0; c < channels_.size(); ++c)
    if (channels_[c] == "N.X") normalChannel_ = c;
  for (Aov a : aovs_) {
    wantsMaterial_ = wantsMaterial_ || a == Aov::kAlbedo || a == Aov::kRoughness;
    wantsCamera_ = wantsCamera_ || a == Aov::kDepth || a == Aov::kNormal;
  }
  sums_.assign(pixels * stride_, 0.0);
}

void AovFilm::addMotion(double* sums, const AovSample& s) {
  const VisibleSurface& v = s.visible;
  const RigidMotion& motion = scene_.motion(v.shape);
  const glm::dvec3 p(v.p);
  // The hit in object space (at the sample's time), then at each frame's reference time.
  const glm::dvec3 object =
      motion.empty() ? p : glm::dvec3(glm::inverse(motion.at(s.time)) * glm::dvec4(p, 1.0));
  // The shape's and the camera's poses at the frame times were computed once (constructor).
  const std::array<glm::dmat4, 3>& shapeAt = shapeAt_[static_cast<std::size_t>(v.shape)];
  std::array<glm::dvec3, 3> at;
  std::array<glm::dvec2, 3> pixel;
  for (std::size_t j = 0; j < 3; ++j) {
    at[j] = motion.empty() ? p : glm::dvec3(shapeAt[j] * glm::dvec4(object, 1.0));
    const std::optional<glm::dvec2> q = scene_.camera().projectFrom(cameraAt_[j], at[j]);
    if (!q) return;
    pixel[j] = *q;
  }
  const std::size_t px = static_cast<std::size_t>(sums - sums_.data()) / stride_;
  motionCount_[px] += 1.0;
  double* m = sums + motionChannel_;
  const glm::dvec2 fw = pixel[2] - pixel[1], bw = pixel[0] - pixel[1];
  const glm::dvec3 flowFw = at[2] - at[1], flowBw = at[0] - at[1];
  const double values[10] = {fw.x,     fw.y,     bw.x,     bw.y,     flowFw.x,
                             flowFw.y, flowFw.z, flowBw.x, flowBw.y, flowBw.z};
  for (double x : values) *m++ += x;
}

void AovFilm::addSample(const AovSample& sample) {
  const glm::ivec2 pixel = sample.pixel;
  const VisibleSurface& v = sample.visible;
  if (!idFilms_.empty()) {
    const std::uint32_t* entries =
        v.hit ? &idEntries_[static_cast<std::size_t>(v.shape) * idFilms_.size()] : nullptr;
    for (std::size_t k = 0; k < idFilms_.size(); ++k)
      idFilms_[k]->add(pixel, entries ? entries[k] : 0u);
  }
  if (!v.hit) return;
  double* s = &sums_[(static_cast<std::size_t>(pixel.y) * static_cast<std::size_t>(resolution_.x) +
                      static_cast<std::size_t>(pixel.x)) *
                     stride_];
  double* const pixelSums = s;
  *s++ += 1.0;
  // The camera's pose at the sample's time, from the render loop (wantsCamera()).
  const glm::dmat4& worldFromCamera = wantsCamera_ ? *sample.worldFromCamera : worldFromCamera_;
  const glm::dvec3& renderOrigin = scene_.renderOrigin();
  const SampledWavelengths& lambda = sample.lambda;
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
        for (int i = 0; i < 3; ++i) s[i] += n[i];
        for (int i = 0; i < 3; ++i) s[3 + i] += ng[i];
        if (!cameraTurns_) {  // camera axes from the world means in toImage (linear)
          s += 12;
          break;
        }
        const glm::dvec3 nc = cameraCvFromWorld(worldFromCamera, n),
                         ngc = cameraCvFromWorld(worldFromCamera, ng);
        for (int i = 0; i < 3; ++i) s[6 + i] += nc[i];
        for (int i = 0; i < 3; ++i) s[9 + i] += ngc[i];
        s += 12;
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
          // The sample's wavelengths averaged in float (the 1/4 cancels in the ratio), the
          // pixel's samples summed in double.
          *s++ += static_cast<double>((white * v.albedo).average());
          den[c] += static_cast<double>(white.average());
        }
        break;
      }
      case Aov::kRoughness:
        *s++ += static_cast<double>(v.roughness);
        break;
      case Aov::kMotion:
        addMotion(pixelSums, sample);
        s += 10;
        break;
      case Aov::kInstanceId:
      case Aov::kClassId:
      case Aov::kMaterialId:
        break;
    }
  }
}

Image AovFilm::toImage(int samplesPerPixel) const {
  std::vector<std::string> names = channels_;
  for (const auto& f : idFilms_)
    names.insert(names.end(), f->channels().begin(), f->channels().end());
  Image out(resolution_.x, resolution_.y, names);
  const std::size_t n =
      static_cast<std::size_t>(resolution_.x) * static_cast<std::size_t>(resolution_.y);
  const std::size_t width = names.size();
  const RgbColorSpace& rec709 = RgbColorSpace::linearRec709();
  for (std::size_t px = 0; px < n; ++px) {
    const double* s = &sums_[px * stride_];
    float* o = &out.pixels[px * width];
    const double hits = s[0];
    o[0] = static_cast<float>(hits / samplesPerPixel);
    for (std::size_t c = 1; c < stride_; ++c)
      o[c] = hits > 0.0 ? static_cast<float>(s[c] / hits) : 0.0f;
    if (normalChannel_ > 0 && !cameraTurns_ && hits > 0.0)
      for (std::size_t layer = 0; layer < 2; ++layer) {  // N, Ng → N_cam, Ng_cam
        const double* w = s + normalChannel_ + 3 * layer;
        const glm::dvec3 c =
            cameraCvFromWorld(worldFromCamera_, glm::dvec3(w[0], w[1], w[2]) / hits);
        for (int i = 0; i < 3; ++i)
          o[normalChannel_ + 6 + 3 * layer + static_cast<std::size_t>(i)] =
              static_cast<float>(c[i]);
      }
    if (motionChannel_ > 0)
      for (std::size_t c = motionChannel_; c < motionChannel_ + 10; ++c)
        o[c] = motionCount_[px] > 0.0 ? static_cast<float>(s[c] / motionCount_[px]) : 0.0f;
    float* ids = o + stride_;
    for (const auto& f : idFilms_) {
      f->pixel(px, samplesPerPixel, ids);
      ids += f->channels().size();
    }
    if (albedoChannel_ == 0 || hits == 0.0) continue;
    // Albedo: the ratio of each XYZ sum to the D65 white's, times the white's XYZ (Y = 1),
    // to Rec.709 (white (1, 1, 1)).
    glm::dvec3 ratio;
    for (int c = 0; c < 3; ++c) {
      const double den = albedoWhite_[px * 3 + static_cast<std::size_t>(c)];
      ratio[c] = den > 0.0 ? s[albedoChannel_ + static_cast<std::size_t>(c)] / den : 0.0;
    }
    const glm::dvec3 rgb = rec709.fromXyz(ratio * rec709.toXyz(glm::dvec3(1.0)));
    for (int c = 0; c < 3; ++c)
      o[albedoChannel_ + static_cast<std::size_t>(c)] = static_cast<float>(rgb[c]);
  }
  return out;
}

}  // namespace camsim
