// The radial projection models: film radius ρ (in units of fx, fy) as a function of the
// field angle θ, m = ρ(θ)·(X, Y)/√(X²+Y²), u = fx·mx + cx, v = fy·my + cy.
//
// | parameter      | unit | default | meaning |
// |----------------|------|---------|---------|
// | fx, fy         | px   | 500     | pixels per unit of ρ |
// | k1 … k4        | —    | 0       | kannala_brandt: θ³…θ⁹ terms; ftheta: θ²…θ⁵ terms |
// | maxFieldAngle  | rad  | π       | the image circle: largest θ imaged |
//
// | model          | ρ(θ)                                  | dρ/dθ                     | θ limit | θ(ρ) |
// |----------------|---------------------------------------|---------------------------|---------|------|
// | opencv (k = 0) | tan θ                                 | 1 / cos²θ                 | < π/2   | (projection.cpp) |
// | kannala_brandt | θ (1 + k1θ² + k2θ⁴ + k3θ⁶ + k4θ⁸)     | 1 + 3k1θ² + 5k2θ⁴ + 7k3θ⁶ + 9k4θ⁸ | π | Newton |
// | equidistant    | θ                                     | 1                         | π       | ρ |
// | equisolid      | 2 sin(θ/2)                            | cos(θ/2)                  | π       | 2 asin(ρ/2) |
// | stereographic  | 2 tan(θ/2)                            | 1 / cos²(θ/2)             | < π     | 2 atan(ρ/2) |
// | orthographic   | sin θ                                 | cos θ                     | < π/2   | asin ρ |
// | ftheta         | θ + k1θ² + k2θ³ + k3θ⁴ + k4θ⁵         | 1 + 2k1θ + 3k2θ² + 4k3θ³ + 5k4θ⁴ | π | Newton |
// | unified, double_sphere | projection_omni.cpp           |                           |         | closed form |
//
// Kannala–Brandt is OpenCV's fisheye model (OpenCV "Fisheye camera model" docs:
// θ_d = θ(1 + k1θ² + k2θ⁴ + k3θ⁶ + k4θ⁸), x' = (θ_d / r)·a with a = X/Z, r = √(a²+b²)); here
// θ = atan2(√(X²+Y²), Z) instead of atan(r), so it extends past 90° (rays behind the camera,
// FOV > 180°) where OpenCV's own functions fold back. The ideal mappings are the classical
// fisheye projections (e.g. Kannala & Brandt, PAMI 2006, Table 1); f-theta is NVIDIA
// DriveWorks' polynomial angle → pixel-radius model with its constant term 0. The model's θ
// limit is further capped by maxFieldAngle (the image circle of a real lens).
//
// Radiometry: dΩ = sin θ dθ dφ and dA = ρ dρ dφ in film units, so
//   dΩ/dA = (sin θ / ρ) / (dρ/dθ) / (fx·fy)     per px²,
// which is 1 for equisolid (equal-area), cos⁴(θ/2) for stereographic, sin θ / θ for
// equidistant, 1/cos θ for orthographic and cos³θ for the pinhole.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "integrator/camera/projection_detail.h"

