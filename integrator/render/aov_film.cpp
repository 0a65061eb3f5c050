#include "integrator/render/aov_film.h"

#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "sensor/base/check.h"
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
    case Aov::kValid:
      return {"valid.A"};
    case Aov::kOcclusion:
      return OcclusionFilm::channels();
    case Aov::kBoundary:
      return {"boundary.A"};
    case Aov::kInstanceId:
    case Aov::kClassId:
    case Aov::kMaterialId:
      return {};  // IdFilm's channels
    case Aov::kAmodal:
      return {};  // MaskFilm's
  }
  return {};
}

}  // namespace

AovFilm::AovFilm(const Scene& scene, bool allowAvx2) : scene_(scene), aovs_(scene.settings().aovs) {
  if (aovs_.empty()) return;
  std::vector<std::string> channels = {"coverage.A"};
  std::vector<IdKind> idKinds;
  for (Aov a : aovs_) {
    if (const std::optional<IdKind> kind = idKindOf(a)) {
      idFilms_.emplace_back(*kind, scene.ids()[*kind]);
      idKinds.push_back(*kind);
    }
    for (std::string& c : channelsOf(a)) channels.push_back(std::move(c));
  }
  CAMSIM_CHECK(idFilms_.size() <= static_cast<std::size_t>(kIdKindCount));  // AovPixel::ids
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const std::string& name = channels[c];
    if (name == "depth.Z") depthChannel_ = c;
    if (name == "distance.Z") distanceChannel_ = c;
    if (name == "P.X") positionChannel_ = c;
    if (name == "N.X") normalChannel_ = c;
    if (name == "albedo.R") albedoChannel_ = c;
    if (name == "roughness.Y") roughnessChannel_ = c;
    if (name == "motion_fw.X") motionChannel_ = c;
    if (name == "valid.A") validChannel_ = c;
    if (name == "occlusion_fw.A") occlusionChannel_ = c;
    if (name == "boundary.A") boundaryChannel_ = c;
  }
  if (albedoChannel_ > 0) {
    const RgbColorSpace& rec709 = RgbColorSpace::linearRec709();
    rec709WhiteXyz_ = rec709.toXyz(glm::dvec3(1.0));
    rec709FromXyz_ = rec709.rgbFromXyz();
    const SpectralResponse xyz = SpectralResponse::cieXyz();
    const Spectrum d65 = cieIlluminant("D65");
    whiteXyz_.assign(kSpectrumSamples, Float4{});
    for (int c = 0; c < 3; ++c) {
      const Spectrum white = xyz.channel(c).curve * d65;
      for (int i = 0; i < kSpectrumSamples; ++i)
        whiteXyz_[static_cast<std::size_t>(i)][c] = white.sample(i);
    }
  }
  shapeMoves_.assign(scene.shapeCount(), 0);
  for (std::size_t s = 0; s < scene.shapeCount(); ++s)
    shapeMoves_[s] = !scene.motion(static_cast<int>(s)).empty();
  stagesMotion_ = motionChannel_ > 0 || occlusionChannel_ > 0;
  if (stagesMotion_) {
    // The frame times' poses once, not per sample.
    // previous, this and the next frame's reference time (shutter centres), s
    const double t = scene.camera().shutter().centre(), dt = scene.frameInterval();
    const std::array<double, 3> frameTimes = {t - dt, t, t + dt};
    std::array<glm::dmat4, 3> cameraAt;
    for (std::size_t j = 0; j < 3; ++j)
      cameraAt[j] = scene.camera().worldFromCameraAt(frameTimes[j]);
    projector_.emplace(scene.camera(), cameraAt);
    shapeAt_.resize(scene.shapeCount());
    for (std::size_t s = 0; s < scene.shapeCount(); ++s)
      if (shapeMoves_[s])
        for (std::size_t j = 0; j < 3; ++j)
          shapeAt_[s][j] = scene.motion(static_cast<int>(s)).at(frameTimes[j]);
    if (occlusionChannel_ > 0)
      occlusion_ = std::make_unique<OcclusionFilm>(scene, frameTimes, cameraAt);
  }
  for (std::size_t s = 0; s < scene.shapeCount(); ++s)
    for (IdKind k : idKinds) idEntries_.push_back(scene.ids()[k].ofShape[s]);
  // Whether the camera turns or moves during this frame's exposure: if not, the camera-axes
  // normals are the world means rotated once per pixel.
  cameraTurns_ = scene.camera().moves(scene.exposureStart(), scene.exposureEnd());
  worldFromCamera_ = scene.camera().worldFromCameraAt(scene.exposureStart());
  wantsMaterial_ = albedoChannel_ > 0 || roughnessChannel_ > 0;
  wantsCamera_ = depthChannel_ > 0 || normalChannel_ > 0;
  idChannel_ = channels.size();
  for (const IdFilm& f : idFilms_)
    channels.insert(channels.end(), f.channels().begin(), f.channels().end());
  if (std::find(aovs_.begin(), aovs_.end(), Aov::kAmodal) != aovs_.end()) {
    masks_.emplace(scene);
    maskChannel_ = channels.size();
    for (std::string& c : masks_->channels()) channels.push_back(std::move(c));
  }
  const glm::ivec2 res = scene.camera().resolution();
  image_ = Image(res.x, res.y, std::move(channels));
  avx2_ = allowAvx2 && simd::cpuHasAvx2();
}

