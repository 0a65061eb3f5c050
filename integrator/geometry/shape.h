// Shape: geometry that Embree intersects and lights sample. Small closed set: triangle
// meshes (which also carry rectangles) and spheres. Intersection itself is done by
// EmbreeScene; a Shape turns Embree's hit into a SurfaceInteraction and samples points.
// Lengths in metres.
//
// Moving shapes hold K ≥ 2 poses at time steps spread uniformly over the scene's motion
// span [t0, t1] (TimeSteps) and interpolate them linearly. Embree traces them as one
// static copy of a reference pose under a motion-blurred instance (InstanceMotion) whose
// transform at step k takes that pose to pose k: Embree interpolates the transforms
// linearly, and for affine X_k, lerp(X_k, X_k+1)·p_ref = lerp(p_k, p_k+1), so hit points
// agree with the shapes' own interpolation.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/geometry/math.h"
#include "integrator/geometry/ray.h"

namespace camsim {

// What Embree reports for a hit: the shape (its index: the geometry or instance id), the primitive, the
// barycentric (u, v) and the ray parameter.
struct Hit {
  int shape = -1;
  int prim = -1;
  float u = 0.0f, v = 0.0f;
  float t = 0.0f;
};

// Uniform time steps over [t0, t1]; count 1 means static.
struct TimeSteps {
  double t0 = 0.0, t1 = 1.0;
  int count = 1;
  // Step index i and fraction f in [0,1] with time between steps i and i+1.
  void locate(double time, int& i, float& f) const {
    if (count <= 1) {
      i = 0;
      f = 0.0f;
      return;
    }
    const double x = (static_cast<double>(time) - t0) / (t1 - t0) * (count - 1);
    const double clamped = x < 0.0 ? 0.0 : (x > count - 1 ? count - 1 : x);
    i = static_cast<int>(clamped);
    if (i >= count - 1) i = count - 2;
    f = static_cast<float>(clamped - i);
  }
  double timeOf(int step) const { return count <= 1 ? t0 : t0 + (t1 - t0) * step / (count - 1); }
};

// How a moving shape is traced: its pose at step `reference` (the pose of the largest size,
// so that a shape growing from a speck keeps its single-precision detail) under an
// instance whose transform at step k (render space, one per time step) is
// X_k = M_k · M_reference⁻¹. Empty (no steps) for a static shape.
struct InstanceMotion {
  int reference = 0;
  std::vector<glm::mat4> steps;
  float translation = 0.0f;  // largest |translation component| over the steps (m)

  InstanceMotion() = default;
  // For a shape whose pose at step k is M_k = poses[k] (shape space → render space, uniform
  // scale; one per time step): the reference is the first pose of the largest scale, where
  // "larger" means by more than 0.1 %, so that rounding does not pick a later pose of a
  // rigid motion; X_k = M_k · M_reference⁻¹. Empty for fewer than two poses.
  static InstanceMotion fromPoses(const std::vector<glm::dmat4>& poses);
  bool empty() const { return steps.empty(); }
  // The transform at step i + fraction f (TimeSteps::locate), interpolated as Embree does.
  glm::mat4 at(int i, float f) const {
    const glm::mat4& a = steps[static_cast<size_t>(i)];
    return f == 0.0f ? a : a + f * (steps[static_cast<size_t>(i) + 1] - a);
  }
  // Extra absolute error bound (m) of a point p on the shape: Embree moves each ray into
  // the instance's space with the interpolated transform, rounding at the scale of p and
  // of the translation. The same on every axis: a rotation carries one axis's rounding
  // into the others (a plane through the origin would otherwise get no offset along its
  // normal).
  glm::vec3 error(const glm::vec3& p) const {
    const glm::vec3 a = absComponents(p);
    return glm::vec3(gammaBound(8) * (std::max(a.x, std::max(a.y, a.z)) + translation));
  }
};

struct SurfaceInteraction {
  glm::vec3 p{0.0f};       // position, m
  glm::vec3 pError{0.0f};  // absolute floating-point error bound on p, m
  glm::vec3 n{0.0f};       // geometric normal, unit; its side is the shape's front
  glm::vec3 ns{0.0f};      // shading normal, unit (interpolated normals may face away from n)
  glm::vec2 uv{0.0f};      // texture coordinates (see integrator/textures/texture.h)
  int shape = -1;
  int prim = -1;      // triangle index (meshes)
  double time = 0.0;  // s

