// Real rays through LensSystem: a plate displaces a ray as Snell says, total internal
// reflection loses it, a ray traced out and back returns to its film point, the pupils
// found by rays are the paraxial ones, a bladed stop cuts its polygon, chief-ray angles.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "integrator/camera/lens_system.h"
#include "tests/integrator/lens_test_support.h"

namespace camsim {
namespace lens_trace_test {

TEST(LensTrace, PlaneParallelPlateDisplacesAsSnellSays) {
  // 10 mm of n = 1.5 between two planes: a ray leaves parallel to itself, displaced
  // sideways by t sin θ (1 − cos θ / √(n² − sin² θ)).
  const LensSystem plate = test::lensFromText("0 1 0 80\n0 10 1.5 80\n0 0 1 80\n");
  const double t = 0.010, n = 1.5;
  for (const double theta : {0.0, 0.1, 0.3, 0.6, 1.0}) {
    const glm::dvec3 d(std::sin(theta), 0.0, std::cos(theta));
    const glm::dvec3 o(-0.01, 0.002, -0.005);
    const std::optional<LensRay> out = plate.traceFromFilm({o, d}, 550.0);
    ASSERT_TRUE(out) << theta;
    EXPECT_NEAR(glm::length(out->direction - d), 0.0, 1e-15);
    const double shift = glm::length(glm::cross(out->origin - o, d));
    const double s = std::sin(theta);
    EXPECT_NEAR(shift, t * s * (1.0 - std::cos(theta) / std::sqrt(n * n - s * s)), 1e-15) << theta;
    // The other way: the same displacement.
    const glm::dvec3 front(0.0, 0.0, 0.012);
    const std::optional<LensRay> in = plate.traceFromObject({front, -d}, 550.0);
    ASSERT_TRUE(in);
    EXPECT_NEAR(glm::length(glm::cross(in->origin - front, d)), shift, 1e-15);
  }
}

TEST(LensTrace, ConicSurfaceFocusesWithoutAberration) {
  // An ellipsoid of eccentricity 1/n (k = −1/n²) refracts parallel rays from air into glass
  // to one point, nR/(n − 1) behind its vertex (Descartes). The exit plane is put there:
  // every real ray, at any height, meets it on the axis.
  // n = 1.5, R = 20 mm: k = −4/9, the focus 60 mm behind the vertex.
  char text[200];
  std::snprintf(text, sizeof text, "0 1 0 24\n20 60 1.5 24 conic=%.17g\n0 0 1 24\n", -4.0 / 9.0);
  const LensSystem lens = test::lensFromText(text);
  ASSERT_TRUE(lens.shape(1).aspheric);
  for (double h = 0.0005; h < 0.012; h += 0.0005) {
    const std::optional<LensRay> out =
        lens.traceFromObject({{h, 0.0, lens.frontVertexZ() + 0.01}, {0.0, 0.0, -1.0}}, 550.0);
    ASSERT_TRUE(out) << h;
    EXPECT_NEAR(out->origin.x, 0.0, 1e-13) << h;
  }
}

TEST(LensTrace, TotalInternalReflectionLosesTheRay) {
  // From the film, rays parallel to the axis enter a flat rear face and meet a sphere of
  // R = 10 mm from inside the glass (n = 1.5) at sin i = h/R: totally reflected beyond
  // h = R/n = 6.667 mm.
  const LensSystem lens = test::lensFromText("0 1 0 40\n10 20 1.5 19\n0 0 1 19\n");
  const auto passes = [&](double h) {
    return lens.traceFromFilm({{h, 0.0, -0.01}, {0.0, 0.0, 1.0}}, 550.0).has_value();
  };
  EXPECT_TRUE(passes(0.0));
  EXPECT_TRUE(passes(0.0066));
  EXPECT_FALSE(passes(0.00668));
  EXPECT_FALSE(passes(0.009));
}

TEST(LensTrace, RayTracedOutAndBackReturnsToItsFilmPoint) {
  for (const char* file : {"dgauss.50mm.dat", "fisheye.10mm.dat", "telephoto.250mm.dat"}) {
    const LensSystem lens = test::cameraLens(file);
    const double s = lens.focusSensorDistance();
    int traced = 0;
    for (double h = 0.0; h <= 0.012; h += 0.002)
      for (double x = -0.004; x <= 0.004; x += 0.001) {
        const glm::dvec3 film(h, 0.3 * h, -s);
        const glm::dvec3 d = glm::normalize(glm::dvec3(x, 0.5 * x, 0.0) - film);
        const std::optional<LensRay> out = lens.traceFromFilm({film, d}, kLambdaDNm);
        if (!out) continue;
        ++traced;
        EXPECT_GT(out->direction.z, 0.0);
        // Back from a point 1 mm out along the ray.
        const std::optional<LensRay> back = lens.traceFromObject(
            {out->origin + 1e-3 * out->direction, -out->direction}, kLambdaDNm);
        ASSERT_TRUE(back) << file;
        EXPECT_NEAR(glm::length(back->direction + d), 0.0, 1e-12) << file;
        const double t = (-s - back->origin.z) / back->direction.z;
        EXPECT_NEAR(glm::length(back->origin + t * back->direction - film), 0.0, 1e-12) << file;
      }
    EXPECT_GT(traced, 20) << file;
  }
}

TEST(LensTrace, RealRaysFindTheParaxialPupils) {
  // Two singlets with the stop between them, stopped down so that rays stay paraxial.
  LensSystem lens =
      test::lensFromText("100 3 1.5 30\n-100 20 1 30\n0 15 0 4\n80 3 1.5 30\n-80 0 1 30\n");
  lens.setStop(0.002);
  const ParaxialData p = lens.paraxial();
  const auto parallelPasses = [&](double h) {
    return lens.traceFromObject({{h, 0.0, 0.1}, {0.0, 0.0, -1.0}}, kLambdaDNm).has_value();
  };
  EXPECT_TRUE(parallelPasses(0.99 * 0.5 * p.entrancePupilDiameter));
  EXPECT_FALSE(parallelPasses(1.01 * 0.5 * p.entrancePupilDiameter));
  // Chief rays: aimed at the entrance pupil's centre from object space they cross the stop
  // at its centre; from the film, aimed at the exit pupil's centre, likewise.
  lens.setStop(1e-5);
  for (const double angle : {0.01, 0.03}) {
    const glm::dvec3 ep(0.0, 0.0, p.entrancePupilZ);
    const glm::dvec3 d(-std::sin(angle), 0.0, -std::cos(angle));
    EXPECT_TRUE(lens.traceFromObject({ep - 0.2 * d, d}, kLambdaDNm)) << angle;
    EXPECT_FALSE(lens.traceFromObject({ep - 0.2 * d + glm::dvec3(1e-4, 0, 0), d}, kLambdaDNm));
    const glm::dvec3 xp(0.0, 0.0, p.exitPupilZ);
    const glm::dvec3 film(0.002 * angle / 0.01, 0.0, -0.1);
    EXPECT_TRUE(lens.traceFromFilm({film, glm::normalize(xp - film)}, kLambdaDNm)) << angle;
    const glm::dvec3 off = xp + glm::dvec3(1e-4, 0.0, 0.0);
    EXPECT_FALSE(lens.traceFromFilm({film, glm::normalize(off - film)}, kLambdaDNm)) << angle;
  }
}

TEST(LensTrace, BladedStopCutsItsPolygon) {
  LensSystem lens = test::lensFromText("0 1 0 20\n50 3 1.5 30\n-50 0 1 30\n");
  lens.setStop(0.010, 6, 0.2);
  const double r = lens.stop().circumradius();
  const double apothem = r * std::cos(M_PI / 6.0);
  for (int k = 0; k < 6; ++k) {
    const double vertex = 0.2 + k * M_PI / 3.0, edge = vertex + M_PI / 6.0;
    EXPECT_TRUE(lens.insideStop(0.99 * r * std::cos(vertex), 0.99 * r * std::sin(vertex)));
    EXPECT_FALSE(lens.insideStop(1.01 * r * std::cos(vertex), 1.01 * r * std::sin(vertex)));
    EXPECT_TRUE(lens.insideStop(0.99 * apothem * std::cos(edge), 0.99 * apothem * std::sin(edge)));
    EXPECT_FALSE(lens.insideStop(1.01 * apothem * std::cos(edge), 1.01 * apothem * std::sin(edge)));
  }
}

TEST(LensTrace, ChiefRayAnglesGrowWithFieldAndStartParaxial) {
  for (const char* file : {"dgauss.50mm.dat", "fisheye.10mm.dat", "telephoto.250mm.dat"}) {
    const LensSystem lens = test::cameraLens(file);
    const double s = lens.focusSensorDistance(), f = lens.paraxial().effectiveFocalLength;
    const std::optional<double> small = lens.chiefRayAngle(1e-6, s);
    ASSERT_TRUE(small) << file;
    EXPECT_NEAR(*small / (1e-6 / f), 1.0, 1e-6) << file;
    double previous = 0.0;
    std::printf("%s chief-ray angle (deg) at film height (mm):", file);
    for (double h = 0.002; h <= 0.0217; h += 0.002) {
      const std::optional<double> a = lens.chiefRayAngle(h, s);
      if (!a) break;
      std::printf(" %.0f: %.2f", h * 1e3, *a * 180.0 / M_PI);
      EXPECT_GT(*a, previous) << file << " " << h;
      previous = *a;
    }
    std::printf("\n");
  }
}

}  // namespace lens_trace_test
}  // namespace camsim
