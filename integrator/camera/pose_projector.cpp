#include "integrator/camera/pose_projector.h"

namespace camsim {
namespace {

// The kernel, written once: with CAMSIM_SIMD_X86 it also has a copy compiled for AVX2
// (always_inline, so that copy runs AVX code throughout). No FMA contraction happens
// (neither the baseline nor the AVX2 target enables FMA), so both copies give the same bits.
// Images per pose, then the lanes to add: in front at every pose and among the first
// `lanes`; the others are masked to +0, which adds nothing.
[[gnu::always_inline]] inline void addLanes(const std::array<PoseProjector::Pose, 3>& poses,
                                            const double* k, const PosePoints& p, int lanes,
                                            MotionVectorSums& sums, Long4& front) {
  Long4 use = Long4{0, 1, 2, 3} < lanes;
  Double4 u[3], v[3];
  for (std::size_t j = 0; j < 3; ++j) {
    const PoseProjector::Pose& m = poses[j];
    // v = p − o; c = (v·x, −(v·y), v·z) with glm::dot's order (x, then y, then z).
    const Double4 dx = p.x[j] - m.o[0], dy = p.y[j] - m.o[1], dz = p.z[j] - m.o[2];
    const Double4 c0 = dx * m.x[0] + dy * m.x[1] + dz * m.x[2];
    const Double4 c1 = -(dx * m.y[0] + dy * m.y[1] + dz * m.y[2]);
    const Double4 c2 = dx * m.z[0] + dy * m.z[1] + dz * m.z[2];
    use &= c2 > 0.0;
    u[j] = k[0] * (c0 / c2) + k[2];
    v[j] = k[1] * (c1 / c2) + k[3];
  }
  // x & use, bit for bit (no function: a Double4 by value changes the ABI without AVX).
  const Double4 one = {1.0, 1.0, 1.0, 1.0}, fwx = u[2] - u[1], fwy = v[2] - v[1], bwx = u[0] - u[1],
                bwy = v[0] - v[1];
  sums.count += __builtin_bit_cast(Double4, __builtin_bit_cast(Long4, one) & use);
  sums.fwx += __builtin_bit_cast(Double4, __builtin_bit_cast(Long4, fwx) & use);
  sums.fwy += __builtin_bit_cast(Double4, __builtin_bit_cast(Long4, fwy) & use);
  sums.bwx += __builtin_bit_cast(Double4, __builtin_bit_cast(Long4, bwx) & use);
  sums.bwy += __builtin_bit_cast(Double4, __builtin_bit_cast(Long4, bwy) & use);
  front = use;
}

void addPortable(const std::array<PoseProjector::Pose, 3>& poses, const double* k,
                 const PosePoints& p, int lanes, MotionVectorSums& sums, Long4& front) {
  addLanes(poses, k, p, lanes, sums, front);
}

#if CAMSIM_SIMD_X86
CAMSIM_TARGET_AVX2 void addAvx2(const std::array<PoseProjector::Pose, 3>& poses, const double* k,
                                const PosePoints& p, int lanes, MotionVectorSums& sums,
                                Long4& front) {
  addLanes(poses, k, p, lanes, sums, front);
}
#endif

}  // namespace

PoseProjector::PoseProjector(const PhysicalCamera& camera,
                             const std::array<glm::dmat4, 3>& worldFromCamera)
    : camera_(&camera), poses_(worldFromCamera), avx2_(simd::cpuHasAvx2()) {
  for (std::size_t j = 0; j < 3; ++j) {
    const glm::dmat4& m = worldFromCamera[j];
    for (int i = 0; i < 3; ++i) {
      pose_[j].o[i] = m[3][i];
      pose_[j].x[i] = m[0][i];
      pose_[j].y[i] = m[1][i];
      pose_[j].z[i] = m[2][i];
    }
  }
  const glm::dvec4& k = camera.intrinsics();
  k_[0] = k.x;
  k_[1] = k.y;
  k_[2] = k.z;
  k_[3] = k.w;
}

void PoseProjector::addMotionVectors(const PosePoints& p, int lanes, MotionVectorSums& sums,
                                     Long4& front) const {
  if (!camera_->idealPinhole()) {  // the scalar reference: the camera model per point
    front = Long4{};
    for (int lane = 0; lane < lanes; ++lane) {
      std::array<glm::dvec2, 3> q;
      bool inFront = true;
      for (std::size_t j = 0; j < 3 && inFront; ++j) {
        const std::optional<glm::dvec2> r =
            camera_->projectFrom(poses_[j], glm::dvec3(p.x[j][lane], p.y[j][lane], p.z[j][lane]));
        inFront = r.has_value();
        if (inFront) q[j] = *r;
      }
      if (!inFront) continue;
      front[lane] = -1;
      sums.count[lane] += 1.0;
      sums.fwx[lane] += q[2].x - q[1].x;
      sums.fwy[lane] += q[2].y - q[1].y;
      sums.bwx[lane] += q[0].x - q[1].x;
      sums.bwy[lane] += q[0].y - q[1].y;
    }
    return;
  }
#if CAMSIM_SIMD_X86
  if (avx2_) {
    addAvx2(pose_, k_, p, lanes, sums, front);
    return;
  }
#endif
  addPortable(pose_, k_, p, lanes, sums, front);
}

}  // namespace camsim
