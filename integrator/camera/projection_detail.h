// Internals shared by the projection model files (projection.cpp, projection_fisheye.cpp,
// projection_omni.cpp); not part of the camera's interface — use projection.h.
#pragma once

#include <optional>

#include <glm/mat2x2.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/camera/projection.h"

namespace camsim::projection_detail {

// OpenCV's pinhole distortion coefficients (calib3d): radial rational k1…k6, tangential
// p1 p2, thin prism s1…s4, sensor tilt τx τy. OpenCV omnidir's k1 k2 p1 p2 are the same with the rest zero.
struct Distortion {
  double k1 = 0.0, k2 = 0.0, k3 = 0.0, k4 = 0.0, k5 = 0.0, k6 = 0.0;
  double p1 = 0.0, p2 = 0.0;
  double s1 = 0.0, s2 = 0.0, s3 = 0.0, s4 = 0.0;
  double tauX = 0.0, tauY = 0.0;  // rad, sensor tilt
};
Distortion openCvDistortion(const Projection& p);   // all twelve
Distortion omnidirDistortion(const Projection& p);  // k1 k2 p1 p2

// Undistorted → distorted normalised coordinates and the Jacobian ∂m_d/∂m (columns ∂/∂x,
// ∂/∂y); none where the rational denominator is ≤ 0 or the Jacobian's determinant is ≤ 0
// (the map folds over there, so it is not invertible).
struct Distorted {
  glm::dvec2 m;
  glm::dmat2 jacobian;
};
std::optional<Distorted> distort(const Distortion& d, glm::dvec2 m);
// d(ρ_d)/dρ of the radial part alone, ρ_d = ρ·(1 + k1ρ² + …)/(1 + k4ρ² + …); −1 where the
// denominator is ≤ 0.
double radialSlope(const Distortion& d, double rho);
// The inverse by damped Newton iteration from m = distorted, to ~1e-15; none when it does not
// converge or lands where distort() is not invertible.
std::optional<glm::dvec2> undistort(const Distortion& d, glm::dvec2 distorted);

// Radial models (kannala_brandt, equidistant, equisolid, stereographic, orthographic,
// ftheta, unified without its distortion, double_sphere): m = ρ(θ)·(X, Y)/√(X²+Y²).
struct Radius {
  double rho;   // ρ(θ)
  double drho;  // dρ/dθ
};
Radius radius(const Projection& p, double theta);
// The largest field angle imaged: min(maxFieldAngle, the model's own limit); `strict` when
// the model's limit itself is excluded (the mapping is singular there).
struct FieldLimit {
  double theta;
  bool strict;
};
FieldLimit fieldLimit(const Projection& p);
bool withinField(const FieldLimit& limit, double theta);
// θ(ρ): closed form or safeguarded Newton; none past the image circle.
std::optional<double> fieldAngle(const Projection& p, double rho);
// dΩ/dA over normalised film area at field angle θ: (sin θ / ρ) / (dρ/dθ).
double radialDensity(const Projection& p, double theta);

// Model-specific pieces in projection_omni.cpp.
Radius unifiedRadius(double xi, double theta);
std::optional<double> unifiedFieldAngle(double xi, double rho);
double unifiedLimit(double xi);
Radius doubleSphereRadius(double xi, double alpha, double theta);
std::optional<double> doubleSphereFieldAngle(double xi, double alpha, double rho);
double doubleSphereLimit(double xi, double alpha);
std::optional<glm::dvec2> projectEquirectangular(const Projection& p, glm::dvec3 d);
std::optional<glm::dvec3> unprojectEquirectangular(const Projection& p, glm::dvec2 pixel);
double equirectangularDensity(const Projection& p, glm::dvec2 pixel);

}  // namespace camsim::projection_detail
