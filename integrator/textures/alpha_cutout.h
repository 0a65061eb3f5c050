// AlphaCutout: a mesh's alpha cut-out (glTF alphaMode MASK) as the HitFilter Embree asks
// about every candidate hit (integrator/geometry/hit_filter.h): where the surface's alpha
// is below the cutoff there is no surface, for camera, bounce and shadow rays alike.
//
// | parameter | unit | default | meaning |
// |-----------|------|---------|---------|
// | alpha     | —    | 1       | a scalar texture (image channel, checkerboard or constant) |
// | factor    | —    | 1       | multiplies the texel (glTF: the base colour factor's alpha) |
// | cutoff    | —    | 0.5     | glTF alphaCutoff |
//
//   opaque(prim, b1, b2)  ⇔  factor · alpha(uv) ≥ cutoff,  uv = the mesh's texture
//   coordinates at the hit (TriangleMesh::uvAt: the same uv shading sees)
// A pure function of the hit: deterministic, and safe on every thread (textures are
// read-only).
#pragma once

#include <memory>

#include "integrator/geometry/hit_filter.h"
#include "integrator/geometry/triangle_mesh.h"
#include "integrator/textures/texture.h"

namespace camsim {

class AlphaCutout final : public HitFilter {
 public:
  // mesh: the triangles Embree reports (for instances, the shared object-space mesh; its
  // texture coordinates are the instances' too); it must outlive the filter. alpha may be
  // shared with other cut-outs of the same material (a Scene keeps it across rebuilds of
  // its meshes, so that the texture is not read again).
  AlphaCutout(const TriangleMesh& mesh, std::shared_ptr<const FloatTexture> alpha, float factor,
              float cutoff)
      : mesh_(mesh), alpha_(std::move(alpha)), factor_(factor), cutoff_(cutoff) {}

  bool opaque(int prim, float b1, float b2) const override {
    const glm::vec2 uv = mesh_.uvAt(static_cast<size_t>(prim), b1, b2);
    return factor_ * alpha_->evaluate(uv) >= cutoff_;
  }

 private:
  const TriangleMesh& mesh_;
  std::shared_ptr<const FloatTexture> alpha_;
  float factor_, cutoff_;
};

}  // namespace camsim
