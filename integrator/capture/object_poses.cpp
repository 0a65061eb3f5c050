// Object poses and models (object_poses.h): the placement's 3×3 part split into a rotation
// and the rest (its polar decomposition), the rest baked into the model.
#include "integrator/capture/object_poses.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include "integrator/scene/scene_ids.h"
#include "sensor/base/check.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace {

constexpr int kModelSphereSegments = 32;  // the sphere model's longitudes
constexpr int kModelSphereRings = 16;     // and latitudes

// L = R · S with R a proper rotation (det +1) and S = Rᵀ L (symmetric positive definite, or
// with a point reflection when L mirrors): Higham's iteration X ← (X + X⁻ᵀ) / 2, which
// converges quadratically to the orthogonal polar factor.
glm::dmat3 rotationOf(const glm::dmat3& linear) {
  glm::dmat3 x = linear;
  for (int i = 0; i < 64; ++i) {
    const glm::dmat3 next = 0.5 * (x + glm::transpose(glm::inverse(x)));
    double change = 0.0;
    for (int c = 0; c < 3; ++c) change = std::max(change, glm::length(next[c] - x[c]));
    x = next;
    if (change < 1e-15) break;
  }
  return glm::determinant(x) < 0.0 ? -x : x;
}

// The affine map (object or render space) ← the shape's raw model coordinates, without the
// motion: an instance's placement, then the model frame's own offset.
glm::dmat4 placedFromModel(const ShapeDescription& s) {
  if (s.kind == ShapeDescription::Kind::kSphere)
    return glm::translate(glm::dmat4(1.0), glm::dvec3(s.centre));
  return s.sharedMesh ? s.placement * s.objectFromModel : s.objectFromModel;
}

// The motion's keyframe scale: the same at every key (1 without motion); none otherwise.
std::optional<double> motionScale(const ShapeDescription& s) {
  if (s.motion.empty()) return 1.0;
  const double first = s.motion.keys().front().scale;
  for (const Keyframe& k : s.motion.keys())
    if (std::abs(k.scale - first) > 1e-12 * std::abs(first)) return std::nullopt;
  return first;
}

// S: what the model's vertices carry besides the rotation (model = S · raw).
glm::dmat3 modelShape(const ShapeDescription& s, double scale) {
  const glm::dmat3 linear(placedFromModel(s));
  return scale * (glm::transpose(rotationOf(linear)) * linear);
}

}  // namespace

SourceLocation exportsPlace(const SceneDescription& d) {
  const auto place = d.keyPlaces.find("exports");
  return place != d.keyPlaces.end() ? place->second : SourceLocation{d.sourceFile, 0, 0};
}

