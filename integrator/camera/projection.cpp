// Projection's dispatch, range checks and the OpenCV pinhole model (OpenCV calib3d,
// "Camera Calibration and 3D Reconstruction": the rational, tangential and thin-prism terms).
//
// | parameter | unit | default | meaning |
// |-----------|------|---------|---------|
// | k1, k2, k3 | —   | 0       | radial numerator: 1 + k1 r² + k2 r⁴ + k3 r⁶ |
// | k4, k5, k6 | —   | 0       | radial denominator: 1 + k4 r² + k5 r⁴ + k6 r⁶ |
// | p1, p2     | —   | 0       | tangential (decentring) |
// | s1 … s4    | —   | 0       | thin prism |
// | τx, τy     | rad | 0       | sensor tilt (Scheimpflug) about x, then y |
//
// For a direction (X, Y, Z) with Z > 0: x' = X/Z, y' = Y/Z, r² = x'² + y'²,
//   c   = (1 + k1 r² + k2 r⁴ + k3 r⁶) / (1 + k4 r² + k5 r⁴ + k6 r⁶)
//   x'' = x' c + 2 p1 x'y' + p2 (r² + 2x'²) + s1 r² + s2 r⁴
//   y'' = y' c + p1 (r² + 2y'²) + 2 p2 x'y' + s3 r² + s4 r⁴
// then the tilted sensor: with R = R_y(τy)·R_x(τx) (R_x = [1 0 0; 0 cτx sτx; 0 −sτx cτx],
// R_y = [cτy 0 −sτy; 0 1 0; sτy 0 cτy]) and the homography
//   H = [R₂₂ 0 −R₀₂; 0 R₂₂ −R₁₂; 0 0 1]·R,   (x''', y''', 1) ∝ H·(x'', y'', 1),
//   u = fx x''' + cx,  v = fy y''' + cy  (x''' = x'' without tilt).
// The inverse (x'', y'') → (x', y') has no closed form: damped Newton with the analytic
// Jacobian J = ∂(x'', y'')/∂(x', y'). The model is valid where the rational denominator is
// positive and det J > 0 (beyond the radius where a strong barrel distortion folds the image
// back, two directions would share a pixel). Radiometry: the undistorted plane z = 1 has
// dΩ/dA = (1 + r²)^(−3/2) = cos³θ, so at a pixel dΩ/dA = cos³θ / (det J · fx · fy).
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "integrator/camera/projection_detail.h"
#include "sensor/base/format.h"

