// Building a Scene's shapes over a motion span (scene_shapes.h).
#include "integrator/scene/scene_shapes.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/gtc/matrix_inverse.hpp>

#include "integrator/geometry/mesh_instance.h"
#include "integrator/geometry/sphere.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace {

// Time steps for a moving shape: linear interpolation between steps must follow the
// keyframed rotation closely (≤ 2° per step: chord error < 1.6e-4 of the radius) and
// must not skip keyframes (≥ 4 steps per key interval inside the span). At most 129, Embree's
// RTC_MAX_TIME_STEP_COUNT (more fails in rtcSetGeometryTimeStepCount).
int timeStepsFor(const RigidMotion& motion, double t0, double t1) {
  const double degrees = motion.rotationAngleDuring(t0, t1) * 180.0 / M_PI;
  int keysInside = 0;
  for (const Keyframe& k : motion.keys()) keysInside += (k.time > t0 && k.time < t1) ? 1 : 0;
  const int steps = 1 + std::max(static_cast<int>(std::ceil(degrees / 2.0)), 4 * (keysInside + 1));
  return std::clamp(steps, 2, 129);
}

// A mesh (object space) placed by `placement` and then the shape's motion: baked into a
// TriangleMesh of its own (its stored pose in render space).
std::unique_ptr<Shape> bakeMesh(const ShapeDescription& s, const MeshData& mesh,
                                const glm::dmat4& placement, TimeSteps steps,
                                const std::vector<glm::dmat4>& poses) {
  // A mesh stores one pose: the reference of its instance motion (Shape), or its only one.
  InstanceMotion instance = InstanceMotion::fromPoses(poses);
  const glm::dmat4& reference = poses[static_cast<size_t>(instance.reference)];
  const glm::dmat4 m = reference * placement;  // exactly `reference` for the identity
  std::vector<glm::vec3> positions;
  positions.reserve(mesh.positions.size() + TriangleMesh::kSpareVertices);
  for (const glm::vec3& v : mesh.positions)
    positions.emplace_back(m * glm::dvec4(glm::dvec3(v), 1.0));
  std::vector<glm::vec3> normals;
  // Normals by the placement's inverse transpose (exactly the identity for none), then the
  // motion's similarity (renormalised below).
  const glm::dmat3 normalMatrix =
      glm::dmat3(reference) * glm::inverseTranspose(glm::dmat3(placement));
  for (const glm::vec3& n : mesh.normals)
    normals.emplace_back(glm::normalize(normalMatrix * glm::dvec3(n)));
  // Tangents by the linear part (they lie in the surface), renormalised; a mirroring
  // placement flips the bitangent's side (w).
  const glm::dmat3 linear(m);
  const double handedness = glm::determinant(glm::dmat3(placement)) < 0.0 ? -1.0 : 1.0;
  std::vector<glm::vec4> tangents;
  for (const glm::vec4& t : mesh.tangents) {
    const glm::dvec3 turned = linear * glm::dvec3(t);
    const double len = glm::length(turned);
    tangents.emplace_back(glm::vec3(len > 0.0 ? turned / len : turned),
                          static_cast<float>(handedness * static_cast<double>(t.w)));
  }
  std::vector<std::uint32_t> indices;
  indices.reserve(mesh.indices.size() + TriangleMesh::kSpareIndices);
  indices.assign(mesh.indices.begin(), mesh.indices.end());
  return std::make_unique<TriangleMesh>(std::move(positions), std::move(normals),
                                        std::move(indices), steps, mesh.uvs, s.emission.has_value(),
                                        std::move(instance), std::move(tangents));
}

// Largest |coordinate| of a mesh's vertices (m), once per mesh however often it is placed.
double largestCoordinate(const MeshData& mesh, std::map<const MeshData*, double>& memo) {
  const auto [it, added] = memo.emplace(&mesh, 0.0);
  if (added)
    for (const glm::vec3& p : mesh.positions)
      it->second =
          std::max({it->second, std::abs(static_cast<double>(p.x)),
                    std::abs(static_cast<double>(p.y)), std::abs(static_cast<double>(p.z))});
  return it->second;
}

