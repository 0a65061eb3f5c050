// MaskFilm: the `amodal` aov — for every labelled shape (one with a `class:`; n its instance
// number, shape index + 1, scene_ids.h) its amodal and its visible mask, as coverages from
// the image's own camera samples (the same film point, lens point, time and wavelengths):
//
// | channel         | unit | meaning |
// |-----------------|------|---------|
// | amodal_<n>.A    | —    | fraction of the pixel's camera samples whose ray passes through shape n anywhere, as if nothing else were in the scene: its amodal mask |
// | visible_<n>.A   | —    | fraction whose first hit is on shape n: its visible mask (the instance matte's coverage of n) |
//
//   amodal_n(p)  = (1/S) Σ_s [camera ray s crosses shape n]
//   visible_n(p) = (1/S) Σ_s [camera ray s first hits shape n]      (0 ≤ visible ≤ amodal ≤ 1)
//
// S counts every sample of the pixel (a film point with no camera ray counts as a miss), so
// both are box-filtered coverages over the photosite, the shutter and the lens, as the ID
// mattes: ramps at blurred edges, exact in expectation. Crossings come from one traversal
// per sample of a second BVH holding the labelled shapes only (Scene::labelledGeometry,
// EmbreeScene::crossedShapes): the cost grows with how many labelled shapes a ray passes
// near, not with the whole scene. A ray passing through more than kMaxCrossings labelled
// shapes counts the first kMaxCrossings traversal meets.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "integrator/geometry/ray.h"
#include "integrator/scene/scene.h"

namespace camsim {

class MaskFilm {
 public:
  static constexpr int kMaxCrossings = 64;

  // One pixel's sample counts per labelled shape (in the film's order of them).
  struct Counts {
    std::vector<std::uint32_t> amodal, visible;
  };

  // The scene must have been built with the amodal aov (Scene::labelledGeometry()).
  explicit MaskFilm(const Scene& scene);

  // amodal_<n>.A for every labelled shape, then visible_<n>.A, each in shape order.
  std::vector<std::string> channels() const;
  // Counts for a pixel's samples, all 0.
  Counts emptyCounts() const {
    return {std::vector<std::uint32_t>(shapes_.size(), 0u),
            std::vector<std::uint32_t>(shapes_.size(), 0u)};
  }
  static void clear(Counts& c);
  // One camera sample: its ray (null: no camera ray) and the shape its first hit is on (−1:
  // none).
  void add(Counts& c, const Ray* cameraRay, int firstHitShape) const;
  // The pixel's channels (channels().size() floats) at out.
  void write(const Counts& c, int samplesPerPixel, float* out) const;

 private:
  const EmbreeScene& crossings_;
  std::vector<int> shapes_;       // the labelled shapes' indices, in order
  std::vector<int> slotOfShape_;  // per shape: its place in shapes_ (−1: unlabelled)
};

}  // namespace camsim
