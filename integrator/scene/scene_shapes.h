// A Scene's shapes built from their descriptions over a motion span (Scene::buildShapes):
// keyframed motion sampled into Embree time steps (finer where the shape turns faster),
// meshes baked into render space or placed as instances of one shared object-space mesh,
// and the checks that only a built shape can make (placement, reach, a sphere's radius).
// What is built depends on the span [t0, t1] (s) only through the motion's time steps, so
// a Scene whose exposure window moves rebuilds its shapes here from the same descriptions.
#pragma once

#include <map>
#include <memory>
#include <vector>

#include "integrator/geometry/shape.h"
#include "integrator/geometry/triangle_mesh.h"
#include "integrator/scene/scene_description.h"

namespace camsim {

// The placement of an instanced mesh, which must be invertible (an InputError names the
// shape otherwise: descriptions built in code are not checked by the loader).
void checkPlacement(const SceneDescription& d, const ShapeDescription& s);

// The InputError of a problem with shape s found after loading: at s.where, key s.key (the
// label first in the message when it is not the key); for a shape built in code, the scene
// file and the label.
InputError shapeError(const SceneDescription& d, const ShapeDescription& s,
                      const std::string& message);

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

// After the shapes' BVH is built, with its bounds [lower, upper] (render space, m; lower >
// upper for no geometry): every transform Embree moves rays by (a moving mesh's time steps,
// an instance's placement; and, for any exposure window, those at the shape's keyframes)
// must be one Embree can invert and trace through. Embree inverts it in float through its
// determinant (below FLT_MIN the instance silently vanishes: |det A| ≥
// kMinInstanceDeterminant) and refuses (asserts on) a ray whose origin or direction in the
// shape's space passes ±1.8e18; rays start within the bounds, at the camera, or head for a
// point or spot light (a shadow ray's direction is as long as the way there), so
// 2 ‖A⁻¹‖∞ (R + |t|∞) ≤ kMaxInstanceReach, R the largest coordinate of those (at least 1 m),
// A the linear part and t the translation. The margin of 1e16 against 1.8e18 covers the
// transforms Embree interpolates between time steps. An InputError names the shape.
void checkInstanceRanges(const SceneDescription& d,
                         const std::vector<std::unique_ptr<Shape>>& shapes, glm::vec3 lower,
                         glm::vec3 upper);
inline constexpr double kMaxInstanceReach = 1e16;         // m in a shape's own space
inline constexpr double kMinInstanceDeterminant = 1e-30;  // |det| of a transform's linear part

}  // namespace camsim
