// AovFilm's per-sample part (aov_film.h): a sample's first hit recorded in its pixel's
// scratch (addSample), and the records summed a batch at a time (sumRecords). Each body is
// written once and inlined into two copies: one for the build's target and, with
// CAMSIM_SIMD_X86, one compiled for AVX2 (whole Double4 registers), chosen once per film by
// simd::cpuHasAvx2(). No FMA contraction happens in either (neither target enables FMA),
// and each lane does the scalar code's operations in its order, so both give the same bits.
#include <cstring>

#include "integrator/render/aov_film.h"

namespace camsim {
namespace {

// Glm vectors as Double4s (x, y, z in lanes 0–2), written through a reference: a Double4
// by value changes the x86-64 ABI without AVX.
// The member `field` of a VisibleSurface: its 16 bytes from the field's start in one load
// (the fourth float is the next member's, inside the struct), lane 3 cleared.
template <glm::vec3 VisibleSurface::*field>
[[gnu::always_inline]] inline void load(Double4& out, const VisibleSurface& v) {
  static_assert(sizeof(glm::vec3) == 12);
  Float4 f;
  std::memcpy(&f, &(v.*field), sizeof f);
  f[3] = 0.0f;
  out = __builtin_convertvector(f, Double4);
}
// Element by element: the pose was written just before (the render loop), and one 32-byte
// load of several recent narrower stores cannot be forwarded from the store buffer (a
// stall of tens of cycles), while each 8-byte load can.
[[gnu::always_inline]] inline void load(Double4& out, const glm::dvec4& v) {
  out = Double4{v.x, v.y, v.z, v.w};
}

}  // namespace

// A sample: only what needs its own camera pose and wavelengths is worked out here (they
// are gone after the sample); the rest waits in the record for sumRecords.
[[gnu::always_inline]] inline void AovFilm::addSampleBody(AovPixel& px,
                                                          const AovSample& sample) const {
  ++px.samples;
  AovRecord& r = px.records[static_cast<std::size_t>(px.pending++)];
  const VisibleSurface& v = r.visible;  // filled in place (nextSurface)
  if (!v.hit) return;
  r.time = sample.time;
  // The camera's pose at the sample's time, from the render loop (wantsCamera()).
  const glm::dmat4& worldFromCamera = wantsCamera_ ? *sample.worldFromCamera : worldFromCamera_;
  if (depthChannel_) {  // glm::dot(p − o, z) in its order
    Double4 p, o, z;
    load<&VisibleSurface::p>(p, v);
    load(o, worldFromCamera[3]);
    load(z, worldFromCamera[2]);
    const Double4 d = (p - o) * z;
    r.depth = d[0] + d[1] + d[2];
  }
  if (normalChannel_ && cameraTurns_) {  // else from the world means in endPixel (linear)
    // cameraCvFromWorld: (n·x, −(n·y), n·z) over the pose's axes, in glm::dot's order:
    // lane c of Σ_k n_k · row_k is n·axis_c.
    Double4 n, ng, x, y, z;
    load<&VisibleSurface::ns>(n, v);
    load<&VisibleSurface::n>(ng, v);
    load(x, worldFromCamera[0]);
    load(y, worldFromCamera[1]);
    load(z, worldFromCamera[2]);
    const Double4 r0 = {x[0], y[0], z[0], 0.0}, r1 = {x[1], y[1], z[1], 0.0},
                  r2 = {x[2], y[2], z[2], 0.0}, sign = {1.0, -1.0, 1.0, 1.0};
    r.normalCam = (n[0] * r0 + n[1] * r1 + n[2] * r2) * sign;
    r.geometricNormalCam = (ng[0] * r0 + ng[1] * r1 + ng[2] * r2) * sign;
  }
  if (albedoChannel_) {
    // r_c·D65/p at each of the sample's wavelengths (the 1/N of the estimate cancels in the
    // ratio), all three c at once; summed over the wavelengths in float (then over the
    // pixel's samples in double). Numerators and the white's denominators: divided in
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
    r.albedo = num;
    r.white = den;
  }
}

// The pending records, in sample order, into the pixel's sums.
[[gnu::always_inline]] inline void AovFilm::sumRecordsBody(AovPixel& px) const {
  const std::size_t idCount = idFilms_.size();
  const glm::dvec3& origin = scene_.renderOrigin();
  const Double4 originLanes = {origin.x, origin.y, origin.z, 0.0};
  for (int i = 0; i < px.pending; ++i) {
    const AovRecord& r = px.records[static_cast<std::size_t>(i)];
    const VisibleSurface& v = r.visible;
    const int shapeHit = v.hit ? v.shape : -1;
    if (idCount > 0) {
      if (shapeHit == px.idShape) {  // the common case: the previous sample's shape again
        for (std::size_t k = 0; k < idCount; ++k)
          if (IdFilm::Slot* slot = px.idSlot[k]) ++slot->count;
      } else {
        const std::uint32_t* entries =
            shapeHit >= 0 ? &idEntries_[static_cast<std::size_t>(shapeHit) * idCount] : nullptr;
        for (std::size_t k = 0; k < idCount; ++k)
          px.idSlot[k] = IdFilm::add(px.ids[k], entries ? entries[k] : 0u);
        px.idShape = shapeHit;
      }
    }
    if (shapeHit < 0) continue;
    if (boundaryChannel_) px.boundary.add(shapeHit, v.distance);
    Double4 p;
    load<&VisibleSurface::p>(p, v);
    px.scalars += Double4{1.0, depthChannel_ ? r.depth : 0.0, static_cast<double>(v.distance),
                          static_cast<double>(v.roughness)};
    if (positionChannel_) px.position += p + originLanes;
    if (normalChannel_) {
      Double4 ns, ng;
      load<&VisibleSurface::ns>(ns, v);
      load<&VisibleSurface::n>(ng, v);
      px.normal += ns;
      px.geometricNormal += ng;
      if (cameraTurns_) {
        px.normalCam += r.normalCam;
        px.geometricNormalCam += r.geometricNormalCam;
      }
    }
    if (albedoChannel_) {
      px.albedo += __builtin_convertvector(r.albedo, Double4);
      px.white += __builtin_convertvector(r.white, Double4);
    }
    if (stagesMotion_) {
      // The hit at each frame's reference time: a static shape's stays where it is; a moving
      // one's is taken to object space at the sample's time and moved to each frame time
      // (the poses at the frame times were computed once, in the constructor). Projected
      // four at a time.
      if (px.motionPending == 4) flushMotion(px);
      const int lane = px.motionPending++;
      const std::size_t shape = static_cast<std::size_t>(shapeHit);
      const bool moves = shapeMoves_[shape];
      px.motionMoves[static_cast<std::size_t>(lane)] = moves;
      if (!moves) {
        for (std::size_t j = 0; j < 3; ++j) {
          px.motion.x[j][lane] = p[0];
          px.motion.y[j][lane] = p[1];
          px.motion.z[j][lane] = p[2];
        }
      } else {
        const glm::dvec3 object = scene_.motion(shapeHit).objectFromWorld(glm::dvec3(v.p), r.time);
        for (std::size_t j = 0; j < 3; ++j) {
          const glm::dvec3 at(shapeAt_[shape][j] * glm::dvec4(object, 1.0));
          px.motion.x[j][lane] = at.x;
          px.motion.y[j][lane] = at.y;
          px.motion.z[j][lane] = at.z;
        }
      }
    }
  }
  px.pending = 0;
}

void AovFilm::sumRecordsPortable(AovPixel& px) const {
  sumRecordsBody(px);
}

#if CAMSIM_SIMD_X86
CAMSIM_TARGET_AVX2 void AovFilm::sumRecordsAvx2(AovPixel& px) const {
  sumRecordsBody(px);
}
#else
void AovFilm::sumRecordsAvx2(AovPixel& px) const {
  sumRecordsBody(px);
}
#endif

void AovFilm::addSamplePortable(AovPixel& px, const AovSample& sample) const {
  addSampleBody(px, sample);
}

#if CAMSIM_SIMD_X86
CAMSIM_TARGET_AVX2 void AovFilm::addSampleAvx2(AovPixel& px, const AovSample& sample) const {
  addSampleBody(px, sample);
}
#else
void AovFilm::addSampleAvx2(AovPixel& px, const AovSample& sample) const {
  addSampleBody(px, sample);
}
#endif

void AovFilm::flushMotion(AovPixel& px) const {
  if (px.motionPending == 0) return;
  if (occlusion_) occlusion_->add(px.motion, px.motionPending, px.occlusion);
  Long4 front{};
  if (motionChannel_)
    projector_->addMotionVectors(px.motion, px.motionPending, px.motionLanes, front);
  // Scene flow: +0 for a static shape's hit, so only the moving ones are summed (rare).
  if (motionChannel_ && px.motionMoves != std::array<bool, 4>{}) {
    const PosePoints& a = px.motion;
    for (int lane = 0; lane < px.motionPending; ++lane) {
      if (!front[lane] || !px.motionMoves[static_cast<std::size_t>(lane)]) continue;
      px.flow[0] += a.x[2][lane] - a.x[1][lane];
      px.flow[1] += a.y[2][lane] - a.y[1][lane];
      px.flow[2] += a.z[2][lane] - a.z[1][lane];
      px.flow[3] += a.x[0][lane] - a.x[1][lane];
      px.flow[4] += a.y[0][lane] - a.y[1][lane];
      px.flow[5] += a.z[0][lane] - a.z[1][lane];
    }
  }
  px.motionPending = 0;
  px.motionMoves = {};
}

}  // namespace camsim
