// Test helper: a slanted edge imaged through a PhysicalCamera (thin lens or traced lens), at
// one wavelength, for the e-SFR (sensor/measure/slanted_edge.h) of the camera's blur.
//
// | parameter  | unit | meaning |
// |------------|------|---------|
// | distance   | m    | the target plane z = distance (camera at the origin looking along +z, pose identity) |
// | angleDeg   | °    | the edge's tilt from the camera's vertical; it runs through (0, 0, distance) |
// | spp        | —    | camera rays per pixel, a perfect square n²: film, lens and diffraction numbers each on a jittered n × n grid |
// | lambdaNm   | nm   | every ray's wavelength (SampledWavelengths::monochromatic) |
//
// The lit half-plane is n·p > 0, n = (cos θ, −sin θ) in the plane's (x, y). A pixel reads
//
//   Σ_k W_k · lit(ray_k) / Σ_k W_k
//
// over its rays (film point over the photosite, lens and diffraction numbers stratified,
// Pcg32 with a fixed seed; W_k the camera's measurement weight at lane 0, 0 for a lost ray): its
// exposure to a lit half-plane over its exposure to a uniformly lit plane, the same samples
// in both (a flat-field-corrected edge). The ratio removes the noise of the weights — a traced lens's
// pupil samples vary in weight, and some are lost — that would otherwise lie on the whole lit
// side; only the pixels the blur reaches are noisy. It is the edge's ESF integrated over the
// photosite, the camera's relative illumination across a pixel divided out. The film point
// follows drawPixelSample's rule (integrator/render/pixel_sample.h): uniform over the
// photosite (the pixel's centred square of √fill sides), pPhotosite its offset from the
// pixel's centre (a diffracting stop's weights integrate the PSF over the photosite around
// the film point from it: CameraSample, camera.h). drawPixelSample itself does not fit: it
// draws from the render's sampler, not these padded strata.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <numeric>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

#include "integrator/camera/physical_camera.h"
#include "integrator/render/pixel_sample.h"
#include "integrator/sampling/rng.h"
#include "sensor/base/image.h"
#include "sensor/spectra/sampled_spectrum.h"

namespace camsim::test {

struct EdgeTarget {
  double distance = 1.0;  // m
  double angleDeg = 5.0;  // °
};

// Fisher–Yates with the test's generator (std::shuffle's result differs between libraries).
inline void shuffleStrata(std::vector<int>& v, Pcg32& rng) {
  for (size_t i = v.size() - 1; i > 0; --i)
    std::swap(v[i], v[rng.next() % static_cast<std::uint32_t>(i + 1)]);
}

inline Image renderEdgeAtOneWavelength(const PhysicalCamera& camera, const EdgeTarget& target,
                                       int spp, float lambdaNm, std::uint64_t seed) {
  const glm::ivec2 res = camera.resolution();
  Image img(res.x, res.y, {"Y"});
  const SampledWavelengths lambda = SampledWavelengths::monochromatic(lambdaNm);
  const double t = target.angleDeg * std::numbers::pi / 180.0;
  const double nx = std::cos(t), ny = -std::sin(t);
  const float side = photositeSide(camera);  // the photosite's side, pixels
  const int n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(spp))));
  const auto stratum = [n](int i, float jitter) {
    return std::min((static_cast<float>(i) + jitter) / static_cast<float>(n), 0x1.fffffep-1f);
  };
  std::vector<int> lensStratum(static_cast<size_t>(n * n)), diffractionStratum(lensStratum.size());
  std::iota(lensStratum.begin(), lensStratum.end(), 0);
  std::iota(diffractionStratum.begin(), diffractionStratum.end(), 0);
  for (int py = 0; py < res.y; ++py) {
    Pcg32 rng(seed, static_cast<std::uint64_t>(py));  // one stream per row
    for (int px = 0; px < res.x; ++px) {
      // Padded strata: the film point, the lens point and diffraction's offset each on their
      // own jittered n × n grid, the three grids paired by random permutations.
      shuffleStrata(lensStratum, rng);
      shuffleStrata(diffractionStratum, rng);
      double lit = 0.0, all = 0.0;
      for (int k = 0; k < n * n; ++k) {
        float u[7];  // drawn in a fixed order (argument evaluation order is unspecified)
        for (float& v : u) v = rng.uniform();
        const int l = lensStratum[static_cast<size_t>(k)];
        const int d = diffractionStratum[static_cast<size_t>(k)];
        CameraSample cs;
        cs.pPhotosite = (glm::vec2(stratum(k % n, u[0]), stratum(k / n, u[1])) - 0.5f) * side;
        cs.pFilm = glm::vec2(static_cast<float>(px), static_cast<float>(py)) + 0.5f + cs.pPhotosite;
        cs.pLens = glm::vec2(stratum(l % n, u[2]), stratum(l / n, u[3]));
        cs.pDiffraction = glm::vec2(stratum(d % n, u[4]), stratum(d / n, u[5]));
        cs.uDiffractionWavelength = u[6];
        const auto r = camera.generateRay(cs, lambda);
        if (!r || !(r->ray.d.z > 0.0f)) continue;
        const double w = static_cast<double>(r->weight[0]);
        const double s =
            (target.distance - static_cast<double>(r->ray.o.z)) / static_cast<double>(r->ray.d.z);
        const double x = static_cast<double>(r->ray.o.x) + s * static_cast<double>(r->ray.d.x);
        const double y = static_cast<double>(r->ray.o.y) + s * static_cast<double>(r->ray.d.y);
        all += w;
        if (nx * x + ny * y > 0.0) lit += w;
      }
      img.at(px, py, 0) = all > 0.0 ? static_cast<float>(lit / all) : 0.0f;
    }
  }
  return img;
}

}  // namespace camsim::test
