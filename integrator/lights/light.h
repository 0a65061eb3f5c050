// Light: a source of radiance the integrator samples directly (next-event estimation).
// Small closed set: area (a shape that emits), point, spot, distant (sun, with an angular
// diameter, or a delta direction) and environment map.
//   sample(ref, t, …) a point on the light at time t as seen from ref: incident radiance Li
//                   (W·m⁻²·sr⁻¹·nm⁻¹), direction wi (unit, towards the light), its
//                   solid-angle pdf (sr⁻¹) and the point (for the shadow ray).
//                   Delta lights (point, spot, delta sun): Li is the spectral irradiance
//                   at ref normal to wi (W·m⁻²·nm⁻¹) and pdf = 1.
//                   Infinite lights (sun, environment): the shadow ray runs to infinity.
//   pdf(ref, p)     solid-angle density of sample() producing the area-light point p
//   Le(d), pdfDirection(d)   infinite lights: radiance arriving along a ray of direction d
//                   that escapes the scene, and the solid-angle density of sampling −d…
//                   i.e. of wi = d
//   power()         Φ = ∫∫∫ L cosθ dA dω dλ (W), for choosing lights in proportion
//                   (infinite lights: through a disc of the scene's bounding radius)
#pragma once

#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/geometry/shape.h"
#include "sensor/spectra/sampled_spectrum.h"
#include "sensor/spectra/spectral_bins.h"

namespace camsim {

struct LightSample {
  SampledSpectrum L;
  glm::vec3 wi{0.0f};
  float pdf = 0.0f;
  SurfaceInteraction point;  // finite lights: the light point (for the shadow ray)
  bool delta = false;        // point/spot/delta sun: no MIS, L is irradiance (see above)
  bool infinite = false;     // sun/environment: shadow ray from ref along wi to infinity
};
// Zeroed twice per light sample (optional<LightSample>): CMakeLists.txt's -mmemset-strategy
// keeps zeroings up to CAMSIM_MEMSET_INLINE_BYTES (its compile definition) as plain stores
// (docs/performance.md).
static_assert(sizeof(std::optional<LightSample>) <= CAMSIM_MEMSET_INLINE_BYTES,
              "LightSample outgrew CMakeLists.txt's -mmemset-strategy threshold");

class Light {
 public:
  virtual ~Light() = default;
  virtual std::optional<LightSample> sample(const glm::vec3& ref, double time, float u1,
                                            glm::vec2 u2,
                                            const SampledWavelengths& lambda) const = 0;
  virtual float pdf(const glm::vec3& /*ref*/, const SurfaceInteraction& /*onLight*/) const {
    return 0.0f;
  }
  virtual double power() const = 0;
  virtual bool isDelta() const { return false; }
  virtual bool isInfinite() const { return false; }
  virtual SampledSpectrum Le(const glm::vec3& /*direction*/,
                             const SampledWavelengths& /*lambda*/) const {
    return SampledSpectrum(0.0f);
  }
  virtual float pdfDirection(const glm::vec3& /*direction*/) const { return 0.0f; }
  // The light's emission as bins of the scene's reference emission (area_light.h), for
  // the spectral control variate; null: its light is not written so.
  virtual const SpectralBins* controlVariateBins() const { return nullptr; }
  // Called once by Scene with the bounding sphere of the geometry (m), before power().
  virtual void setSceneBounds(const glm::vec3& /*centre*/, float /*radius*/) {}
};

}  // namespace camsim
