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
    case Aov::kInstanceId:
    case Aov::kClassId:
    case Aov::kMaterialId:
      return {};  // IdFilm's channels
  }
  return {};
}

}  // namespace

AovFilm::AovFilm(const Scene& scene) : scene_(scene), aovs_(scene.settings().aovs) {
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
  CAMSIM_CHECK(idFilms_.size() <= static_cast<std::size_t>(kIdKindCount));  // AovPixel::idSlot
  stride_ = channels.size();  // slot 0: the hit count (coverage.A once divided by spp)
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const std::string& name = channels[c];
    if (name == "depth.Z") depthChannel_ = c;
    if (name == "distance.Z") distanceChannel_ = c;
    if (name == "P.X") positionChannel_ = c;
    if (name == "N.X") normalChannel_ = c;
    if (name == "albedo.R") albedoChannel_ = c;
    if (name == "roughness.Y") roughnessChannel_ = c;
    if (name == "motion_fw.X") motionChannel_ = c;
  }
  if (albedoChannel_ > 0) {
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
  if (motionChannel_ > 0) {
    // The frame times' poses once, not per sample.
    const double t = scene.camera().shutter().centre(), dt = scene.frameInterval();
    frameTimes_ = {t - dt, t, t + dt};
    std::array<glm::dmat4, 3> cameraAt;
    for (std::size_t j = 0; j < 3; ++j)
      cameraAt[j] = scene.camera().worldFromCameraAt(frameTimes_[j]);
    projector_.emplace(scene.camera(), cameraAt);
    shapeAt_.resize(scene.shapeCount());
    for (std::size_t s = 0; s < scene.shapeCount(); ++s)
      if (shapeMoves_[s])
        for (std::size_t j = 0; j < 3; ++j)
          shapeAt_[s][j] = scene.motion(static_cast<int>(s)).at(frameTimes_[j]);
  }
  for (std::size_t s = 0; s < scene.shapeCount(); ++s)
    for (IdKind k : idKinds) idEntries_.push_back(scene.ids()[k].ofShape[s]);
  // Whether the camera turns or moves during this frame's exposure: if not, the camera-axes
  // normals are the world means rotated once per pixel.
  cameraTurns_ = scene.camera().moves(scene.exposureStart(), scene.exposureEnd());
  worldFromCamera_ = scene.camera().worldFromCameraAt(scene.exposureStart());
  wantsMaterial_ = albedoChannel_ > 0 || roughnessChannel_ > 0;
  wantsCamera_ = depthChannel_ > 0 || normalChannel_ > 0;
  for (const IdFilm& f : idFilms_)
    channels.insert(channels.end(), f.channels().begin(), f.channels().end());
  const glm::ivec2 res = scene.camera().resolution();
  image_ = Image(res.x, res.y, std::move(channels));
}

AovPixel AovFilm::scratch() const {
  AovPixel px;
  px.sums.assign(stride_, 0.0);
  px.ids.assign(idFilms_.size(), IdFilm::Slots{});
  return px;
}

void AovFilm::startPixel(AovPixel& px, glm::ivec2 pixel) const {
  px.pixel = pixel;
  px.samples = 0;
  std::fill(px.sums.begin(), px.sums.end(), 0.0);
  px.albedo = Double4{};
  px.white = Double4{};
  px.motionLanes = MotionVectorSums{};
  px.motionPending = 0;
  px.motionMoves = {};
  std::fill(px.ids.begin(), px.ids.end(), IdFilm::Slots{});
  px.idShape = AovPixel::kNoShape;
}

void AovFilm::addMotion(AovPixel& px, const AovSample& s) const {
  const VisibleSurface& v = s.visible;
  const glm::dvec3 p(v.p);
  // The hit at each frame's reference time: a static shape's stays where it is; a moving
  // one's is taken to object space at the sample's time and moved to each frame time (the
  // poses at the frame times were computed once, in the constructor).
  const int lane = px.motionPending++;
  const std::size_t shape = static_cast<std::size_t>(v.shape);
  const bool moves = shapeMoves_[shape];
  px.motionMoves[static_cast<std::size_t>(lane)] = moves;
  if (!moves) {
    for (std::size_t j = 0; j < 3; ++j) {
      px.motion.x[j][lane] = p.x;
      px.motion.y[j][lane] = p.y;
      px.motion.z[j][lane] = p.z;
    }
  } else {
    const glm::dvec3 object = scene_.motion(v.shape).objectFromWorld(p, s.time);
    for (std::size_t j = 0; j < 3; ++j) {
      const glm::dvec3 at(shapeAt_[shape][j] * glm::dvec4(object, 1.0));
      px.motion.x[j][lane] = at.x;
      px.motion.y[j][lane] = at.y;
      px.motion.z[j][lane] = at.z;
    }
  }
  if (px.motionPending == 4) flushMotion(px);
}

