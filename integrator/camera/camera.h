// Camera: maps a CameraSample (a point on the film, a point on the lens, a time) to a ray
// leaving the camera and the weight that ray carries in the pixel measurement.
//
// Film coordinates: pixels, continuous, origin at the top-left corner of the image,
// x right, y down; pixel (i, j) covers [i, i+1) × [j, j+1). The image is stored upright
// (the optical inversion is undone).
// Camera space: x right, y up, z forward (the viewing direction), origin at the pinhole /
// lens centre; worldFromCamera maps it to the (right-handed) world, in metres.
#pragma once

#include <optional>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "integrator/geometry/ray.h"
#include "sensor/spectra/sampled_spectrum.h"

namespace camsim {

class Shutter;

struct CameraSample {
  glm::vec2 pFilm{0.0f};  // pixels
  // pFilm's offset from the centre of the photosite it was drawn in (pixels, pFilm's axes);
  // used only by cameras whose stop diffracts: the weights integrate the PSF over the
  // photosite (diffraction.h), which is unbiased only if pFilm is uniform over the
  // photosite (the centred square of √fill of the pixel's sides) and this is its offset —
  // as drawPixelSample (integrator/render/pixel_sample.h) draws them.
  glm::vec2 pPhotosite{0.0f};
  glm::vec2 pLens{0.5f};  // [0,1)², used only by cameras with an aperture
  double time = 0.0;      // s
  // [0,1)² and [0,1), used only by cameras whose stop diffracts (diffraction.h): the offset
  // drawn from the PSF and the choice of the wavelength whose PSF it is drawn from.
  glm::vec2 pDiffraction{0.5f};
  float uDiffractionWavelength = 0.5f;
};

struct CameraRay {
  Ray ray;
  SampledSpectrum weight{1.0f};  // measurement weight: radiance → the film's quantity
};

class Camera {
 public:
  virtual ~Camera() = default;
  virtual std::optional<CameraRay> generateRay(const CameraSample& sample,
                                               const SampledWavelengths& lambda) const = 0;
  virtual glm::ivec2 resolution() const = 0;
  virtual bool hasAperture() const = 0;
  virtual bool moves(double t0, double t1) const = 0;
  virtual const Shutter& shutter() const = 0;
};

}  // namespace camsim
