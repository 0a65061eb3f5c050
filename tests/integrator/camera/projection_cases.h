// Test support: one typical camera per projection model (a calibrated-looking set of
// coefficients, an image that the model fills), shared by the projection tests.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

#include <glm/vec2.hpp>

#include "integrator/camera/projection.h"

namespace camsim::test {

struct ProjectionCase {
  const char* name;
  Projection p;
  glm::ivec2 size;          // image size, px
  double testedFieldAngle;  // rad: directions up to this are round-tripped
  double imageRadius;       // radial models: the image circle's radius in film units; 0: none
};

inline std::vector<ProjectionCase> projectionCases() {
  constexpr double deg = std::numbers::pi / 180.0;
  std::vector<ProjectionCase> cases;
  cases.reserve(16);  // add() returns a reference into the vector
  const auto add = [&](const char* name, ProjectionModel model, double f, glm::ivec2 size,
                       double maxField, double tested, double radius) -> Projection& {
    Projection p;
    p.model = model;
    p.fx = f;
    p.fy = 0.98 * f;  // non-square pixels
    p.cx = 0.5 * size.x - 0.5;
    p.cy = 0.5 * size.y - 0.5;
    p.maxFieldAngle = maxField;
    cases.push_back({name, p, size, tested, radius});
    return cases.back().p;
  };
  Projection& cv =
      add("opencv", ProjectionModel::kOpenCv, 600.0, {640, 480}, std::numbers::pi, 38.0 * deg, 0.0);
  cv.k1 = -0.21, cv.k2 = 0.05, cv.k3 = 0.001, cv.k4 = 0.1, cv.k5 = 0.01, cv.k6 = 0.001;
  cv.p1 = 0.001, cv.p2 = -0.0005, cv.s1 = 0.002, cv.s2 = -0.0003, cv.s3 = 0.001, cv.s4 = 0.0002;
  Projection& tilt = add("opencv_tilt", ProjectionModel::kOpenCv, 600.0, {640, 480},
                         std::numbers::pi, 38.0 * deg, 0.0);
  tilt = cases[cases.size() - 2].p;  // the same lens on a sensor tilted by 3° and −2°
  tilt.tauX = 3.0 * deg, tilt.tauY = -2.0 * deg;

  const double kbMax = 100.0 * deg, t2 = kbMax * kbMax;
  Projection& kb = add("kannala_brandt", ProjectionModel::kKannalaBrandt, 260.0, {1000, 1000},
                       kbMax, kbMax, 0.0);
  kb.k1 = 0.02, kb.k2 = -0.003, kb.k3 = 0.0005, kb.k4 = -0.00005;
  cases.back().imageRadius =
      kbMax * (1.0 + t2 * (kb.k1 + t2 * (kb.k2 + t2 * (kb.k3 + t2 * kb.k4))));

  add("equidistant", ProjectionModel::kEquidistant, 280.0, {1000, 1000}, 100.0 * deg, 100.0 * deg,
      100.0 * deg);
  add("equisolid", ProjectionModel::kEquisolid, 240.0, {1000, 1000}, std::numbers::pi, 170.0 * deg,
      2.0);
  add("stereographic", ProjectionModel::kStereographic, 20.0, {1000, 1000}, 170.0 * deg,
      170.0 * deg, 2.0 * std::tan(85.0 * deg));
  add("orthographic", ProjectionModel::kOrthographic, 480.0, {1000, 1000}, std::numbers::pi,
      85.0 * deg, 1.0);

  const double ftMax = 105.0 * deg;
  Projection& ft = add("ftheta", ProjectionModel::kFTheta, 265.0, {1000, 1000}, ftMax, ftMax, 0.0);
  ft.k1 = -0.02, ft.k2 = 0.01, ft.k3 = -0.002, ft.k4 = 0.0001;
  cases.back().imageRadius =
      ftMax * (1.0 + ftMax * (ft.k1 + ftMax * (ft.k2 + ftMax * (ft.k3 + ftMax * ft.k4))));

  Projection& un =
      add("unified", ProjectionModel::kUnified, 280.0, {1000, 1000}, 110.0 * deg, 110.0 * deg, 0.0);
  un.xi = 0.9, un.k1 = -0.02, un.k2 = 0.002, un.p1 = 0.0005, un.p2 = -0.0003;
  // ξ > 1: the image ends where ρ(θ) turns back, at cos θ = −1/ξ, ρ = 1/√(ξ² − 1).
  Projection& un2 = add("unified_xi1.5", ProjectionModel::kUnified, 500.0, {1000, 1000},
                        std::numbers::pi, 125.0 * deg, 1.0 / std::sqrt(1.5 * 1.5 - 1.0));
  un2.xi = 1.5;

  Projection& ds = add("double_sphere", ProjectionModel::kDoubleSphere, 220.0, {1000, 1000},
                       110.0 * deg, 110.0 * deg, 0.0);
  ds.xi = -0.2, ds.alpha = 0.6;
  {
    const double c = std::cos(110.0 * deg), s = std::sin(110.0 * deg);
    const double d2 = std::sqrt(1.0 + 2.0 * ds.xi * c + ds.xi * ds.xi);
    cases.back().imageRadius = s / (ds.alpha * d2 + (1.0 - ds.alpha) * (ds.xi + c));
  }

  Projection& eq = add("equirectangular", ProjectionModel::kEquirectangular, 1.0, {720, 360},
                       std::numbers::pi, std::numbers::pi, 0.0);
  eq.fx = 720.0 / (2.0 * std::numbers::pi);
  eq.fy = 360.0 / std::numbers::pi;
  return cases;
}

}  // namespace camsim::test
