#include "integrator/camera/diffraction.h"

#include <algorithm>
#include <cmath>

#include "sensor/base/check.h"

namespace camsim {

Diffraction::Diffraction(const ApertureShape& stop, double workingFNumber)
    : grid_(PsfGrid::forStop(stop)), workingFNumber_(workingFNumber) {
  CAMSIM_CHECK(workingFNumber > 0.0 && std::isfinite(workingFNumber));
}

DiffractionSample Diffraction::sample(glm::vec2 u, float uChoice, const SampledWavelengths& lambda,
                                      const Photosite& site) const {
  constexpr int n = kWavelengthSamples;
  const int j = std::min(static_cast<int>(uChoice * static_cast<float>(n)), n - 1);
  DiffractionSample out;
  out.offset = grid_->sample(u) * metresPerUnit(static_cast<double>(lambda[j]));
  // Each wavelength's share of y: the photosite moved to y − c, in that wavelength's units
  // (its probability is scale-free); a point photosite: the density times scale² (the
  // common factor scale_j² cancels in w_i).
  const glm::dvec2 centre = site.offset + out.offset;
  const bool point = !(site.halfSide.x > 0.0 && site.halfSide.y > 0.0);
  double share[n];
  double mixture = 0.0;
  for (int i = 0; i < n; ++i) {
    const double scale = metresPerUnit(static_cast<double>(lambda[i]));
    share[i] =
        point ? grid_->density(centre / scale) / (scale * scale)
              : grid_->boxMass((centre - site.halfSide) / scale, (centre + site.halfSide) / scale);
    mixture += share[i];
  }
  mixture /= n;
  // Never 0 for the δ drawn (its own cell has probability); guarded all the same: no NaN.
  for (int i = 0; i < n; ++i)
    out.weight[i] = mixture > 0.0 ? static_cast<float>(share[i] / mixture) : 0.0f;
  return out;
}

glm::dvec2 Diffraction::sampleOffset(glm::vec2 u, double lambdaNm) const {
  return grid_->sample(u) * metresPerUnit(lambdaNm);
}

double Diffraction::psf(glm::dvec2 offset, double lambdaNm) const {
  const double scale = metresPerUnit(lambdaNm);
  return grid_->density(offset / scale) / (scale * scale);
}

}  // namespace camsim
