// HitFilter: a surface with holes. EmbreeScene asks a shape's filter about every candidate
// hit on it, for closest-hit and occlusion rays alike (Embree's intersection and occlusion
// filter functions); a hit the filter calls not opaque is skipped and traversal goes on, so
// camera rays, bounces and shadow rays all see through the same holes.
//
// What decides is left to the implementation (an alpha cut-out: factor · texel < cutoff,
// integrator/textures/alpha_cutout.h): geometry may not know materials or textures. It must
// be a pure function of its arguments (the same answer on every thread and every call), so
// that renders stay deterministic, and safe to call from many threads at once.
#pragma once

namespace camsim {

class HitFilter {
 public:
  virtual ~HitFilter() = default;
  // Whether triangle `prim` is there at Embree's barycentrics (b1, b2) (Hit::u, Hit::v;
  // the point b0·p0 + b1·p1 + b2·p2 with b0 = 1 − b1 − b2).
  virtual bool opaque(int prim, float b1, float b2) const = 0;
};

}  // namespace camsim