void AovFilm::startPixel(AovPixel& px, glm::ivec2 pixel) const {
  static_cast<AovPixelState&>(px) = AovPixelState{};
  px.pixel = pixel;
  if (!masks_) return;
  if (px.masks.amodal.empty()) px.masks = masks_->emptyCounts();  // the thread's first pixel
  MaskFilm::clear(px.masks);
}

void AovFilm::endPixel(AovPixel& px) {
  sumRecords(px);
  if (stagesMotion_) flushMotion(px);
  // The image's pixel is still 0 (the constructor's), as writePixel expects.
  writePixel(px, &image_.pixels[image_.index(px.pixel.x, px.pixel.y, 0)]);
}

void AovFilm::writePixel(const AovPixel& px, float* o) const {
  const double hits = px.scalars[0];
  o[0] = static_cast<float>(hits / px.samples);
  if (validChannel_) o[validChannel_] = static_cast<float>(px.samples - px.noRay) / px.samples;
  float* ids = o + idChannel_;
  for (std::size_t k = 0; k < idFilms_.size(); ++k) {
    idFilms_[k].write(px.ids[k], px.samples, ids);
    ids += idFilms_[k].channels().size();
  }
  if (motionChannel_ > 0) writeMotion(px, o + motionChannel_);
  if (occlusionChannel_ > 0) OcclusionFilm::write(px.occlusion, o + occlusionChannel_);
  if (boundaryChannel_ > 0)  // misses: the samples with a camera ray that hit nothing
    o[boundaryChannel_] =
        px.boundary.value(static_cast<int>(hits), px.samples - static_cast<int>(hits) - px.noRay);
  if (masks_) masks_->write(px.masks, px.samples, o + maskChannel_);
  if (hits == 0.0) return;  // the averaged channels stay 0
  // Σ · (1/hits): one division for the ≈ 25 means (a division per mean was most of a
  // pixel's cost here).
  const double invHits = 1.0 / hits;
  const auto mean = [invHits](double sum) { return static_cast<float>(sum * invHits); };
  if (depthChannel_) o[depthChannel_] = mean(px.scalars[1]);
  if (distanceChannel_) o[distanceChannel_] = mean(px.scalars[2]);
  if (roughnessChannel_) o[roughnessChannel_] = mean(px.scalars[3]);
  if (positionChannel_)
    for (int i = 0; i < 3; ++i)
      o[positionChannel_ + static_cast<std::size_t>(i)] = mean(px.position[i]);
  if (normalChannel_) {  // N, Ng, N_cam, Ng_cam
    float* n = o + normalChannel_;
    for (int i = 0; i < 3; ++i) {
      n[i] = mean(px.normal[i]);
      n[3 + i] = mean(px.geometricNormal[i]);
    }
    if (cameraTurns_) {
      for (int i = 0; i < 3; ++i) {
        n[6 + i] = mean(px.normalCam[i]);
        n[9 + i] = mean(px.geometricNormalCam[i]);
      }
    } else {  // the world means in the camera's axes (linear)
      const glm::dvec3 c = cameraCvFromWorld(
          worldFromCamera_, glm::dvec3(px.normal[0], px.normal[1], px.normal[2]) * invHits);
      const glm::dvec3 cg = cameraCvFromWorld(
          worldFromCamera_,
          glm::dvec3(px.geometricNormal[0], px.geometricNormal[1], px.geometricNormal[2]) *
              invHits);
      for (int i = 0; i < 3; ++i) {
        n[6 + i] = static_cast<float>(c[i]);
        n[9 + i] = static_cast<float>(cg[i]);
      }
    }
  }
  if (albedoChannel_ == 0) return;
  // Albedo: the ratio of each XYZ sum to the D65 white's, times the white's XYZ (Y = 1),
  // to Rec.709 (white (1, 1, 1)).
  glm::dvec3 ratio;
  for (int c = 0; c < 3; ++c) {
    const double den = px.white[c];
    ratio[c] = den > 0.0 ? px.albedo[c] / den : 0.0;
  }
  const glm::dvec3 rgb = rec709FromXyz_ * (ratio * rec709WhiteXyz_);  // RgbColorSpace::fromXyz
  for (int c = 0; c < 3; ++c)
    o[albedoChannel_ + static_cast<std::size_t>(c)] = static_cast<float>(rgb[c]);
}

void AovFilm::writeMotion(const AovPixel& px, float* o) const {
  // The motion vectors' lane sums, lanes in order (each lane's samples in sample order).
  const MotionVectorSums& l = px.motionLanes;
  const double count = (l.count[0] + l.count[1]) + (l.count[2] + l.count[3]);
  if (!(count > 0.0)) return;  // no sample in front of the lens at all three times: 0
  const double vectors[4] = {
      (l.fwx[0] + l.fwx[1]) + (l.fwx[2] + l.fwx[3]), (l.fwy[0] + l.fwy[1]) + (l.fwy[2] + l.fwy[3]),
      (l.bwx[0] + l.bwx[1]) + (l.bwx[2] + l.bwx[3]), (l.bwy[0] + l.bwy[1]) + (l.bwy[2] + l.bwy[3])};
  const double inv = 1.0 / count;
  for (std::size_t c = 0; c < 4; ++c) o[c] = static_cast<float>(vectors[c] * inv);
  for (std::size_t c = 0; c < 6; ++c) o[4 + c] = static_cast<float>(px.flow[c] * inv);
}

}  // namespace camsim