namespace camsim {

namespace projection_detail {

Distortion openCvDistortion(const Projection& p) {
  return {p.k1, p.k2, p.k3, p.k4, p.k5, p.k6, p.p1, p.p2, p.s1, p.s2, p.s3, p.s4, p.tauX, p.tauY};
}

Distortion omnidirDistortion(const Projection& p) {
  Distortion d;
  d.k1 = p.k1;
  d.k2 = p.k2;
  d.p1 = p.p1;
  d.p2 = p.p2;
  return d;
}

std::optional<Distorted> distort(const Distortion& d, glm::dvec2 m) {
  const double x = m.x, y = m.y, r2 = x * x + y * y;
  const double num = 1.0 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3));
  const double den = 1.0 + r2 * (d.k4 + r2 * (d.k5 + r2 * d.k6));
  if (!(den > 0.0)) return std::nullopt;
  const double c = num / den;
  if (!(c > 0.0)) return std::nullopt;  // the point would be mirrored through the centre
  // dc/d(r²) and the thin-prism terms' d/d(r²).
  const double dnum = d.k1 + r2 * (2.0 * d.k2 + 3.0 * r2 * d.k3);
  const double dden = d.k4 + r2 * (2.0 * d.k5 + 3.0 * r2 * d.k6);
  const double dc = (dnum * den - num * dden) / (den * den);
  const double sx = d.s1 + 2.0 * d.s2 * r2, sy = d.s3 + 2.0 * d.s4 * r2;
  Distorted out;
  out.m = {x * c + 2.0 * d.p1 * x * y + d.p2 * (r2 + 2.0 * x * x) + r2 * (d.s1 + r2 * d.s2),
           y * c + d.p1 * (r2 + 2.0 * y * y) + 2.0 * d.p2 * x * y + r2 * (d.s3 + r2 * d.s4)};
  // glm matrices are column-major: jacobian[0] = ∂m_d/∂x, jacobian[1] = ∂m_d/∂y.
  out.jacobian[0] = {c + 2.0 * x * x * dc + 2.0 * d.p1 * y + 6.0 * d.p2 * x + 2.0 * x * sx,
                     2.0 * x * y * dc + 2.0 * d.p1 * x + 2.0 * d.p2 * y + 2.0 * x * sy};
  out.jacobian[1] = {2.0 * x * y * dc + 2.0 * d.p1 * x + 2.0 * d.p2 * y + 2.0 * y * sx,
                     c + 2.0 * y * y * dc + 6.0 * d.p1 * y + 2.0 * d.p2 * x + 2.0 * y * sy};
  if (d.tauX != 0.0 || d.tauY != 0.0) {
    // The tilt homography H (rows h0 h1 h2) and its Jacobian, chained after the distortion.
    const double ctx = std::cos(d.tauX), stx = std::sin(d.tauX);
    const double cty = std::cos(d.tauY), sty = std::sin(d.tauY);
    // Rows of R = R_y(τy)·R_x(τx).
    const glm::dvec3 q0(cty, sty * stx, -sty * ctx), q1(0.0, ctx, stx),
        q2(sty, -cty * stx, cty * ctx);
    const glm::dvec3 h0 = q2.z * q0 - q0.z * q2, h1 = q2.z * q1 - q1.z * q2, h2 = q2;
    const glm::dvec3 q(out.m, 1.0);
    const double w = glm::dot(h2, q);
    if (!(w > 0.0)) return std::nullopt;
    const glm::dvec2 t(glm::dot(h0, q) / w, glm::dot(h1, q) / w);
    glm::dmat2 jt;  // ∂t/∂(x'', y''), columns
    jt[0] = glm::dvec2(h0.x - t.x * h2.x, h1.x - t.y * h2.x) / w;
    jt[1] = glm::dvec2(h0.y - t.x * h2.y, h1.y - t.y * h2.y) / w;
    out.m = t;
    out.jacobian = jt * out.jacobian;
  }
  if (!(glm::determinant(out.jacobian) > 0.0)) return std::nullopt;
  return out;
}

double radialSlope(const Distortion& d, double rho) {
  const double r2 = rho * rho;
  const double num = 1.0 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3));
  const double den = 1.0 + r2 * (d.k4 + r2 * (d.k5 + r2 * d.k6));
  if (!(den > 0.0)) return -1.0;
  const double dnum = d.k1 + r2 * (2.0 * d.k2 + 3.0 * r2 * d.k3);
  const double dden = d.k4 + r2 * (2.0 * d.k5 + 3.0 * r2 * d.k6);
  return num / den + 2.0 * r2 * (dnum * den - num * dden) / (den * den);
}

