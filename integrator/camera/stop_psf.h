// StopPsf: the incoherent Fraunhofer point-spread function of the stop's shape in units of
// λ·N_w, in closed form (the circle's Airy pattern, the N-gon's edge sum).
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
// Tabulated for sampling and box integrals by PsfGrid (psf_grid.h).
#pragma once

#include <complex>
#include <vector>

#include <glm/vec2.hpp>

namespace camsim {

class StopPsf {
 public:
  explicit StopPsf(int blades);  // cheap: the N-gon's edges (PsfGrid caches what is costly)

  int blades() const { return blades_; }
  // The analytic PSF p(u) of the shape ((λN_w)⁻²) and the pupil's Fourier transform F(k).
  double analytic(glm::dvec2 u) const;
  std::complex<double> pupilTransform(glm::dvec2 k) const;
  // The circle's encircled energy E(r) within radius r (λN_w).
  static double airyEncircledEnergy(double r);

 private:
  int blades_;
  // The N-gon's edges, counter-clockwise: outward normal × length L, tangent × L/2, midpoint.
  struct Edge {
    glm::dvec2 normal, halfTangent, midpoint;
  };
  std::vector<Edge> polygonEdges_;
};

}  // namespace camsim
