// AovFilm: ground-truth outputs (AOVs) from the first hit of the very camera samples that
// make the image (the same film point, lens point, time and wavelengths), averaged with the
// image's pixel filter — a box over the photosite — so they describe the same footprint.
// Each value is the mean over the pixel's samples whose camera ray hit a surface; a pixel
// that no sample hit holds 0. Written as layers of NAME.exr (docs/output.md):
//
// | aov        | channels                     | unit | meaning |
// |------------|------------------------------|------|---------|
// | (any)      | coverage.A                   | —    | fraction of the pixel's samples that hit a surface |
// | depth      | depth.Z                      | m    | camera-space z of the hit: distance along the optical axis from the lens plane, at the sample's time |
// | distance   | distance.Z                   | m    | distance from the ray's origin on the lens (the pinhole) to the hit |
// | position   | P.X, P.Y, P.Z                | m    | world position (the scene file's coordinates, in double before the float sum) |
// | normal     | N.*, Ng.*, N_cam.*, Ng_cam.* | —    | shading and geometric normal, world axes and camera axes (OpenCV: x right, y down, z forward); each on the shape's front side; the mean of unit vectors (shorter at edges), not renormalised |
// | albedo     | albedo.R, .G, .B             | —    | the material's reflectance (material.h SurfaceAov) as linear Rec.709 under D65: per XYZ channel the ratio of the pixel's sums Σ r_c ρ D65/p ÷ Σ r_c D65/p over its samples' wavelengths (CIE 1931 r_c), so a spectrally flat ρ reads exactly ρ |
// | roughness  | roughness.Y                  | —    | the material's α as the scene gives it (diffuse 1, mirror 0) |
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/render/path_tracer.h"
#include "integrator/scene/scene_description.h"
#include "sensor/base/image.h"
#include "sensor/model/spectral_response.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

class AovFilm {
 public:
  AovFilm(glm::ivec2 resolution, const std::vector<Aov>& aovs);

  bool enabled() const { return !aovs_.empty(); }
  // One camera sample: its first hit (visible.hit false: a miss), the camera pose at the
  // sample's time (render space) and the render origin (world = render + origin).
  void addSample(glm::ivec2 pixel, const VisibleSurface& visible, const glm::dmat4& worldFromCamera,
                 const glm::dvec3& renderOrigin, const SampledWavelengths& lambda);
  // The channels in the table's order of the scene's aovs, coverage.A first.
  Image toImage(int samplesPerPixel) const;

 private:
  glm::ivec2 resolution_;
  std::vector<Aov> aovs_;
  std::vector<std::string> channels_;
  std::size_t stride_ = 0;  // sums per pixel: hit count, then one per channel
  std::vector<double> sums_;
  std::size_t albedoChannel_ = 0;     // of albedo.R (0: no albedo)
  std::vector<double> albedoWhite_;   // per pixel: the D65 white's X, Y, Z sums
  std::array<Spectrum, 3> whiteXyz_;  // x̄·D65, ȳ·D65, z̄·D65
};

}  // namespace camsim