std::optional<glm::dvec2> undistort(const Distortion& d, glm::dvec2 target) {
  // Start at the distorted point itself, moved towards the centre while that lies outside
  // the invertible region (a strong distortion whose fold is nearer than the target).
  glm::dvec2 m = target;
  std::optional<Distorted> cur = distort(d, m);
  for (int i = 0; i < 60 && !cur; ++i) cur = distort(d, m *= 0.5);
  if (!cur) return std::nullopt;
  for (int iter = 0; iter < 100; ++iter) {
    const glm::dvec2 f = cur->m - target;
    const double err = glm::length(f);
    // Converged to rounding: another step could only fail its backtracking (20 evaluations).
    if (err <= 1e-15 * (1.0 + glm::length(target))) break;
    const glm::dvec2 step = glm::inverse(cur->jacobian) * f;
    // Backtrack while the step leaves the invertible region or increases the residual.
    bool improved = false;
    for (double t = 1.0; t > 1e-6; t *= 0.5) {
      const glm::dvec2 next = m - t * step;
      const std::optional<Distorted> trial = distort(d, next);
      if (trial && glm::length(trial->m - target) < err) {
        m = next;
        cur = trial;
        improved = true;
        break;
      }
    }
    if (!improved || glm::length(step) <= 1e-16 * (1.0 + glm::length(m))) break;
  }
  if (!(glm::length(cur->m - target) <= 1e-12 * (1.0 + glm::length(target)))) return std::nullopt;
  return m;
}

}  // namespace projection_detail

namespace pd = projection_detail;

namespace {

glm::dvec2 toPixel(const Projection& p, glm::dvec2 m) {
  return {p.fx * m.x + p.cx, p.fy * m.y + p.cy};
}
glm::dvec2 toFilm(const Projection& p, glm::dvec2 px) {
  return {(px.x - p.cx) / p.fx, (px.y - p.cy) / p.fy};
}

// The unit direction at field angle θ towards film point m (|m| = ρ).
glm::dvec3 radialDirection(glm::dvec2 m, double theta) {
  const double rho = glm::length(m);
  if (rho == 0.0) return {0.0, 0.0, 1.0};
  const double s = std::sin(theta) / rho;
  return {s * m.x, s * m.y, std::cos(theta)};
}

}  // namespace

std::optional<glm::dvec2> project(const Projection& p, glm::dvec3 dirCv) {
  const double len = glm::length(dirCv);
  if (!(len > 0.0) || !std::isfinite(len)) return std::nullopt;
  const glm::dvec3 d = dirCv / len;
  if (p.model == ProjectionModel::kEquirectangular) return pd::projectEquirectangular(p, d);
  const double s = std::hypot(d.x, d.y);
  const double theta = std::atan2(s, d.z);
  if (!pd::withinField(pd::fieldLimit(p), theta)) return std::nullopt;
  switch (p.model) {
    case ProjectionModel::kOpenCv: {
      const std::optional<pd::Distorted> m =
          pd::distort(pd::openCvDistortion(p), {d.x / d.z, d.y / d.z});
      if (!m) return std::nullopt;
      return toPixel(p, m->m);
    }
    case ProjectionModel::kUnified: {
      // OpenCV omnidir: the unit sphere's point seen from (0, 0, −ξ), then k1 k2 p1 p2.
      const double w = d.z + p.xi;
      const std::optional<pd::Distorted> m =
          pd::distort(pd::omnidirDistortion(p), {d.x / w, d.y / w});
      if (!m) return std::nullopt;
      return toPixel(p, m->m);
    }
    default: {
      const double rho = pd::radius(p, theta).rho;
      const glm::dvec2 m = s > 0.0 ? glm::dvec2(d.x, d.y) * (rho / s) : glm::dvec2(rho, 0.0);
      return toPixel(p, m);
    }
  }
}

std::optional<glm::dvec3> unproject(const Projection& p, glm::dvec2 pixel) {
  if (p.model == ProjectionModel::kEquirectangular) return pd::unprojectEquirectangular(p, pixel);
  glm::dvec2 m = toFilm(p, pixel);
  if (!std::isfinite(m.x) || !std::isfinite(m.y)) return std::nullopt;
  if (p.model == ProjectionModel::kOpenCv) {
    const std::optional<glm::dvec2> mu = pd::undistort(pd::openCvDistortion(p), m);
    if (!mu || !pd::withinField(pd::fieldLimit(p), std::atan(glm::length(*mu))))
      return std::nullopt;
    return glm::normalize(glm::dvec3(mu->x, mu->y, 1.0));
  }
  if (p.model == ProjectionModel::kUnified) {
    const std::optional<glm::dvec2> mu = pd::undistort(pd::omnidirDistortion(p), m);
    if (!mu) return std::nullopt;
    m = *mu;
  }
  const std::optional<double> theta = pd::fieldAngle(p, glm::length(m));
  if (!theta) return std::nullopt;
  return radialDirection(m, *theta);
}

