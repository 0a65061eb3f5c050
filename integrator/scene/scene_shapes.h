// A Scene's shapes built from their descriptions over a motion span (Scene::buildShapes):
// keyframed motion sampled into Embree time steps (finer where the shape turns faster),
// meshes baked into render space or placed as instances of one shared object-space mesh,
// and the checks that only a built shape can make (placement, reach, a sphere's radius).
// What is built depends on the span [t0, t1] (s) only through the motion's time steps, so
// a Scene whose exposure window moves rebuilds its shapes here from the same descriptions.
#pragma once

#include <map>
#include <memory>

#include "integrator/geometry/shape.h"
#include "integrator/geometry/triangle_mesh.h"
#include "integrator/scene/scene_description.h"

namespace camsim {

// The placement of an instanced mesh, which must be invertible (an InputError names the
// shape otherwise: descriptions built in code are not checked by the loader).
void checkPlacement(const SceneDescription& d, const ShapeDescription& s);

// One shared object-space mesh per MeshData that several shapes place: static, sampled by
// no light (emitting instances sample their own placed areas).
std::shared_ptr<const TriangleMesh> objectMesh(const MeshData& mesh);

// Shape s over [t0, t1]; moving: whether its motion moves it during the span. instanced:
// the shared object mesh when s is placed as an instance of it (else null). meshReach
// memoises each mesh's largest coordinate. Throws InputError naming the shape when it
// reaches past SceneLimits::kMaxCoordinate or a sphere's scaled radius leaves [1e-9, 1e12] m.
std::unique_ptr<Shape> buildShape(const SceneDescription& d, const ShapeDescription& s, double t0,
                                  double t1, const std::shared_ptr<const TriangleMesh>& instanced,
                                  std::map<const MeshData*, double>& meshReach, bool& moving);

}  // namespace camsim