// A shape must stay within ±SceneLimits::kMaxCoordinate of the render origin at every
// step of its motion (Embree drops geometry past ±1.8e18 and refuses rays from it), and a
// sphere's radius times its keyframe scale within [kMinSphereRadius, 1e12] m. Mesh files,
// glTF nodes, placements and keyframe scales reach past what the loader checks point by
// point; the bound |A v + t|∞ ≤ ‖A‖∞ max|v| + |t|∞ is worked out in double per step.
void checkReach(const SceneDescription& d, const ShapeDescription& s,
                const std::vector<glm::dmat4>& transforms, double meshReach) {
  for (const glm::dmat4& m : transforms) {
    double reach = 0.0;
    for (int r = 0; r < 3; ++r) {
      const double row = std::abs(m[0][r]) + std::abs(m[1][r]) + std::abs(m[2][r]);
      const double centre = s.kind == ShapeDescription::Kind::kSphere
                                ? std::abs((m * glm::dvec4(glm::dvec3(s.centre), 1.0))[r])
                                : std::abs(m[3][r]);
      reach = std::max(reach, s.kind == ShapeDescription::Kind::kSphere
                                  ? centre + row * static_cast<double>(s.radius)
                                  : centre + row * meshReach);
    }
    if (!(reach <= SceneLimits::kMaxCoordinate))
      throw shapeError(d, s,
                       "the shape reaches " + formatNumber(reach) +
                           " m from the camera's rest position; camsim traces within ±1e15 m "
                           "(limit SceneLimits::kMaxCoordinate)");
    if (s.kind == ShapeDescription::Kind::kSphere) {
      // Compared as the float the shape stores: the loader's smallest radius, 1e-9 m, is
      // the float 9.99999972e-10 (below 1e-9 as a double), and must still build.
      const double radius = glm::length(glm::dvec3(m[0])) * static_cast<double>(s.radius);
      const auto stored = static_cast<float>(radius);
      if (!(stored >= static_cast<float>(SceneLimits::kMinSphereRadius) && radius <= 1e12))
        throw shapeError(d, s,
                         "the sphere's radius times its keyframe scale is " + formatNumber(radius) +
                             " m, outside [1e-09, 1e+12] m");
    }
  }
}

}  // namespace

InputError shapeError(const SceneDescription& d, const ShapeDescription& s,
                      const std::string& message) {
  if (s.where.file.empty()) return InputError({d.sourceFile, 0, 0}, s.label, message);
  return InputError(s.where, s.key, s.label == s.key ? message : "'" + s.label + "': " + message);
}

void checkPlacement(const SceneDescription& d, const ShapeDescription& s) {
  const double det = glm::determinant(glm::dmat3(s.placement));
  bool finite = std::isfinite(det);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) finite = finite && std::isfinite(s.placement[c][r]);
  if (!finite || det == 0.0)
    throw shapeError(d, s, "the instance's placement matrix is singular or not finite");
}

std::shared_ptr<const TriangleMesh> objectMesh(const MeshData& mesh) {
  std::vector<glm::vec3> positions;
  positions.reserve(mesh.positions.size() + TriangleMesh::kSpareVertices);
  positions.assign(mesh.positions.begin(), mesh.positions.end());
  std::vector<glm::vec3> normals;
  for (const glm::vec3& n : mesh.normals) normals.emplace_back(glm::normalize(glm::dvec3(n)));
  std::vector<std::uint32_t> indices;
  indices.reserve(mesh.indices.size() + TriangleMesh::kSpareIndices);
  indices.assign(mesh.indices.begin(), mesh.indices.end());
  return std::make_shared<const TriangleMesh>(std::move(positions), std::move(normals),
                                              std::move(indices), TimeSteps{}, mesh.uvs, false,
                                              InstanceMotion{}, mesh.tangents);
}

std::unique_ptr<Shape> buildShape(const SceneDescription& d, const ShapeDescription& s, double t0,
                                  double t1, const std::shared_ptr<const TriangleMesh>& instanced,
                                  std::map<const MeshData*, double>& meshReach, bool& moving) {
  moving = !s.motion.empty() && !s.motion.isStaticDuring(t0, t1);
  TimeSteps steps{t0, t1, moving ? timeStepsFor(s.motion, t0, t1) : 1};
  auto transformAt = [&](int k) {
    return s.motion.empty() ? glm::dmat4(1.0) : s.motion.at(steps.timeOf(k));
  };
  if (s.kind == ShapeDescription::Kind::kSphere) {
    std::vector<glm::dmat4> transforms;
    for (int k = 0; k < steps.count; ++k) transforms.push_back(transformAt(k));
    checkReach(d, s, transforms, 0.0);
    std::vector<glm::vec3> centres;
    std::vector<float> radii;
    for (int k = 0; k < steps.count; ++k) {
      const glm::dmat4 m = transformAt(k);
      centres.emplace_back(m * glm::dvec4(glm::dvec3(s.centre), 1.0));
      radii.push_back(
          static_cast<float>(glm::length(glm::dvec3(m[0])) * static_cast<double>(s.radius)));
    }
    return std::make_unique<Sphere>(std::move(centres), std::move(radii), steps);
  }
  std::vector<glm::dmat4> poses;
  for (int k = 0; k < steps.count; ++k) poses.push_back(transformAt(k));
  std::vector<glm::dmat4> placed = poses;  // mesh data → render space at each step
  if (s.sharedMesh)
    for (glm::dmat4& pose : placed) pose = pose * s.placement;
  checkReach(d, s, placed, largestCoordinate(s.sharedMesh ? *s.sharedMesh : s.mesh, meshReach));
  if (!s.sharedMesh) return bakeMesh(s, s.mesh, glm::dmat4(1.0), steps, poses);
  if (!instanced) return bakeMesh(s, *s.sharedMesh, s.placement, steps, poses);
  for (glm::dmat4& pose : poses) pose = pose * s.placement;  // object → render at each step
  return std::make_unique<MeshInstance>(instanced, poses, steps, s.emission.has_value());
}