  // Origin for a ray leaving towards w, offset against self-intersection (inline: three
  // per bounce on the hot path).
  glm::vec3 spawnOrigin(const glm::vec3& w) const { return offsetRayOrigin(p, pError, n, w); }
};

// The surface's tangent directions at a hit, for tangent-space normal maps (render space;
// neither unit nor orthogonal to the shading normal: integrator/textures/normal_map.h
// orthonormalises them): `tangent` along ∂p/∂u, `bitangent` on the side of ∂p/∂v.
struct SurfaceTangents {
  glm::vec3 tangent{0.0f};
  glm::vec3 bitangent{0.0f};
};

struct ShapeSample {
  SurfaceInteraction point;  // uv only where it comes free (meshes); no light reads it
  glm::vec3 wi{0.0f};        // unit direction from the reference point to point.p
  float pdf = 0.0f;          // solid angle (sr⁻¹) as seen from the reference point
};
// CMakeLists.txt's -mmemset-strategy zeroes up to CAMSIM_MEMSET_INLINE_BYTES (a compile
// definition from the same CMake variable) with plain stores (GCC's default above 80 bytes
// is `rep stos`, slow to start: docs/performance.md). A light sample zeroes
// optional<ShapeSample> once per light sample: past the threshold it would call memset.
static_assert(sizeof(std::optional<ShapeSample>) <= CAMSIM_MEMSET_INLINE_BYTES,
              "ShapeSample outgrew CMakeLists.txt's -mmemset-strategy threshold");

// From a reference point to a point p: the unit direction and the squared distance (m²),
// computed once per light sample for both the direction and the pdf, with one division
// (the light sample's divides queue on one divider).
struct Towards {
  glm::vec3 wi;
  float dist2;
};
inline std::optional<Towards> towards(const glm::vec3& ref, const glm::vec3& p) {
  const glm::vec3 d = p - ref;
  const float dist2 = lengthSquared(d);
  if (dist2 == 0.0f) return std::nullopt;
  return Towards{d * (1.0f / std::sqrt(dist2)), dist2};
}

// Solid-angle pdf (sr⁻¹) of a point with normal n, sampled by area with density pdfArea
// (m⁻²), seen along t: pdfArea·dist² / |cos θ|, and 0 when seen edge-on.
inline float solidAnglePdf(float pdfArea, const Towards& t, const glm::vec3& n) {
  const float cosTheta = std::abs(glm::dot(n, t.wi));
  if (cosTheta == 0.0f) return 0.0f;
  return pdfArea * t.dist2 / cosTheta;
}

// Completes the sample in `out` of a point (out->point) chosen by area with density pdfArea
// (m⁻²), as seen from ref: its direction and solid-angle pdf; empties `out` when the sample
// cannot be used (the point at ref, zero density, seen edge-on, a pdf beyond float). Works on
// the caller's slot, so meshes build their samples in place (triangle_mesh.cpp).
inline void completeAreaSample(std::optional<ShapeSample>& out, const glm::vec3& ref,
                               float pdfArea) {
  ShapeSample& s = *out;
  const std::optional<Towards> t = towards(ref, s.point.p);
  if (!t || !(pdfArea > 0.0f)) {
    out.reset();
    return;
  }
  s.wi = t->wi;
  s.pdf = solidAnglePdf(pdfArea, *t, s.point.n);
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) out.reset();
}

// A static shape whose points all lie in one plane and whose normals n (as interaction()
// and sample() give them) all point to the same side:
//   |n·x − offset| ≤ spread (m) for every point x, all x within radius (m) of centre, and
//   every normal within tilt (chord length of unit vectors, rounding included) of n.
// entirelyBehind(ref) is true only if ref is strictly behind every point of the shape, so
// that a one-sided emitter cannot light it (a ceiling behind a lamp); false when unsure:
// for any point x and normal n' of the shape, n'·(ref − x) ≤ (n·ref − offset) + spread +
// tilt·|ref − x| (+ rounding), with |ref − x| ≤ |ref − centre| + radius.
struct FrontPlane {
  glm::vec3 n{0.0f};
  float offset = 0.0f;
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
  float spread = 0.0f;
  float tilt = 0.0f;

  bool entirelyBehind(const glm::vec3& ref) const {
    const float d = glm::dot(n, ref) - offset;
    if (!(d < 0.0f)) return false;
    const glm::vec3 r = ref - centre;
    const float distance = std::sqrt(glm::dot(r, r)) + radius;
    // float rounding of the dot products: a few ulps of the coordinates involved
    const float scale =
        std::max({std::abs(ref.x), std::abs(ref.y), std::abs(ref.z)}) + std::abs(offset) + distance;
    return d < -(spread + tilt * distance + 1e-6f * scale);
  }
};

class Shape {
 public:
  virtual ~Shape() = default;
  virtual float area() const = 0;  // m², at rest
  virtual const TimeSteps& timeSteps() const = 0;
  virtual const InstanceMotion& instanceMotion() const = 0;  // empty if static
  virtual SurfaceInteraction interaction(const Hit& hit, const Ray& ray) const = 0;
  // The tangent frame at a hit whose interaction() is si, computed only when a normal map
  // needs it (not part of SurfaceInteraction: light samples copy that). None: the shape
  // has no (u, v) frame there, and a normal map leaves the shading normal as it is.
  virtual std::optional<SurfaceTangents> tangentFrame(const Hit& /*hit*/,
                                                      const SurfaceInteraction& /*si*/) const {
    return std::nullopt;
  }
  // A point on the shape at `time` seen from ref (u1 in [0,1), u2 in [0,1)²), with its
  // solid-angle pdf.
  virtual std::optional<ShapeSample> sample(const glm::vec3& ref, float u1, glm::vec2 u2,
                                            double time) const = 0;
  // Solid-angle density of sample() producing `onShape` (at onShape.time) as seen from ref.
  virtual float pdf(const glm::vec3& ref, const SurfaceInteraction& onShape) const = 0;
  // The plane of a static planar shape with one front side (see FrontPlane); empty when
  // the shape is not one, or not provably so.
  virtual std::optional<FrontPlane> frontPlane() const { return std::nullopt; }
};

// Solid-angle pdf of a point sampled by area with density pdfArea (m⁻²), seen from ref.
inline float areaToSolidAnglePdf(float pdfArea, const glm::vec3& ref,
                                 const SurfaceInteraction& onShape) {
  const std::optional<Towards> t = towards(ref, onShape.p);
  return t ? solidAnglePdf(pdfArea, *t, onShape.n) : 0.0f;
}

}  // namespace camsim
