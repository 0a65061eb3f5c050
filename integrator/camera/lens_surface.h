// One refracting surface of a lens system (or its stop): the prescription's data, the
// surface's shape in lens space, ray intersection and Snell refraction.
//
// Lens space (metres): the optical axis is z, the lens looks along +z (towards the
// object), x and y are the camera's right and up; z = 0 is the rear vertex (the last
// surface's vertex), so a lens's surfaces lie at z ≥ 0 and its sensor at z < 0.
//
// | field     | unit      | meaning |
// |-----------|-----------|---------|
// | vertexZ   | m         | z of the surface's vertex on the axis |
// | curvature | 1/m       | c = 1/R at the vertex; R > 0: centre of curvature on the image side (−z); 0: plane |
// | conic     | —         | k |
// | asphere   | m^(1−2i)  | a4 … a16 |
//
// The surface is z = vertexZ − sag(r), r² = x² + y², with the even-asphere sag
//
//   sag(r) = c r² / (1 + √(1 − (1 + k) c² r²)) + Σ_{i=2..8} a_{2i} r^{2i}
//
// (positive sag bends towards the image). Its normal is the normalised gradient of
// G = vertexZ − sag(r) − z: n ∝ (sag'(r) x/r, sag'(r) y/r, 1), facing +z.
//
// Intersection: a sphere (k = 0, no terms) or a plane in closed form, the root on the
// vertex's hemisphere (1 + c·(z − vertexZ) > 0, both roots there: the first ahead); an
// asphere by Newton's method on G along the ray started from that sphere's (or the
// plane's) root: converged when a step is below 1e-14 m, else the ray is lost.
#pragma once

#include <array>
#include <optional>

#include <glm/vec3.hpp>

#include "integrator/camera/glass.h"

namespace camsim {

inline constexpr int kMaxLensSurfaces = 64;
inline constexpr int kAsphereTerms = 7;  // a4, a6, …, a16

// A surface as the prescription gives it (lens_file.h), in SI.
struct LensSurface {
  double radius = 0.0;            // m, vertex radius of curvature; 0: plane
  double thickness = 0.0;         // m, to the next surface's vertex
  double apertureDiameter = 0.0;  // m, clear aperture (the stop's: its largest diameter)
  bool stop = false;              // the aperture stop (a plane that refracts nothing)
  double conic = 0.0;             // k, dimensionless
  std::array<double, kAsphereTerms> asphere{};  // a4 … a16, m^(1−2i)
  Glass medium;                                 // after the surface (towards the image)
  int line = 0;                                 // 1-based line in the file, for messages

  double curvature() const { return radius == 0.0 ? 0.0 : 1.0 / radius; }  // 1/m
  bool aspheric() const;  // conic or any a_{2i} non-zero
};

// The surface placed in lens space: what the tracer reads.
struct SurfaceShape {
  double vertexZ = 0.0;    // m
  double curvature = 0.0;  // 1/m
  double conic = 0.0;
  std::array<double, kAsphereTerms> asphere{};  // m^(1−2i)
  double clearRadius2 = 0.0;                    // (clear aperture / 2)², m²
  bool aspheric = false;

  static SurfaceShape from(const LensSurface& s, double vertexZ);
};

// Whether 1 − (1 + k) c² r² > 0 at r² (m²): the sag and its slope are defined (finite).
bool sagDefined(const SurfaceShape& s, double rSquared);
// sag(r) (m) and sag'(r)/r (1/m, finite at r = 0) at r² where sagDefined.
double sag(const SurfaceShape& s, double rSquared);
double sagSlopeOverR(const SurfaceShape& s, double rSquared);
// The unit normal at a point of the surface, facing +z.
glm::dvec3 surfaceNormal(const SurfaceShape& s, const glm::dvec3& p);

// The distance t > 0 along the unit direction d from o to the surface, or none (a miss,
// the sag undefined, Newton not converged). Clear apertures are the caller's.
std::optional<double> intersectSurface(const SurfaceShape& s, const glm::dvec3& o,
                                       const glm::dvec3& d);

// Snell's law in vector form: the unit direction d refracted at the unit normal n (either
// orientation) from index etaFrom into etaTo; false at total internal reflection.
bool refract(glm::dvec3& d, glm::dvec3 n, double etaFrom, double etaTo);

}  // namespace camsim