void AovFilm::flushMotion(AovPixel& px) const {
  if (px.motionPending == 0) return;
  Long4 front;
  projector_->addMotionVectors(px.motion, px.motionPending, px.motionLanes, front);
  // Scene flow: +0 for a static shape's hit, so only the moving ones are summed (rare).
  if (px.motionMoves != std::array<bool, 4>{}) {
    double* m = px.sums.data() + motionChannel_;
    const PosePoints& a = px.motion;
    for (int lane = 0; lane < px.motionPending; ++lane) {
      if (!front[lane] || !px.motionMoves[static_cast<std::size_t>(lane)]) continue;
      m[4] += a.x[2][lane] - a.x[1][lane];
      m[5] += a.y[2][lane] - a.y[1][lane];
      m[6] += a.z[2][lane] - a.z[1][lane];
      m[7] += a.x[0][lane] - a.x[1][lane];
      m[8] += a.y[0][lane] - a.y[1][lane];
      m[9] += a.z[0][lane] - a.z[1][lane];
    }
  }
  px.motionPending = 0;
  px.motionMoves = {};
}

void AovFilm::addSample(AovPixel& px, const AovSample& sample) const {
  const VisibleSurface& v = sample.visible;
  ++px.samples;
  const std::size_t idCount = idFilms_.size();
  if (idCount > 0) {
    const int shape = v.hit ? v.shape : -1;
    if (shape == px.idShape) {  // the common case: the previous sample's shape again
      for (std::size_t k = 0; k < idCount; ++k)
        if (IdFilm::Slot* slot = px.idSlot[k]) ++slot->count;
    } else {
      const std::uint32_t* entries =
          v.hit ? &idEntries_[static_cast<std::size_t>(v.shape) * idCount] : nullptr;
      for (std::size_t k = 0; k < idCount; ++k)
        px.idSlot[k] = IdFilm::add(px.ids[k], entries ? entries[k] : 0u);
      px.idShape = shape;
    }
  }
  if (!v.hit) return;
  double* const s = px.sums.data();
  s[0] += 1.0;
  // The camera's pose at the sample's time, from the render loop (wantsCamera()).
  const glm::dmat4& worldFromCamera = wantsCamera_ ? *sample.worldFromCamera : worldFromCamera_;
  const double px_ = v.p.x, py = v.p.y, pz = v.p.z;
  if (depthChannel_) {  // glm::dot((p − o), z) in its order
    const glm::dvec4& o = worldFromCamera[3];
    const glm::dvec4& z = worldFromCamera[2];
    s[depthChannel_] += (px_ - o.x) * z.x + (py - o.y) * z.y + (pz - o.z) * z.z;
  }
  if (distanceChannel_) s[distanceChannel_] += static_cast<double>(v.distance);
  if (positionChannel_) {
    const glm::dvec3& origin = scene_.renderOrigin();
    double* w = s + positionChannel_;
    w[0] += px_ + origin.x;
    w[1] += py + origin.y;
    w[2] += pz + origin.z;
  }
  if (normalChannel_) {
    double* w = s + normalChannel_;
    const double n[3] = {v.ns.x, v.ns.y, v.ns.z}, ng[3] = {v.n.x, v.n.y, v.n.z};
    for (int i = 0; i < 3; ++i) w[i] += n[i];
    for (int i = 0; i < 3; ++i) w[3 + i] += ng[i];
    if (cameraTurns_) {  // else the camera axes from the world means in endPixel (linear)
      // cameraCvFromWorld: (n·x, −(n·y), n·z) over the pose's axes, in glm::dot's order.
      for (int c = 0; c < 3; ++c) {
        const glm::dvec4& axis = worldFromCamera[c];
        const double sign = c == 1 ? -1.0 : 1.0;
        w[6 + c] += sign * (n[0] * axis.x + n[1] * axis.y + n[2] * axis.z);
        w[9 + c] += sign * (ng[0] * axis.x + ng[1] * axis.y + ng[2] * axis.z);
      }
    }
  }
  if (albedoChannel_) {
    // r_c·D65/p at each of the sample's wavelengths (the 1/N of the estimate cancels in the
    // ratio), all three c at once; summed over the wavelengths in float, over the pixel's
    // samples in double. Numerators here, the white's denominators beside: divided in
    // endPixel (a ratio of the pixel's sums, not a mean of per-sample ratios, which is
    // biased for colour).
    const SampledWavelengths& lambda = sample.lambda;
    // 1/p (0 for a terminated wavelength), the four at once.
    const SampledSpectrum invPdf = safeDiv(SampledSpectrum(1.0f), lambda.pdfs());
    Float4 num{}, den{};
    for (int i = 0; i < kWavelengthSamples; ++i) {
      const std::size_t k = static_cast<std::size_t>(lambda.gridIndex(i));
      const Float4 a = whiteXyz_[k], b = whiteXyz_[k + 1];
      const Float4 white = (a + lambda.gridFraction(i) * (b - a)) * invPdf[i];
      num += white * v.albedo[i];
      den += white;
    }
    px.albedo += __builtin_convertvector(num, Double4);
    px.white += __builtin_convertvector(den, Double4);
  }
  if (roughnessChannel_) s[roughnessChannel_] += static_cast<double>(v.roughness);
  if (motionChannel_) addMotion(px, sample);
}

