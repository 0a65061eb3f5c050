// The camera sample of one pixel sample, drawn in the fixed dimension slots of sampler.h:
// diffraction's offset and wavelength choice (only if the stop diffracts) → wavelengths →
// film position, uniform over the photosensitive area (centred in the pixel, sides scaled by
// √fill) → lens position (only if the camera has an aperture) → time from the shutter
// curve, offset by the row for a rolling shutter (only if something moves).
// The sampler is left at kDimPath for the path. One function for the render loop
// (render.cpp) and the guide's training (path_guide.cpp), so both draw the same numbers.
#pragma once

#include <cmath>

#include <glm/vec2.hpp>

#include "integrator/camera/physical_camera.h"
#include "integrator/sampling/sampler.h"
#include "integrator/scene/scene.h"
#include "sensor/spectra/sampled_spectrum.h"

namespace camsim {

struct PixelSample {
  SampledWavelengths lambda;
  CameraSample camera;
};

// √fill: the photosensitive area's side as a fraction of the pixel's.
inline float photositeSide(const PhysicalCamera& camera) {
  return static_cast<float>(std::sqrt(camera.params().fillFactor));
}

template <typename SamplerT>
PixelSample drawPixelSample(SamplerT& sampler, const PhysicalCamera& camera,
                            const ModelledDimensions& dims, glm::ivec2 pixel, int sampleIndex,
                            float side) {
  sampler.startPixelSample(pixel, sampleIndex);
  CameraSample diffraction;
  if (dims.diffraction) {  // first: the Sobol' sampler's block from −2 then holds 0 … 13 too
    sampler.setDimension(kDimDiffraction);
    diffraction.pDiffraction = sampler.get2D();
    diffraction.uDiffractionWavelength = sampler.get1D();
  }
  sampler.setDimension(kDimWavelength);
  PixelSample ps{SampledWavelengths::sampleVisible(sampler.get1D()), diffraction};
  // A dispersing traced lens sends each wavelength its own way; it traces λ[0] only.
  if (camera.lensDisperses()) ps.lambda.terminateSecondary();
  CameraSample& cs = ps.camera;
  sampler.setDimension(kDimPixel);
  cs.pPhotosite = (sampler.get2D() - 0.5f) * side;
  cs.pFilm = glm::vec2(pixel) + 0.5f + cs.pPhotosite;
  if (dims.aperture) {
    sampler.setDimension(kDimLens);
    cs.pLens = sampler.get2D();
  }
  const Shutter& shutter = camera.shutter();
  cs.time = shutter.open();
  if (dims.time) {
    sampler.setDimension(kDimTime);
    cs.time = shutter.sample(static_cast<double>(sampler.get1D())) + shutter.rowOffset(pixel.y);
  }
  sampler.setDimension(kDimPath);
  return ps;
}

}  // namespace camsim
