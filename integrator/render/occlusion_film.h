// OcclusionFilm: occlusion-aware flow (aov `occlusion`) and occlusion boundaries (aov
// `boundary`), from the very camera samples the image and the other AOVs use (aov_film.h).
//
// | channel        | unit | meaning |
// |----------------|------|---------|
// | occlusion_fw.A | —    | of the pixel's samples that hit, the fraction whose hit point, at the next frame's reference time t_{k+1}, is imaged inside the image but hidden: the segment from the camera's projection centre at t_{k+1} to the point crosses a surface of the scene as it is at t_{k+1} |
// | occlusion_bw.A | —    | the same at the previous frame's reference time t_{k−1} |
// | outside_fw.A   | —    | of the same samples, the fraction whose point at t_{k+1} is not imaged inside the image: outside [−½, W − ½) × [−½, H − ½) px (OpenCV pixel coordinates), behind the lens, or outside the camera model's domain |
// | outside_bw.A   | —    | the same at t_{k−1} |
// | boundary.A     | —    | 1 on an occlusion boundary (below), else 0 |
//
// The point x_j at t_j is the motion field's (aov motion): the sample's first hit taken
// through its shape's exact keyframed motion to t_j. With o_j the camera's projection
// centre at t_j (the pose's origin: the pinhole, the thin lens's centre) and q_j the image
// of x_j through the camera at t_j (PhysicalCamera::projectFrom):
//
//   outside_j   ⇔  q_j does not exist or lies outside the image
//   occluded_j  ⇔  not outside_j, and a surface at t_j lies on o_j + s (x_j − o_j),
//                  0 < s < 1 − ε
//   visible_j   ⇔  neither:  occlusion + outside + visible = 1 per pixel (disjoint)
//
// ε = 1e-4 (kEndGap): surfaces within 1e-4 of the point's distance in front of it do not
// count (the point's own surface, rounded), so a surface seen nearly edge-on from
// t_j may be reported hidden by itself. The surfaces are the exact geometry at t_j: the
// scene's BVH for shapes without keyframes (alpha cut-outs included), and for shapes with
// keyframes a second BVH of copies placed at t_{k−1} and t_{k+1} through their exact motion
// (a moving shape's cut-out is not applied there: it occludes as opaque). Not a
// forward–backward check of the vectors.
//
// Occlusion boundary (boundary.A = 1) when, among the pixel's samples that have a camera ray,
//   some hit and some miss (an object against the background), or
//   the hits are on more than one shape (instance: an object boundary, even a seamless one), or
//   the hits' distances along their rays span more than τ = 5 % (kDepthStep) of the nearest:
//   d_max − d_min > τ d_min (a depth discontinuity, e.g. a shape hiding part of itself; a
//   plane is marked only where it is seen within ≈ 1.1° of edge-on at 1 mrad per pixel;
//   docs/output.md, "Occlusion and occlusion boundaries", for a sphere's limb).
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/camera/pose_projector.h"
#include "integrator/geometry/embree_scene.h"
#include "integrator/geometry/shape.h"

namespace camsim {

class Scene;

// A pixel's occlusion counts: its hitting samples and, of them, how many are occluded at
// the next / previous frame and outside its image.
struct OcclusionSums {
  int samples = 0;
  std::array<int, 4> counts{};  // occluded fw, occluded bw, outside fw, outside bw
};

// A pixel's hits for its boundary value: the shapes and the distances seen.
struct BoundarySums {
  static constexpr double kDepthStep = 0.05;  // τ, relative
  int shape = -1;                             // the first hit's shape (−1: none yet)
  bool severalShapes = false;                 // a hit on another shape
  float nearest = std::numeric_limits<float>::infinity(), farthest = 0.0f;  // m
  void add(int hitShape, float distance) {
    if (shape < 0) shape = hitShape;
    severalShapes |= hitShape != shape;
    nearest = distance < nearest ? distance : nearest;
    farthest = distance > farthest ? distance : farthest;
  }
  // 1 on a boundary, else 0; hits and misses: the pixel's samples that hit and that had a
  // camera ray and missed.
  float value(int hits, int misses) const {
    if (hits == 0) return 0.0f;
    const double d0 = static_cast<double>(nearest), d1 = static_cast<double>(farthest);
    const bool step = d1 - d0 > kDepthStep * d0;
    return misses > 0 || severalShapes || step ? 1.0f : 0.0f;
  }
};

class OcclusionFilm {
 public:
  static constexpr double kEndGap = 1e-4;  // ε
  // The scene at the three frame times (previous, this, next; s) with the camera's pose at
  // each (render space): copies of the shapes with keyframes are placed at times[0] and
  // times[2] (their memory: a moving mesh's positions once more).
  OcclusionFilm(const Scene& scene, const std::array<double, 3>& times,
                const std::array<glm::dmat4, 3>& worldFromCamera);
  ~OcclusionFilm();

  static std::vector<std::string> channels() {
    return {"occlusion_fw.A", "occlusion_bw.A", "outside_fw.A", "outside_bw.A"};
  }
  // Adds the first `lanes` samples of `p` (each one's hit at the three times) to `sums`.
  void add(const PosePoints& p, int lanes, OcclusionSums& sums) const;
  // The four fractions (0 for a pixel no sample hit).
  static void write(const OcclusionSums& sums, float* o);

 private:
  enum class Seen { kVisible, kOccluded, kOutside };
  Seen classify(const glm::dvec3& x, std::size_t j) const;  // the point x at times_[j]
  bool hidden(const Ray& ray) const;                        // a surface on the segment

  const Scene& scene_;
  std::array<double, 3> times_;
  std::array<glm::dmat4, 3> worldFromCamera_;
  glm::dvec2 imageEnd_{0.0};     // (W − ½, H − ½) px
  std::vector<char> keyframed_;  // per shape: it has keyframes (the scene's BVH skips it)
  bool anyKeyframed_ = false;
  std::vector<std::unique_ptr<Shape>> movedShapes_;  // the keyframed shapes' copies
  std::unique_ptr<EmbreeScene> moved_;               // their BVH over [times[0], times[2]]
};

}  // namespace camsim