ObjectModel objectModel(const SceneDescription& d, std::size_t shape) {
  const ShapeDescription& s = d.shapes[shape];
  const std::optional<double> scale = motionScale(s);
  if (!scale) {
    throw InputError(exportsPlace(d), "exports",
                     "shape '" + s.label +
                         "': its motion's keyframes scale it differently over time, so no rigid "
                         "pose describes it (give every keyframe the same scale)");
  }
  const glm::dmat3 shapeMatrix = modelShape(s, *scale);
  ObjectModel m;
  if (s.kind == ShapeDescription::Kind::kSphere) {
    const double r = static_cast<double>(s.radius);
    for (int j = 0; j <= kModelSphereRings; ++j) {
      const double theta = std::numbers::pi * j / kModelSphereRings;
      for (int i = 0; i < kModelSphereSegments; ++i) {
        const double phi = 2.0 * std::numbers::pi * i / kModelSphereSegments;
        m.vertices.push_back(shapeMatrix *
                             (r * glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                             std::sin(theta) * std::sin(phi))));
      }
    }
    auto at = [](int j, int i) {
      return static_cast<std::uint32_t>(j * kModelSphereSegments + (i % kModelSphereSegments));
    };
    for (int j = 0; j < kModelSphereRings; ++j)
      for (int i = 0; i < kModelSphereSegments; ++i) {
        // Outward-facing (counter-clockwise seen from outside), degenerate at the poles.
        if (j > 0) m.indices.insert(m.indices.end(), {at(j, i), at(j, i + 1), at(j + 1, i)});
        if (j + 1 < kModelSphereRings)
          m.indices.insert(m.indices.end(), {at(j, i + 1), at(j + 1, i + 1), at(j + 1, i)});
      }
  } else {
    const MeshData& mesh = s.sharedMesh ? *s.sharedMesh : s.mesh;
    const glm::dmat4 rawFromStored = glm::inverse(s.objectFromModel);
    m.vertices.reserve(mesh.positions.size());
    double largest = 0.0;  // the largest stored coordinate's magnitude, m
    for (const glm::vec3& p : mesh.positions) {
      m.vertices.push_back(shapeMatrix *
                           glm::dvec3(rawFromStored * glm::dvec4(glm::dvec3(p), 1.0)));
      largest = std::max({largest, std::abs(static_cast<double>(p.x)),
                          std::abs(static_cast<double>(p.y)), std::abs(static_cast<double>(p.z))});
    }
    const glm::dmat3 toModel = shapeMatrix * glm::dmat3(rawFromStored);
    double gain = 0.0;  // a bound on the map's stretch: its Frobenius norm
    for (int c = 0; c < 3; ++c) gain += glm::dot(toModel[c], toModel[c]);
    m.rounding =
        std::sqrt(gain) * largest * static_cast<double>(std::numeric_limits<float>::epsilon());
    m.indices = mesh.indices;
  }
  m.boxMin = glm::dvec3(std::numeric_limits<double>::max());
  m.boxMax = glm::dvec3(-std::numeric_limits<double>::max());
  for (const glm::dvec3& v : m.vertices) {
    m.boxMin = glm::min(m.boxMin, v);
    m.boxMax = glm::max(m.boxMax, v);
  }
  if (m.vertices.empty()) m.boxMin = m.boxMax = glm::dvec3(0.0);
  return m;
}

glm::dmat4 renderFromModel(const ShapeDescription& s, double t) {
  const glm::dmat4 placed = placedFromModel(s);
  const glm::dmat3 rotation = rotationOf(glm::dmat3(placed));
  glm::dmat4 m(rotation);
  m[3] = placed[3];
  if (s.motion.empty()) return m;
  // The motion's rotation and translation at t; its (constant) scale is in the model. The
  // scale also scales the placement's offset: M(t) · placed maps the model origin to
  // M(t) · placed[3].
  const glm::dmat4 motion = s.motion.at(t);
  const glm::dmat3 turn = rotationOf(glm::dmat3(motion));
  glm::dmat4 out(turn * rotation);
  out[3] = motion * placed[3];
  return out;
}

glm::dmat4 renderFromCameraCv(const PhysicalCamera& camera, double t) {
  glm::dmat4 m = camera.worldFromCameraAt(t);
  m[1] = -m[1];  // camsim's up → OpenCV's down
  return m;
}

glm::dmat4 cameraCvFromRender(const PhysicalCamera& camera, double t) {
  return glm::inverse(renderFromCameraCv(camera, t));
}

std::vector<ObjectPose> objectPoses(const SceneDescription& d, const PhysicalCameraParams& params,
                                    std::span<const ObjectModel* const> models) {
  CAMSIM_CHECK(models.empty() || models.size() == d.shapes.size());
  const PhysicalCamera camera(params);
  const double t = params.shutter.centre();
  const glm::dmat4 cameraFromRender = cameraCvFromRender(camera, t);
  const SceneIds ids = sceneIds(d);
  const IdTable& classes = ids[IdKind::kClass];
  std::vector<ObjectPose> poses;
  for (std::size_t i = 0; i < d.shapes.size(); ++i) {
    if (classes.ofShape[i] == 0) continue;  // unlabelled
    const ObjectModel* given = models.empty() ? nullptr : models[i];
    const ObjectModel made = given ? ObjectModel{} : objectModel(d, i);
    const ObjectModel& model = given ? *given : made;
    const glm::dmat4 m = cameraFromRender * renderFromModel(d.shapes[i], t);
    ObjectPose p;
    p.shape = i;
    p.instance = static_cast<std::uint32_t>(i + 1);
    p.classNumber = classes.numbers[classes.ofShape[i]];
    p.rotation = glm::dmat3(m);
    p.translation = glm::dvec3(m[3]);
    p.boxMin = model.boxMin;
    p.boxMax = model.boxMax;
    poses.push_back(p);
  }
  return poses;
}

}  // namespace camsim
