#include "integrator/measure/bench_reference.h"

#include <algorithm>
#include <fstream>
#include <ostream>
#include <sstream>

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/file_status.h"
#include "sensor/base/fnv1a.h"
#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "sensor/io/output_set.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {
namespace {

// Part of every cache key: bumped when the renderer's expectation changes, so that no cached
// reference of the old estimator is reused (2: the aplanatic pupil).
constexpr const char* kFormatTag = "camsim-bench-reference/2";

std::string fileStamp(const std::filesystem::path& p, bool withContent) {
  std::error_code ec;
  std::ostringstream s;
  s << p.string() << "|" << std::filesystem::file_size(p, ec) << "|"
    << std::filesystem::last_write_time(p, ec).time_since_epoch().count();
  if (withContent) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    s << "|" << fnv1aHex(bytes.str());
  }
  return s.str();
}

// The cached file's three channels, or false if it is missing, unreadable or not ours.
bool readCached(const std::filesystem::path& file, const std::string& key, Reference& ref) {
  if (!isRegularFile(file)) return false;
  try {
    const ExrFile exr = readExr(file);
    const auto keyIt = std::find_if(exr.metadata.begin(), exr.metadata.end(),
                                    [](const auto& kv) { return kv.first == "camsim:bench_key"; });
    const int y = exr.image.channelIndex("Y"), a = exr.image.channelIndex("A.Y"),
              b = exr.image.channelIndex("B.Y");
    if (keyIt == exr.metadata.end() || keyIt->second != key || y < 0 || a < 0 || b < 0)
      return false;
    ref.image = exr.image.channel(y, "Y");
    ref.halfA = exr.image.channel(a, "Y");
    ref.halfB = exr.image.channel(b, "Y");
    return true;
  } catch (const InputError&) {
    return false;  // a damaged file: render anew
  }
}

}  // namespace

Image luminanceOf(const Image& xyz) {
  const int y = xyz.channelIndex("Y");
  CAMSIM_CHECK(y >= 0 && "the film image has a Y channel");
  return xyz.channel(y, "Y");
}

RenderOptions benchRenderOptions(int spp, std::uint64_t seed, int threads, SamplerKind sampler) {
  RenderOptions o;
  o.spp = spp;
  o.seed = seed;
  o.threads = threads;
  o.sampler = sampler;
  return o;
}

RenderResult renderXyz(const Scene& scene, const RenderOptions& options) {
  static const SpectralResponse response = SpectralResponse::cieXyz();
  return render(scene, response, options);
}

std::string referenceKeyText(const ReferenceRequest& request) {
  std::ostringstream key;
  const glm::ivec2 res = request.resolution;
  key << kFormatTag << "\n"
      << CAMSIM_VERSION << "\n"
      << formatSize(res.x, res.y) << "\n"
      << request.spp << "\n"
      << request.sceneText << "\n";
  for (const auto& f : request.inputFiles) key << fileStamp(f, true) << "\n";
  // The tables built into camsim, which no scene file names: the CIE observer (luminance
  // Y itself) and the named illuminants — every embedded table, by name and content.
  for (const std::string_view name : embeddedSpectralFileNames())
    key << name << "\n" << embeddedSpectralFile(name) << "\n";
  return key.str();
}

std::string referenceKey(const ReferenceRequest& request) {
  return fnv1aHex(referenceKeyText(request));
}

Reference obtainReference(const ReferenceRequest& request, const Scene& scene,
                          const std::filesystem::path& cacheDir, std::ostream& log,
                          const std::function<void(int, int)>& progress) {
  const std::string key = referenceKey(request);
  const std::string fileName = request.name + "-" + key + ".exr";
  Reference ref;
  ref.file = cacheDir / fileName;
  if (readCached(ref.file, key, ref)) {
    ref.fromCache = true;
    ref.noise = referenceNoise(ref.halfA, ref.halfB, 0);
    log << "reference " << request.name << ": cached " << ref.file.string() << "\n";
    return ref;
  }
  const int half = std::max(1, request.spp / 2);
  auto renderHalf = [&](std::uint64_t seed, int offset) {
    RenderOptions o = benchRenderOptions(half, seed, request.threads, SamplerKind::kSobol);
    if (progress)
      o.progress = [&progress, offset](int done, int total) {
        progress(offset * total + done, 2 * total);
      };
    return renderXyz(scene, o);
  };
  const RenderResult a = renderHalf(kReferenceSeedA, 0);
  const RenderResult b = renderHalf(kReferenceSeedB, 1);
  ref.seconds = a.stats.seconds + b.stats.seconds;
  ref.halfA = luminanceOf(a.image);
  ref.halfB = luminanceOf(b.image);
  ref.image = Image(ref.halfA.width, ref.halfA.height, {"Y"});
  for (std::size_t i = 0; i < ref.image.pixels.size(); ++i)
    ref.image.pixels[i] = 0.5f * (ref.halfA.pixels[i] + ref.halfB.pixels[i]);
  ref.noise = referenceNoise(ref.halfA, ref.halfB, 0);

  Image file(ref.image.width, ref.image.height, {"Y", "A.Y", "B.Y"});
  for (int y = 0; y < file.height; ++y)
    for (int x = 0; x < file.width; ++x) {
      file.at(x, y, 0) = ref.image.at(x, y, 0);
      file.at(x, y, 1) = ref.halfA.at(x, y, 0);
      file.at(x, y, 2) = ref.halfB.at(x, y, 0);
    }
  const Metadata meta = {
      {"camsim:version", CAMSIM_VERSION},
      {"camsim:bench_key", key},
      {"camsim:scene", request.sceneFile},
      {"camsim:spp", std::to_string(2 * half) + " (two halves of " + std::to_string(half) +
                         ", Sobol', seeds 1001 and 1002)"},
      {"camsim:render_seconds", formatNumber(ref.seconds, 6)},
      {"camsim:units", "CIE Y of the film (lm*s per photosite)"}};
  try {
    OutputSet::prepareDirectory(cacheDir);  // also cleans a killed run's temporaries
    OutputSet out(cacheDir);
    writeExr(out.add(fileName), file, meta, std::nullopt);
    out.commit();
  } catch (const InputError& e) {
    log << "warning: cannot write the reference cache (" << e.what() << "): not cached\n";
  }
  log << "reference " << request.name << ": rendered " << 2 * half << " spp in "
      << formatNumber(ref.seconds, 3) << " s (rMSE floor " << formatNumber(ref.noise.rmse, 3)
      << "), cached as " << ref.file.string() << "\n";
  return ref;
}

}  // namespace camsim