void AovFilm::endPixel(AovPixel& px) {
  if (motionChannel_ > 0) flushMotion(px);
  const double* s = px.sums.data();
  float* o = &image_.pixels[image_.index(px.pixel.x, px.pixel.y, 0)];
  const double hits = s[0];
  o[0] = static_cast<float>(hits / px.samples);
  for (std::size_t c = 1; c < stride_; ++c)
    o[c] = hits > 0.0 ? static_cast<float>(s[c] / hits) : 0.0f;
  if (normalChannel_ > 0 && !cameraTurns_ && hits > 0.0)
    for (std::size_t layer = 0; layer < 2; ++layer) {  // N, Ng → N_cam, Ng_cam
      const double* w = s + normalChannel_ + 3 * layer;
      const glm::dvec3 c = cameraCvFromWorld(worldFromCamera_, glm::dvec3(w[0], w[1], w[2]) / hits);
      for (int i = 0; i < 3; ++i)
        o[normalChannel_ + 6 + 3 * layer + static_cast<std::size_t>(i)] = static_cast<float>(c[i]);
    }
  if (motionChannel_ > 0) {
    // The motion vectors' lane sums, lanes in order (each lane's samples in sample order).
    const MotionVectorSums& l = px.motionLanes;
    const double count = (l.count[0] + l.count[1]) + (l.count[2] + l.count[3]);
    const double sums[4] = {(l.fwx[0] + l.fwx[1]) + (l.fwx[2] + l.fwx[3]),
                            (l.fwy[0] + l.fwy[1]) + (l.fwy[2] + l.fwy[3]),
                            (l.bwx[0] + l.bwx[1]) + (l.bwx[2] + l.bwx[3]),
                            (l.bwy[0] + l.bwy[1]) + (l.bwy[2] + l.bwy[3])};
    for (std::size_t c = 0; c < 10; ++c) {
      const double sum = c < 4 ? sums[c] : s[motionChannel_ + c];
      o[motionChannel_ + c] = count > 0.0 ? static_cast<float>(sum / count) : 0.0f;
    }
  }
  float* ids = o + stride_;
  for (std::size_t k = 0; k < idFilms_.size(); ++k) {
    idFilms_[k].write(px.ids[k], px.samples, ids);
    ids += idFilms_[k].channels().size();
  }
  if (albedoChannel_ == 0 || hits == 0.0) return;
  // Albedo: the ratio of each XYZ sum to the D65 white's, times the white's XYZ (Y = 1),
  // to Rec.709 (white (1, 1, 1)).
  glm::dvec3 ratio;
  for (int c = 0; c < 3; ++c) {
    const double den = px.white[c];
    ratio[c] = den > 0.0 ? px.albedo[c] / den : 0.0;
  }
  const RgbColorSpace& rec709 = RgbColorSpace::linearRec709();
  const glm::dvec3 rgb = rec709.fromXyz(ratio * rec709.toXyz(glm::dvec3(1.0)));
  for (int c = 0; c < 3; ++c)
    o[albedoChannel_ + static_cast<std::size_t>(c)] = static_cast<float>(rgb[c]);
}

}  // namespace camsim