double solidAngleDensity(const Projection& p, glm::dvec2 pixel) {
  const std::optional<ModelRay> r = unprojectWithDensity(p, pixel);
  return r ? r->density : 0.0;
}

std::optional<ModelRay> unprojectWithDensity(const Projection& p, glm::dvec2 pixel) {
  if (p.model == ProjectionModel::kEquirectangular) {
    const std::optional<glm::dvec3> d = pd::unprojectEquirectangular(p, pixel);
    const double density = d ? pd::equirectangularDensity(p, pixel) : 0.0;
    if (!(density > 0.0)) return std::nullopt;
    return ModelRay{*d, density};
  }
  glm::dvec2 m = toFilm(p, pixel);
  if (!std::isfinite(m.x) || !std::isfinite(m.y)) return std::nullopt;
  const double perPixel = 1.0 / (p.fx * p.fy);
  double detJ = 1.0;  // of the distortion, where the model has one
  if (p.model == ProjectionModel::kOpenCv || p.model == ProjectionModel::kUnified) {
    const pd::Distortion dist =
        p.model == ProjectionModel::kOpenCv ? pd::openCvDistortion(p) : pd::omnidirDistortion(p);
    const std::optional<glm::dvec2> mu = pd::undistort(dist, m);
    if (!mu) return std::nullopt;
    detJ = glm::determinant(pd::distort(dist, *mu)->jacobian);
    m = *mu;
  }
  ModelRay r;
  if (p.model == ProjectionModel::kOpenCv) {
    const double r2 = glm::dot(m, m);
    if (!pd::withinField(pd::fieldLimit(p), std::atan(std::sqrt(r2)))) return std::nullopt;
    r = {glm::normalize(glm::dvec3(m.x, m.y, 1.0)),
         perPixel / (detJ * (1.0 + r2) * std::sqrt(1.0 + r2))};
  } else {
    const std::optional<double> theta = pd::fieldAngle(p, glm::length(m));
    if (!theta) return std::nullopt;
    r = {radialDirection(m, *theta), pd::radialDensity(p, *theta) * perPixel / detJ};
  }
  if (!(r.density > 0.0) || !std::isfinite(r.density)) return std::nullopt;
  return r;
}

namespace {

[[noreturn]] void fail(const SourceLocation& where, const std::string& key,
                       const std::string& msg) {
  throw InputError(where, key, msg);
}

}  // namespace

std::string imagedNothing(const Projection& p, glm::ivec2 resolution) {
  for (int i = 0; i < 81; ++i)
    if (unproject(p, {(i % 9) / 8.0 * (resolution.x - 1), (i / 9) / 8.0 * (resolution.y - 1)}))
      return "";
  return "the model images none of a 9 × 9 grid of the " + std::to_string(resolution.x) + "×" +
         std::to_string(resolution.y) +
         " image's pixels (fx, fy, cx, cy are in pixels, centres at integers)";
}

