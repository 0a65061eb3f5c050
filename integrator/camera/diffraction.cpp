#include "integrator/camera/diffraction.h"

#include <algorithm>
#include <cmath>

#include "sensor/base/check.h"

namespace camsim {

Diffraction::Diffraction(const ApertureShape& stop, double workingFNumber)
    : psf_(StopPsf::forBlades(stop.blades)),
      workingFNumber_(workingFNumber),
      cosRotation_(std::cos(stop.rotation)),
      sinRotation_(std::sin(stop.rotation)) {
  CAMSIM_CHECK(workingFNumber > 0.0 && std::isfinite(workingFNumber));
}

DiffractionSample Diffraction::sample(glm::vec2 u, float uChoice,
                                      const SampledWavelengths& lambda) const {
  constexpr int n = kWavelengthSamples;
  const int j = std::min(static_cast<int>(uChoice * static_cast<float>(n)), n - 1);
  // The offset in the table's units (the stop unturned) and in metres for λ_j.
  const glm::dvec2 t = psf_->sample(u);
  const double scaleJ = static_cast<double>(lambda[j]) * 1e-9 * workingFNumber_;  // m per λN_w
  DiffractionSample out;
  out.offset = toFilm(t, scaleJ);
  // Every wavelength's PSF at this δ: the same direction (column), radius |t|·scale_j/scale_i.
  const int column = psf_->densityColumn(t);
  const double radius = std::hypot(t.x, t.y);
  double density[n];
  double mixture = 0.0;
  for (int i = 0; i < n; ++i) {
    const double ratio = static_cast<double>(lambda[j]) / static_cast<double>(lambda[i]);
    // PSF_λi(δ) · scale_j² (the common factor cancels in w_i).
    density[i] = psf_->densityAt(radius * ratio, column) * ratio * ratio;
    mixture += density[i];
  }
  mixture /= n;
  // Never 0 for the δ drawn (its own cell has energy); guarded all the same: no NaN.
  for (int i = 0; i < n; ++i)
    out.weight[i] = mixture > 0.0 ? static_cast<float>(density[i] / mixture) : 0.0f;
  return out;
}

glm::dvec2 Diffraction::sampleOffset(glm::vec2 u, double lambdaNm) const {
  return toFilm(psf_->sample(u), lambdaNm * 1e-9 * workingFNumber_);
}

double Diffraction::psf(glm::dvec2 offset, double lambdaNm) const {
  const double scale = lambdaNm * 1e-9 * workingFNumber_;
  // R⁻¹ offset / scale: back into the table's axes and units.
  const glm::dvec2 t((cosRotation_ * offset.x + sinRotation_ * offset.y) / scale,
                     (-sinRotation_ * offset.x + cosRotation_ * offset.y) / scale);
  return psf_->density(t) / (scale * scale);
}

}  // namespace camsim