namespace {

// One transform Embree moves rays by (see checkInstanceRanges): its linear part must invert
// in float (|det A| ≥ kMinInstanceDeterminant: Embree inverts in single precision through the
// determinant, and past FLT_MIN the instance silently vanishes) and keep every ray inside
// Embree's range. label: the shape's key; when: "" or " at its keyframe at t = … s".
void checkInstanceTransform(const SceneDescription& d, const std::string& label,
                            const glm::dmat4& x, double reach, const std::string& when) {
  const glm::dmat3 a{x};
  const double det = glm::determinant(a);
  const glm::dmat3 inv = glm::inverse(a);
  double norm = 0.0;  // ‖A⁻¹‖∞, the largest row sum: about 1 / the smallest scale
  for (int r = 0; r < 3; ++r)
    norm = std::max(norm, std::abs(inv[0][r]) + std::abs(inv[1][r]) + std::abs(inv[2][r]));
  const double t = std::max({std::abs(x[3][0]), std::abs(x[3][1]), std::abs(x[3][2])});
  const double far = 2.0 * norm * (reach + t);  // origin and direction (|d| ≤ 2 R) there
  if (std::isfinite(det) && std::abs(det) >= kMinInstanceDeterminant && std::isfinite(far) &&
      far <= kMaxInstanceReach)
    return;
  throw InputError(
      {d.sourceFile, 0, 0}, label,
      "a keyframe or placement scale too small for the tracer" + when +
          ": it scales the shape by about " + formatNumber(norm > 0.0 ? 1.0 / norm : 0.0) +
          " (relative to its largest keyframe scale, for a moving mesh), and a "
          "transform must keep |det| ≥ " +
          formatNumber(kMinInstanceDeterminant) +
          " (a uniform scale of at least 1e-10) and, in a scene reaching " + formatNumber(reach) +
          " m (shapes, lights, camera), keep rays within " + formatNumber(kMaxInstanceReach) +
          " m in the shape's own space (limits kMinInstanceDeterminant, "
          "kMaxInstanceReach)");
}

}  // namespace

void checkInstanceRanges(const SceneDescription& d,
                         const std::vector<std::unique_ptr<Shape>>& shapes, glm::vec3 lower,
                         glm::vec3 upper) {
  // Every ray starts within the geometry's bounds, at the camera or towards a point or spot
  // light (a shadow ray's direction is as long as the way to the light).
  double reach = 1.0;
  const auto extend = [&](const glm::dvec3& p) {
    reach = std::max({reach, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  };
  if (lower.x <= upper.x) {
    extend(glm::dvec3(lower));
    extend(glm::dvec3(upper));
  }
  for (const LightDescription& l : d.lights) extend(glm::dvec3(l.position));
  for (const Keyframe& k : d.camera.motion.keys()) extend(k.translate);
  for (size_t i = 0; i < shapes.size() && i < d.shapes.size(); ++i) {
    const ShapeDescription& s = d.shapes[i];
    // What Embree gets for this exposure window.
    std::vector<glm::mat4> transforms = shapes[i]->instanceMotion().steps;
    const auto* instance = dynamic_cast<const MeshInstance*>(shapes[i].get());
    if (instance && transforms.empty()) transforms.push_back(instance->placement());
    for (const glm::mat4& x : transforms)
      checkInstanceTransform(d, s.label, glm::dmat4(x), reach, "");
    // And what it could get for any other window (a sequence's later frame, a re-exposed
    // bracket): an instance at each keyframe; a moving mesh baked at one keyframe's pose and
    // moved to another's. Checked at the first build, before anything is written.
    if (s.kind != ShapeDescription::Kind::kMesh || s.motion.empty()) continue;
    const std::vector<Keyframe>& keys = s.motion.keys();
    for (const Keyframe& k : keys) {
      const glm::dmat4 pose = s.motion.at(k.time);
      const std::string when = " at its keyframe at t = " + formatNumber(k.time) + " s";
      if (instance) {
        checkInstanceTransform(d, s.label, pose * s.placement, reach, when);
        continue;
      }
      for (const Keyframe& other : keys)  // baked at a pose of a larger scale (motion.h)
        if (other.scale >= k.scale)
          checkInstanceTransform(d, s.label, pose * glm::inverse(s.motion.at(other.time)), reach,
                                 when);
    }
  }
}

}  // namespace camsim