void checkProjection(const Projection& p, const SourceLocation& where,
                     const std::string& keyPrefix) {
  const auto key = [&](const char* name) { return keyPrefix + "." + name; };
  const struct {
    const char* name;
    double value;
  } finite[] = {{"cx", p.cx},      {"cy", p.cy}, {"k1", p.k1},      {"k2", p.k2}, {"k3", p.k3},
                {"k4", p.k4},      {"k5", p.k5}, {"k6", p.k6},      {"p1", p.p1}, {"p2", p.p2},
                {"s1", p.s1},      {"s2", p.s2}, {"s3", p.s3},      {"s4", p.s4}, {"tau_x", p.tauX},
                {"tau_y", p.tauY}, {"xi", p.xi}, {"alpha", p.alpha}};
  for (const auto& f : finite)
    if (!std::isfinite(f.value)) fail(where, key(f.name), "must be a finite number");
  for (const auto& [name, v] : {std::pair{"fx", p.fx}, std::pair{"fy", p.fy}})
    if (!(v > 0.0) || !std::isfinite(v))
      fail(where, key(name), "value " + formatNumber(v, 10) + " px must be positive and finite");
  if (!(p.maxFieldAngle > 0.0 && p.maxFieldAngle <= std::numbers::pi))
    fail(where, key("max_field_angle"),
         "value " + formatNumber(p.maxFieldAngle, 10) + " rad is out of range " +
             formatRange(0.0, std::numbers::pi, true));
  if (p.model == ProjectionModel::kUnified && !(p.xi >= 0.0))
    fail(where, key("xi"), "value " + formatNumber(p.xi, 10) + " must be ≥ 0");
  if (p.model == ProjectionModel::kDoubleSphere) {
    // ξ = −1 is singular (found by probing: the axis imaged as a circle, α = ½ gave 0/0 and
    // a black frame): (−1, 1].
    if (!(p.xi > -1.0 && p.xi <= 1.0))
      fail(where, key("xi"),
           "value " + formatNumber(p.xi, 10) + " is out of range " + formatRange(-1.0, 1.0, true) +
               " (ξ = −1 is singular: the axis maps to a circle)");
    if (!(p.alpha >= 0.0 && p.alpha <= 1.0))
      fail(where, key("alpha"),
           "value " + formatNumber(p.alpha, 10) + " is out of range " + formatRange(0.0, 1.0));
  }
  if (p.model == ProjectionModel::kKannalaBrandt || p.model == ProjectionModel::kFTheta) {
    // The polynomial must increase over the field imaged, or unproject would be ambiguous.
    const double limit = pd::fieldLimit(p).theta, fold = foldFieldAngle(p);
    if (fold < limit)
      fail(where, key("k1"),
           "k1 … k4 make the radius ρ(θ) stop increasing at field angle " +
               formatNumber(fold * 180.0 / std::numbers::pi, 6) + "°, inside max_field_angle " +
               formatNumber(limit * 180.0 / std::numbers::pi, 6) +
               "°: change them or lower max_field_angle");
  }
}

double foldFieldAngle(const Projection& p) {
  Projection whole = p;
  whole.maxFieldAngle = std::numbers::pi;
  const pd::FieldLimit limit = pd::fieldLimit(whole);
  // Whether the radial part still increases at field angle θ.
  const auto increasing = [&](double theta) {
    switch (p.model) {
      case ProjectionModel::kOpenCv:
        return pd::radialSlope(pd::openCvDistortion(p), std::tan(theta)) > 0.0;
      case ProjectionModel::kUnified:
        return pd::radialSlope(pd::omnidirDistortion(p), pd::unifiedRadius(p.xi, theta).rho) > 0.0;
      default:
        return pd::radius(p, theta).drho > 0.0;
    }
  };
  if (p.model != ProjectionModel::kOpenCv && p.model != ProjectionModel::kUnified &&
      p.model != ProjectionModel::kKannalaBrandt && p.model != ProjectionModel::kFTheta)
    return limit.theta;
  const double step = std::numbers::pi / 18000.0;  // 0.01°
  for (double lo = 0.0; lo < limit.theta;) {
    double hi = std::min(lo + step, limit.theta);
    if (limit.strict && hi == limit.theta) break;
    if (!increasing(hi)) {
      for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (increasing(mid) ? lo : hi) = mid;
      }
      return lo;
    }
    lo = hi;
  }
  return limit.theta;
}

Projection limitedToFold(Projection p) {
  p.maxFieldAngle = std::min(p.maxFieldAngle, foldFieldAngle(p));
  return p;
}

}  // namespace camsim
