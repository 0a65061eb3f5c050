// render(): the render loop. The image is cut into 16×16 tiles that TBB schedules over
// the threads; each pixel sample draws its numbers from its own stream (seed, pixel,
// sample index), so the result is bit-identical for any thread count.
//
// Per pixel sample (dimension slots in sampler.h): wavelengths → film position, uniform
// over the photosite → lens position (only if the camera has an aperture) → time from the
// shutter curve, offset by the row for a rolling shutter (only if something moves) →
// camera ray and its measurement weight → traceRadiance → film.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "integrator/render/path_tracer.h"
#include "integrator/scene/scene.h"
#include "sensor/base/image.h"
#include "sensor/model/spectral_response.h"

namespace camsim {

struct RenderOptions {
  int spp = 16;
  std::uint64_t seed = 0;
  int threads = 0;  // 0 = all hardware threads
  // Called from worker threads (serialised) as tiles finish: (tiles done, tiles total).
  std::function<void(int, int)> progress;
  // Checked between tiles; when set, the render stops early and reports cancelled.
  const std::atomic<bool>* cancel = nullptr;
  // Sample time even when the scene analysis says nothing moves (for tests: the image
  // must not change).
  bool forceTime = false;
  // Overrides the scene's render.sampler (benchmarks compare samplers).
  std::optional<SamplerKind> sampler;
  // When set, sees every ray cast, from the thread that casts it (ray_stats.h; camsim
  // bench records them with a RayRecorder and replays them).
  RayObserver* rayObserver = nullptr;
};

struct RenderStats {
  double seconds = 0.0;
  std::uint64_t samples = 0;          // pixel samples traced
  std::uint64_t rejectedSamples = 0;  // NaN/Inf radiance, dropped from the film
  RayCounts rays;
  int threads = 0;
  bool cancelled = false;
  ModelledDimensions modelled;  // what was integrated over

  double samplesPerSecond() const {
    return seconds > 0.0 ? static_cast<double>(samples) / seconds : 0.0;
  }
  double raysPerSecond() const {
    return seconds > 0.0 ? static_cast<double>(rays.total()) / seconds : 0.0;
  }
};

struct RenderResult {
  Image image;                // the first response's image (pixel means)
  std::vector<Image> images;  // one per response, in order
  Image aovs;                 // the scene's render.aovs (aov_film.h); empty without
  RenderStats stats;
};

RenderResult render(const Scene& scene, const SpectralResponse& response,
                    const RenderOptions& options);
// Several responses filled by the same samples (e.g. CIE XYZ and a sensor's electrons).
RenderResult render(const Scene& scene, const std::vector<const SpectralResponse*>& responses,
                    const RenderOptions& options);

}  // namespace camsim
