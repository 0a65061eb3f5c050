// MeshInstance: one placement of a shared mesh. The geometry, a static TriangleMesh in its
// own object space, is stored once however many instances place it (with one Embree BVH,
// EmbreeScene); an instance holds a pointer to it and its placement M, object → render
// space (m):
//   static:  M = [A | t], any invertible affine A (rotation, non-uniform scale, shear,
//            mirroring)
//   moving:  one M_k per uniform time step (the keyframed motion at step k's time times the
//            placement), interpolated linearly between steps exactly as Embree interpolates
//            the instance transforms it traces
//
//   p  = M·p_obj, p_obj = b0·p0 + b1·p1 + b2·p2 (the mesh's own point in object space)
//   n  = normalize(cof(A)·n_obj), cof(A) = det(A)·A⁻ᵀ: the direction of the placed
//        triangle's (M p1 − M p0) × (M p2 − M p0), so that the front is the counter-clockwise
//        side in render space, as for the same triangles baked into a TriangleMesh (a
//        mirroring placement flips the object's front, as baking it does)
//   ns = normalize(Σ b_i·normalize(A⁻ᵀ·n_i)) with vertex normals n_i, as a baked copy
//        interpolates its placed normals (normals are covectors: a mirrored outward normal
//        stays outward); for a conformal A (rotation, mirror, uniform scale: the common
//        case) that is normalize(A⁻ᵀ·ns_obj), one transform of the object's interpolated
//        normal. n is then turned to ns's side as TriangleMesh does; without vertex
//        normals ns = n
//   uv = the mesh's (object space)
//   pError = |A|·pError_obj + γ(4)·(|A|·|p_obj| + |t|) (γ(6) moving: the transform's lerp)
//            + InstanceMotion::error(p)·κ, κ = ‖A‖∞·‖A⁻¹‖∞ ≥ 1: Embree moves each ray into
//            object space with M⁻¹, and a stretched instance magnifies that rounding
// Light sampling (an emitting instance): a triangle with probability ∝ its area in render
// space at rest (the first step), area_k = ½·|cof(A)·((p1 − p0) × (p2 − p0))| (under a
// non-uniform scale not proportional to the object's areas), then a uniform point on it
// (uniform on the placed triangle too: M is affine); pdf_area = P(k) / area_k(t), which is
// 1/area for a static instance. No FrontPlane (shape.h): that only skips work.
//
// Memory: a static instance holds sizeof(MeshInstance) bytes (the shared mesh not counted;
// see docs/performance.md for Embree's share); an emitting one adds a per-triangle area
// table (12 B per triangle), a moving one 64 B per time step.
#pragma once

#include <memory>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "integrator/geometry/shape.h"
#include "integrator/geometry/triangle_mesh.h"
#include "integrator/sampling/distribution.h"

namespace camsim {

class MeshInstance final : public Shape {
 public:
  // mesh: static (one time step), object space. poses: object → render space, one per
  // step of `steps` (a static instance: steps.count = 1, one pose), each invertible.
  // samplable: false for an instance no light samples (sample() and pdf() must then not be
  // called).
  MeshInstance(std::shared_ptr<const TriangleMesh> mesh, const std::vector<glm::dmat4>& poses,
               TimeSteps steps, bool samplable = false);

  const std::shared_ptr<const TriangleMesh>& mesh() const { return mesh_; }
  // Object → render space at rest (the first step), as Embree traces a static instance.
  const glm::mat4& placement() const { return placement_; }
  const TimeSteps& timeSteps() const override { return steps_; }
  // A moving instance: steps = the poses M_k (the "reference pose" is the mesh's object
  // space); empty for a static one.
  const InstanceMotion& instanceMotion() const override { return motion_; }

  float area() const override;  // at rest; an instance no light samples sums it on each call
  SurfaceInteraction interaction(const Hit& hit, const Ray& ray) const override;
  // The object mesh's frame carried by the placement's linear part A at si.time (∂p/∂u and
  // ∂p/∂v transform by A, as the baked copy's would).
  std::optional<SurfaceTangents> tangentFrame(const Hit& hit,
                                              const SurfaceInteraction& si) const override;
  std::optional<ShapeSample> sample(const glm::vec3& ref, float u1, glm::vec2 u2,
                                    double time) const override;
  float pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const override;

 private:
  // The placement at `time` and what pointOn derives from it.
  struct Affine {
    glm::mat3 a;    // linear part A
    glm::vec3 t;    // translation (m)
    glm::mat3 cof;  // cofactor matrix det(A)·A⁻ᵀ (geometric normals, areas)
    float sign;     // sign of det(A): cof·sign = |det A|·A⁻ᵀ (shading normals)
  };
  static Affine affineOf(const glm::mat4& m);
  Affine affineAt(double time) const;
  void pointOn(size_t tri, float b1, float b2, double time, float* area,
               SurfaceInteraction& si) const;
  float triangleArea(size_t tri, const glm::mat3& cof) const;  // m²
  float areaPdf(size_t tri, float area) const;

  std::shared_ptr<const TriangleMesh> mesh_;
  glm::mat4 placement_;
  Affine rest_;  // of placement_
  TimeSteps steps_;
  InstanceMotion motion_;
  float kappa_ = 1.0f;     // largest ‖A‖∞·‖A⁻¹‖∞ over the steps
  bool conformal_ = true;  // every step's A a rotation (or mirror) times a uniform scale
  bool samplable_;
  float area_ = 0.0f;                      // at rest; samplable instances only
  DiscreteDistribution areaDistribution_;  // render-space areas at rest; samplable only
};

}  // namespace camsim
