// The projection models (integrator/camera/projection.h): exact round trips over each
// model's whole image and past 180° of field, the ideal fisheye mappings against their closed
// forms, the solid-angle density against analytic integrals and a finite difference of
// unproject and the range checks. The
// comparison with the real OpenCV is in projection_opencv_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "integrator/camera/projection.h"
#include "tests/integrator/camera/projection_cases.h"

namespace camsim {
namespace {

using test::ProjectionCase;
using test::projectionCases;
constexpr double kProjectionPi = std::numbers::pi;
constexpr double kDeg = kProjectionPi / 180.0;

double fieldAngleOf(glm::dvec3 d) {
  return std::atan2(std::hypot(d.x, d.y), d.z);
}

TEST(Projection, NamesRoundTrip) {
  for (const ProjectionCase& c : projectionCases()) {
    const std::string_view name = enumName(c.p.model);
    EXPECT_FALSE(name.empty());
    EXPECT_EQ(enumFromName<ProjectionModel>(name), c.p.model);
  }
  EXPECT_EQ(enumFromName<ProjectionModel>("opencv_fisheye"), ProjectionModel::kKannalaBrandt);
  EXPECT_EQ(enumNameList<ProjectionModel>(),
            "opencv, kannala_brandt, equidistant, equisolid, stereographic, orthographic, "
            "ftheta, unified, double_sphere, equirectangular");
}

// project(unproject(p)) == p over every third pixel centre of the whole image, and for the
// radial models the valid pixels are exactly those inside the image circle.
TEST(Projection, PixelRoundTripOverTheWholeImage) {
  for (const ProjectionCase& c : projectionCases()) {
    double worst = 0.0;
    int valid = 0, total = 0;
    for (int y = 0; y < c.size.y; y += 3)
      for (int x = 0; x < c.size.x; x += 3) {
        const glm::dvec2 px(x, y);
        ++total;
        const std::optional<glm::dvec3> d = unproject(c.p, px);
        if (c.imageRadius > 0.0) {
          // Radial models: valid exactly inside the image circle (1e-6 margin).
          const double r =
              glm::length((px - glm::dvec2(c.p.cx, c.p.cy)) / glm::dvec2(c.p.fx, c.p.fy));
          if (r < c.imageRadius * (1.0 - 1e-6)) {
            EXPECT_TRUE(d) << c.name << " " << x << "," << y;
          }
          if (r > c.imageRadius * (1.0 + 1e-6)) {
            EXPECT_FALSE(d) << c.name << " " << x << "," << y;
          }
        }
        if (!d) continue;
        ++valid;
        EXPECT_NEAR(glm::length(*d), 1.0, 1e-14) << c.name;
        const std::optional<glm::dvec2> back = project(c.p, *d);
        ASSERT_TRUE(back) << c.name << " pixel " << x << "," << y;
        worst = std::max(worst, glm::length(*back - px));
      }
    std::printf(
        "%-16s pixel round trip: %d of %d valid, largest |p − project(unproject(p))| "
        "%.3g px\n",
        c.name, valid, total, worst);
    EXPECT_GT(valid, total / 2) << c.name;
    EXPECT_LE(worst, 1e-9) << c.name;
  }
}

// unproject(project(d)) == d for directions spread evenly over the sphere (a Fibonacci
// lattice) up to each case's tested field angle, past 90° for the wide models.
TEST(Projection, DirectionRoundTripIncludingBehindTheCamera) {
  const int n = 20000;
  for (const ProjectionCase& c : projectionCases()) {
    double worst = 0.0, widest = 0.0;
    for (int i = 0; i < n; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / n, s = std::sqrt(1.0 - z * z);
      const double phi = i * kProjectionPi * (3.0 - std::sqrt(5.0));
      const glm::dvec3 d(s * std::cos(phi), s * std::sin(phi), z);
      const double theta = fieldAngleOf(d);
      const std::optional<glm::dvec2> px = project(c.p, d);
      if (theta > c.p.maxFieldAngle + 1e-12 && c.p.model != ProjectionModel::kEquirectangular) {
        EXPECT_FALSE(px) << c.name << " θ = " << theta / kDeg;
      }
      if (theta > c.testedFieldAngle) continue;
      ASSERT_TRUE(px) << c.name << " θ = " << theta / kDeg;
      const std::optional<glm::dvec3> back = unproject(c.p, *px);
      ASSERT_TRUE(back) << c.name << " θ = " << theta / kDeg;
      worst = std::max(worst, glm::length(*back - d));
      widest = std::max(widest, theta);
    }
    std::printf(
        "%-16s direction round trip up to %.1f°: largest |d − unproject(project(d))| "
        "%.3g\n",
        c.name, widest / kDeg, worst);
    EXPECT_LE(worst, 1e-9) << c.name;
    EXPECT_GT(widest, c.testedFieldAngle - 2.0 * kDeg) << c.name;
  }
}

// The ideal fisheye mappings against r = fθ, 2f sin(θ/2), 2f tan(θ/2), f sin θ, with
// different fx and fy (the radius scales per axis).
TEST(Projection, IdealFisheyesMatchTheirClosedForms) {
  const struct {
    ProjectionModel model;
    double (*radius)(double);
    double maxTheta;
  } models[] = {
      {ProjectionModel::kEquidistant, [](double t) { return t; }, kProjectionPi},
      {ProjectionModel::kEquisolid, [](double t) { return 2.0 * std::sin(0.5 * t); },
       kProjectionPi},
      {ProjectionModel::kStereographic, [](double t) { return 2.0 * std::tan(0.5 * t); },
       170.0 * kDeg},
      {ProjectionModel::kOrthographic, [](double t) { return std::sin(t); }, 89.0 * kDeg},
  };
  for (const auto& m : models) {
    Projection p;
    p.model = m.model;
    p.fx = 310.0;
    p.fy = 290.0;
    p.cx = 500.25;
    p.cy = 480.5;
    double worst = 0.0;
    for (double theta = 0.0; theta <= m.maxTheta + 1e-12; theta += 0.5 * kDeg)
      for (double phi = 0.0; phi < 2.0 * kProjectionPi; phi += 0.37) {
        const glm::dvec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                           std::cos(theta));
        const std::optional<glm::dvec2> px = project(p, 2.5 * d);
        ASSERT_TRUE(px) << enumName(m.model) << " θ " << theta / kDeg;
        const double r = m.radius(theta);
        const glm::dvec2 expected(p.cx + p.fx * r * std::cos(phi), p.cy + p.fy * r * std::sin(phi));
        worst = std::max(worst, glm::length(*px - expected));
      }
    EXPECT_LE(worst, 1e-9) << enumName(m.model);
  }
}

// The double sphere against the paper's projection written out (Usenko et al. 2018, eq. 40-43).
TEST(Projection, DoubleSphereMatchesThePapersProjection) {
  Projection p;
  p.model = ProjectionModel::kDoubleSphere;
  p.fx = 350.0;
  p.fy = 340.0;
  p.cx = 640.0;
  p.cy = 512.0;
  p.xi = -0.18;
  p.alpha = 0.59;
  for (double theta = 0.0; theta < 115.0 * kDeg; theta += 1.0 * kDeg)
    for (double phi = 0.1; phi < 2.0 * kProjectionPi; phi += 0.5) {
      const glm::dvec3 X = 3.0 * glm::dvec3(std::sin(theta) * std::cos(phi),
                                            std::sin(theta) * std::sin(phi), std::cos(theta));
      const double d1 = glm::length(X);
      const double d2 = std::sqrt(X.x * X.x + X.y * X.y + (p.xi * d1 + X.z) * (p.xi * d1 + X.z));
      const double den = p.alpha * d2 + (1.0 - p.alpha) * (p.xi * d1 + X.z);
      const std::optional<glm::dvec2> px = project(p, X);
      ASSERT_TRUE(px);
      EXPECT_NEAR(px->x, p.fx * X.x / den + p.cx, 1e-9);
      EXPECT_NEAR(px->y, p.fy * X.y / den + p.cy, 1e-9);
    }
}

// A strong barrel distortion folds the image back: ρ_d = ρ(1 − 0.5ρ²) peaks at ρ = √(2/3)
// (ρ_d = √(2/3)·2/3). Directions beyond the fold do not project, pixels beyond the peak do not
// unproject, and inside both round trip.
TEST(Projection, OpenCvDistortionFoldBoundsTheValidDomain) {
  Projection p;
  p.fx = p.fy = 1.0;
  p.cx = p.cy = 0.0;
  p.k1 = -0.5;
  const double foldRho = std::sqrt(2.0 / 3.0), peak = foldRho * 2.0 / 3.0;
  for (double rho = 0.01; rho < 1.5; rho += 0.01) {
    const glm::dvec3 d(0.6 * rho, -0.8 * rho, 1.0);
    const std::optional<glm::dvec2> px = project(p, d);
    EXPECT_EQ(px.has_value(), rho < foldRho) << rho;
    if (px) {
      const std::optional<glm::dvec3> back = unproject(p, *px);
      ASSERT_TRUE(back) << rho;
      EXPECT_LE(glm::length(*back - glm::normalize(d)), 1e-12) << rho;
    }
    const glm::dvec2 pixel(0.6 * rho, -0.8 * rho);
    EXPECT_EQ(unproject(p, pixel).has_value(), rho < peak) << rho;
  }
}

// k1 = −0.6, k2 = 0.12: ρ_d = ρ − 0.6ρ³ + 0.12ρ⁵ falls between its turning points
// ρ² = (1.8 ∓ √0.84)/1.2 and rises again, so a direction past the second one passes the
// local tests but shares its pixel with one inside the fold. limitedToFold clips the field
// at the first turning point (the fold, analytically), and the mapping is one-to-one again.
TEST(Projection, LimitedToFoldMakesAFoldingDistortionOneToOne) {
  Projection p;
  p.fx = p.fy = 1.0;
  p.cx = p.cy = 0.0;
  p.k1 = -0.6;
  p.k2 = 0.12;
  const double foldRho = std::sqrt((1.8 - std::sqrt(0.84)) / 1.2);
  EXPECT_NEAR(foldFieldAngle(p), std::atan(foldRho), 1e-12);
  const glm::dvec3 beyond(1.6, 0.0, 1.0);
  EXPECT_TRUE(project(p, beyond));  // the local tests alone let it through
  const Projection q = limitedToFold(p);
  EXPECT_NEAR(q.maxFieldAngle, std::atan(foldRho), 1e-12);
  EXPECT_FALSE(project(q, beyond));
  const double peak =
      foldRho * (1.0 - 0.6 * foldRho * foldRho + 0.12 * foldRho * foldRho * foldRho * foldRho);
  for (double rho = 0.01; rho < 2.0; rho += 0.01) {
    const glm::dvec3 d(0.8 * rho, 0.6 * rho, 1.0);
    const std::optional<glm::dvec2> px = project(q, d);
    EXPECT_EQ(px.has_value(), rho < foldRho) << rho;
    if (px) {
      const std::optional<glm::dvec3> back = unproject(q, *px);
      ASSERT_TRUE(back) << rho;
      EXPECT_LE(glm::length(*back - glm::normalize(d)), 1e-12) << rho;
    }
    EXPECT_EQ(unproject(q, glm::dvec2(0.8 * rho, 0.6 * rho)).has_value(), rho < peak) << rho;
  }
}

}  // namespace
}  // namespace camsim