namespace camsim::projection_detail {

Radius radius(const Projection& p, double theta) {
  const double t2 = theta * theta;
  switch (p.model) {
    case ProjectionModel::kOpenCv: {
      const double c = std::cos(theta);
      return {std::tan(theta), 1.0 / (c * c)};
    }
    case ProjectionModel::kKannalaBrandt:
      return {theta * (1.0 + t2 * (p.k1 + t2 * (p.k2 + t2 * (p.k3 + t2 * p.k4)))),
              1.0 + t2 * (3.0 * p.k1 + t2 * (5.0 * p.k2 + t2 * (7.0 * p.k3 + t2 * 9.0 * p.k4)))};
    case ProjectionModel::kEquisolid:
      return {2.0 * std::sin(0.5 * theta), std::cos(0.5 * theta)};
    case ProjectionModel::kStereographic: {
      const double c = std::cos(0.5 * theta);
      return {2.0 * std::tan(0.5 * theta), 1.0 / (c * c)};
    }
    case ProjectionModel::kOrthographic:
      return {std::sin(theta), std::cos(theta)};
    case ProjectionModel::kFTheta:
      return {theta * (1.0 + theta * (p.k1 + theta * (p.k2 + theta * (p.k3 + theta * p.k4)))),
              1.0 + theta * (2.0 * p.k1 +
                             theta * (3.0 * p.k2 + theta * (4.0 * p.k3 + theta * 5.0 * p.k4)))};
    case ProjectionModel::kUnified:
      return unifiedRadius(p.xi, theta);
    case ProjectionModel::kDoubleSphere:
      return doubleSphereRadius(p.xi, p.alpha, theta);
    case ProjectionModel::kEquidistant:
    case ProjectionModel::kEquirectangular:
      break;
  }
  return {theta, 1.0};
}

FieldLimit fieldLimit(const Projection& p) {
  double model = std::numbers::pi;
  bool strict = false;
  switch (p.model) {
    case ProjectionModel::kOpenCv:
    case ProjectionModel::kOrthographic:
      model = 0.5 * std::numbers::pi;
      strict = true;
      break;
    case ProjectionModel::kStereographic:
      strict = true;
      break;
    case ProjectionModel::kUnified:
      model = unifiedLimit(p.xi);
      strict = true;
      break;
    case ProjectionModel::kDoubleSphere:
      model = doubleSphereLimit(p.xi, p.alpha);
      strict = true;
      break;
    default:
      break;
  }
  if (p.maxFieldAngle < model) return {p.maxFieldAngle, false};
  return {model, strict};
}

bool withinField(const FieldLimit& limit, double theta) {
  return limit.strict ? theta < limit.theta : theta <= limit.theta;
}

namespace {

// θ with ρ(θ) = rho on [0, θmax] for a polynomial model increasing there: Newton's method
// kept inside a shrinking bracket (bisection when a step would leave it).
std::optional<double> polynomialFieldAngle(const Projection& p, double rho, double thetaMax) {
  if (rho > radius(p, thetaMax).rho) return std::nullopt;
  double lo = 0.0, hi = thetaMax, theta = std::min(rho, thetaMax);
  for (int iter = 0; iter < 200; ++iter) {
    const Radius r = radius(p, theta);
    const double f = r.rho - rho;
    if (f == 0.0) break;
    (f < 0.0 ? lo : hi) = theta;
    double next = theta - f / r.drho;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const double step = std::abs(next - theta);
    theta = next;
    if (step <= 1e-17 * (1.0 + theta) || hi - lo <= 1e-17 * (1.0 + theta)) break;
  }
  if (!(std::abs(radius(p, theta).rho - rho) <= 1e-13 * (1.0 + rho))) return std::nullopt;
  return theta;
}

}  // namespace

std::optional<double> fieldAngle(const Projection& p, double rho) {
  if (!std::isfinite(rho)) return std::nullopt;
  const FieldLimit limit = fieldLimit(p);
  std::optional<double> theta;
  switch (p.model) {
    case ProjectionModel::kOpenCv:
      theta = std::atan(rho);
      break;
    case ProjectionModel::kEquidistant:
      theta = rho;
      break;
    case ProjectionModel::kEquisolid:
      if (rho <= 2.0) theta = 2.0 * std::asin(0.5 * rho);
      break;
    case ProjectionModel::kStereographic:
      theta = 2.0 * std::atan(0.5 * rho);
      break;
    case ProjectionModel::kOrthographic:
      if (rho <= 1.0) theta = std::asin(rho);
      break;
    case ProjectionModel::kKannalaBrandt:
    case ProjectionModel::kFTheta:
      theta = polynomialFieldAngle(p, rho, limit.theta);
      break;
    case ProjectionModel::kUnified:
      theta = unifiedFieldAngle(p.xi, rho);
      break;
    case ProjectionModel::kDoubleSphere:
      theta = doubleSphereFieldAngle(p.xi, p.alpha, rho);
      break;
    case ProjectionModel::kEquirectangular:
      break;
  }
  if (!theta || !withinField(limit, *theta)) return std::nullopt;
  return theta;
}

double radialDensity(const Projection& p, double theta) {
  switch (p.model) {
    case ProjectionModel::kEquisolid:
      return 1.0;
    case ProjectionModel::kStereographic: {
      const double c = std::cos(0.5 * theta);
      return c * c * c * c;
    }
    case ProjectionModel::kOrthographic:
      return 1.0 / std::cos(theta);
    default:
      break;
  }
  const Radius r = radius(p, theta);
  // sin θ / ρ → 1 / (dρ/dθ) on the axis.
  const double sinOverRho = theta > 0.0 && r.rho > 0.0 ? std::sin(theta) / r.rho : 1.0 / r.drho;
  return sinOverRho / r.drho;
}

}  // namespace camsim::projection_detail
