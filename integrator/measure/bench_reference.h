// `camsim bench`: reference images, rendered once and cached.
//
// None of the bench scenes has a closed-form image (interreflections, glossy and glass
// transport, a moving fan), so each reference is a high-spp render: two independent Sobol'
// renders of refSpp/2 samples each (seeds 1001 and 1002; the bench's own renders use seed
// 1), averaged. The two halves also give the reference's own noise (bench_metrics.h).
//
// Cache: CACHE_DIR/NAME-HASH.exr with channels Y (the reference luminance), A.Y and B.Y
// (the halves). HASH (FNV-1a 64) covers a format tag, camsim's version, the scene file's
// text, the bench resolution, refSpp, and every file the scene loader read for the scene
// (SceneDescription::inputFiles: meshes, textures, maps, spectral tables wherever they were
// found — next to the scene, on its spectra_path or in luts/spectra — and the sensor's files)
// by path, size, modification time and content, and the tables built into camsim (the CIE
// observer, the named illuminants). Any change to these renders a new reference;
// nothing else does (a changed tracer with the same version reuses the old one: delete the
// cache directory to force a new one). Files are written
// under a temporary name and renamed (OutputSet), so a killed run never leaves a truncated
// reference behind.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include "integrator/measure/bench_metrics.h"

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "sensor/base/image.h"

namespace camsim {

// The seeds of a reference's two halves (the bench's and the peer bench's, peer_bench.h).
inline constexpr std::uint64_t kReferenceSeedA = 1001, kReferenceSeedB = 1002;

struct ReferenceRequest {
  std::string name;                               // scene name (file stem)
  std::string sceneText;                          // the scene file as read
  std::vector<std::filesystem::path> inputFiles;  // SceneDescription::inputFiles
  glm::ivec2 resolution{0};                       // px, the bench resolution the Scene was built at
  std::string sceneFile;                          // for the reference's metadata
  int spp = 2048;                                 // total: two halves of spp/2
  int threads = 0;
};

struct Reference {
  Image image;         // one channel: "Y"
  Image halfA, halfB;  // one channel each: "Y"
  ErrorMetrics noise;  // the floor (referenceNoise of the halves)
  std::filesystem::path file;
  bool fromCache = false;
  double seconds = 0.0;  // render time (0 when read from the cache)
};

// The cache key (16 hex digits): the FNV-1a hash of referenceKeyText.
std::string referenceKey(const ReferenceRequest& request);
std::string referenceKeyText(const ReferenceRequest& request);

// Reads CACHE_DIR/NAME-KEY.exr if present and valid, else renders `scene` (the request's
// scene, built by the caller) and writes it. `log` gets one line on what happened;
// `progress(done, total)` follows the render's tiles.
Reference obtainReference(const ReferenceRequest& request, const Scene& scene,
                          const std::filesystem::path& cacheDir, std::ostream& log,
                          const std::function<void(int, int)>& progress = {});

// The luminance channel of a film image as a one-channel "Y" image.
Image luminanceOf(const Image& xyz);

// The options of every bench render (references, sweeps, the limit): spp, seed, threads and
// sampler; the rest at RenderOptions' defaults for the caller to set.
RenderOptions benchRenderOptions(int spp, std::uint64_t seed, int threads, SamplerKind sampler);
// A render onto the CIE 1931 XYZ film (the bench's metrics use its Y).
RenderResult renderXyz(const Scene& scene, const RenderOptions& options);

}  // namespace camsim
