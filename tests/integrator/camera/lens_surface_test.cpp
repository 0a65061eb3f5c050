// Surface geometry: the asphere's sag slope and normal against finite differences, ray
// intersections on the surface (closed form and Newton), Snell's law and its limit.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "integrator/camera/lens_surface.h"

namespace camsim {
namespace lens_surface_test {

// A strong even asphere: R = 30 mm, k = −0.8, a4 = 2e-6 mm⁻³, a6 = −3e-9 mm⁻⁵, a8 = 1e-12
// mm⁻⁷, clear aperture 30 mm, vertex at z = 5 mm.
SurfaceShape asphere() {
  LensSurface s;
  s.radius = 0.030;
  s.conic = -0.8;
  s.asphere[0] = 2e-6 * 1e9;
  s.asphere[1] = -3e-9 * 1e15;
  s.asphere[2] = 1e-12 * 1e21;
  s.apertureDiameter = 0.030;
  return SurfaceShape::from(s, 0.005);
}

double surfaceFunction(const SurfaceShape& s, const glm::dvec3& p) {
  return s.vertexZ - sag(s, p.x * p.x + p.y * p.y) - p.z;
}

TEST(LensSurface, AsphereSlopeAndNormalMatchFiniteDifferences) {
  const SurfaceShape s = asphere();
  const double h = 1e-7;  // m; central differences err by O(h²)
  for (double r = 0.0005; r <= 0.015; r += 0.0005) {
    const double fd = (sag(s, (r + h) * (r + h)) - sag(s, (r - h) * (r - h))) / (2.0 * h);
    EXPECT_NEAR(sagSlopeOverR(s, r * r) * r, fd, 1e-7 * (std::abs(fd) + 1e-3)) << r;
    // The normal is the gradient of G = vertexZ − sag − z, negated (it faces +z).
    const glm::dvec3 p(0.6 * r, 0.8 * r, s.vertexZ - sag(s, r * r));
    glm::dvec3 grad;
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 e(0.0);
      e[k] = h;
      grad[k] = (surfaceFunction(s, p + e) - surfaceFunction(s, p - e)) / (2.0 * h);
    }
    const glm::dvec3 n = surfaceNormal(s, p);
    EXPECT_NEAR(glm::length(n - glm::normalize(-grad)), 0.0, 1e-7) << r;
  }
  // The conic alone: a paraboloid (k = −1) has sag exactly c r²/2.
  SurfaceShape parabola;
  parabola.curvature = 1.0 / 0.05;
  parabola.conic = -1.0;
  EXPECT_NEAR(sag(parabola, 0.01 * 0.01), 0.5 / 0.05 * 1e-4, 1e-18);
}

TEST(LensSurface, IntersectionsLieOnTheSurfaceNearTheVertex) {
  SurfaceShape sphere;
  sphere.vertexZ = 0.002;
  sphere.curvature = -1.0 / 0.04;  // R = −40 mm
  SurfaceShape plane;
  plane.vertexZ = -0.001;
  const SurfaceShape aspheric = asphere();
  for (const SurfaceShape* s :
       std::initializer_list<const SurfaceShape*>{&sphere, &plane, &aspheric}) {
    for (const double dirZ : {1.0, -1.0}) {
      for (double h = 0.0; h <= 0.014; h += 0.002) {
        const glm::dvec3 o(h, -0.3 * h, s->vertexZ - dirZ * 0.03);
        const glm::dvec3 d = glm::normalize(glm::dvec3(0.1, 0.05, dirZ));
        const std::optional<double> t = intersectSurface(*s, o, d);
        ASSERT_TRUE(t) << h;
        const glm::dvec3 p = o + *t * d;
        EXPECT_NEAR(surfaceFunction(*s, p), 0.0, 1e-13) << h;
        EXPECT_LT(std::abs(p.z - s->vertexZ), 0.01);  // the vertex's branch
      }
    }
  }
  // A sphere in closed form: a ray parallel to the axis at height h meets the cap at
  // vertexZ − (R − √(R² − h²)), R = −40 mm here, so towards +z.
  const std::optional<double> t = intersectSurface(sphere, {0.01, 0.0, -0.05}, {0.0, 0.0, 1.0});
  ASSERT_TRUE(t);
  EXPECT_NEAR(-0.05 + *t, 0.002 + (0.04 - std::sqrt(0.04 * 0.04 - 1e-4)), 1e-15);
  // A ray that misses the sphere, and one that starts past the surface.
  EXPECT_FALSE(intersectSurface(sphere, {0.05, 0.0, -0.05}, {0.0, 0.0, 1.0}));
  EXPECT_FALSE(intersectSurface(plane, {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}));
}

TEST(LensSurface, RefractionObeysSnellAndTotalInternalReflectionFails) {
  const glm::dvec3 n(0.0, 0.0, 1.0);
  for (double theta = 0.0; theta < 1.5; theta += 0.1) {
    glm::dvec3 d(std::sin(theta), 0.0, -std::cos(theta));
    ASSERT_TRUE(refract(d, n, 1.0, 1.5));
    EXPECT_NEAR(1.5 * d.x, std::sin(theta), 1e-15);  // n₁ sin θ₁ = n₂ sin θ₂
    EXPECT_NEAR(glm::length(d), 1.0, 1e-15);
    EXPECT_LT(d.z, 0.0);
    EXPECT_EQ(d.y, 0.0);
  }
  const double critical = std::asin(1.0 / 1.5);
  glm::dvec3 below(std::sin(critical - 1e-6), 0.0, std::cos(critical - 1e-6));
  glm::dvec3 above(std::sin(critical + 1e-6), 0.0, std::cos(critical + 1e-6));
  EXPECT_TRUE(refract(below, -n, 1.5, 1.0));
  EXPECT_FALSE(refract(above, n, 1.5, 1.0));  // either orientation of the normal
}

}  // namespace lens_surface_test
}  // namespace camsim
