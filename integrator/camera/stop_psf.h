// StopPsf: the incoherent Fraunhofer point-spread function of the stop's shape, tabulated
// once per shape in units of λ·N_w, sampled exactly from the table and evaluated from it.
//
// | parameter | unit | meaning |
// |-----------|------|---------|
// | blades    | —    | 0: circular stop; N ≥ 3: the regular N-gon of Aperture (a vertex on +x) |
// | u         | λN_w | image-plane offset from the geometric image point, x right, y up |
// | p(u)      | (λN_w)⁻² | the PSF in these units: ∫ p d²u = 1 over the whole plane |
//
// The pupil is scaled to the stop of diameter D = 1 (the N-gon of the same area as the
// circle, as Aperture's), P its indicator, A = π/4 its area. In the Fraunhofer
// approximation the image-plane intensity of a point at offset x, for wavelength λ and
// working f-number N_w = z_i/D, is |P̂(x/(λ z_i))|² (P̂ the Fourier transform), so with
// u = x/(λN_w)
//
//   p(u) = |F(2πu)|² / A,   F(k) = ∫_P e^{−i k·ξ} d²ξ               (Parseval: ∫ p = 1)
//
// the same function for every λ and N_w: x = λN_w·u, PSF_λ(x) = p(x/(λN_w)) / (λN_w)².
//   circle:  p(u) = (π/4)·[2J₁(π|u|)/(π|u|)]²  (Airy), encircled energy
//            E(r) = 1 − J₀²(πr) − J₁²(πr)
//   N-gon:   F(k) = (i/|k|²) Σ_edges (k·n_e) L_e e^{−i k·m_e} sinc(k·t_e L_e/2)   (k ≠ 0)
//            (divergence theorem; edge e of length L_e, midpoint m_e, unit tangent t_e,
//            outward normal n_e; sinc x = sin x / x), F(0) = A.
//
// The table: a polar grid of cells, radial edges r_k = b·sinh(k/a) (b/a = 1/16 λN_w at
// the centre, a ratio e^{1/a} = 1.02 per cell far out) up to kRadius = 256 λN_w, and
// angular cells of 2π/M (one cell for the circle; M ≈ 1024, a multiple of N, for an
// N-gon). A cell's probability is its energy — for the circle exactly E(r_{k+1}) − E(r_k),
// for an N-gon two-point Gauss–Legendre on sub-cells of at most ½ λN_w radially and 1 λN_w
// along the arc (four times as many points change no cell by more than 0.3 %), computed
// over half a period π/N and mirrored and repeated (the N-gon's symmetry). The sampled
// distribution is that table: a cell with its probability, then a point uniform over the
// cell's area; density() is that distribution's density, so sampling is exact for it. The
// energy past r_rows ≥ kRadius is left out (the table is normalised to 1):
// truncatedEnergy(), 0.079 % for the circle, 0.083 % for 6 blades, 0.098 % for 3, 0.079 %
// for 64 (about P/(2π²R·A) for a stop of perimeter P and area A).
#pragma once

#include <complex>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>

#include "integrator/sampling/distribution_2d.h"

namespace camsim {

class StopPsf {
 public:
  static constexpr double kRadius = 256.0;  // λN_w: the table's extent

  explicit StopPsf(int blades);
  // The shared table of a shape (built once per blade count, then kept; thread-safe).
  static std::shared_ptr<const StopPsf> forBlades(int blades);

  int blades() const { return blades_; }
  // An offset u (λN_w) with density density(u), from uniform numbers in [0,1)².
  glm::dvec2 sample(glm::vec2 u) const;
  // The tabulated density at u ((λN_w)⁻²); 0 past kRadius.
  double density(glm::dvec2 u) const;
  // The density at radius r in the direction's column `column` (densityColumn(u)): for a
  // caller that evaluates several radii in one direction (the wavelengths of a path).
  int densityColumn(glm::dvec2 u) const;
  double densityAt(double r, int column) const;
  // The PSF's energy past kRadius, left out of the table (fraction of the total).
  double truncatedEnergy() const { return truncated_; }

  // The analytic PSF p(u) of the shape ((λN_w)⁻²) and the pupil's Fourier transform F(k).
  double analytic(glm::dvec2 u) const;
  std::complex<double> pupilTransform(glm::dvec2 k) const;
  // The circle's encircled energy E(r) within radius r (λN_w).
  static double airyEncircledEnergy(double r);

  // The radial cell of radius r (λN_w), rows() past the table; and its edges.
  int radialCell(double r) const;
  double radialEdge(int k) const;
  int rows() const { return rows_; }
  int columns() const { return columns_; }

 private:
  void buildCircle();
  void buildPolygon();

  int blades_;
  int rows_ = 0;               // radial cells
  int columns_ = 1;            // angular cells over 2π
  int period_ = 1;             // angular cells per period 2π/N (the circle: 1)
  std::vector<double> edges_;  // rows_ + 1 radial edges (λN_w)
  // The N-gon's edges, counter-clockwise: outward normal × length L, tangent × L/2, midpoint.
  struct Edge {
    glm::dvec2 normal, halfTangent, midpoint;
  };
  std::vector<Edge> polygonEdges_;
  std::vector<double> density_;  // rows_ × period_ cell densities, (λN_w)⁻²
  PiecewiseConstant2D table_;    // columns_ × rows_ cell probabilities
  double truncated_ = 0.0;
};

}  // namespace camsim
