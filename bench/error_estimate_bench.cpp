// error_estimate_bench: the cost of a render's estimate of its own error
// (integrator/render/error_estimate.h) against the render it describes — issue 38's "Error
// estimate" cost line in docs/performance.md. Renders SCENE (default scenes/cornell_box.yaml
// at its own size) once at --spp samples per pixel on all cores with the CIE XYZ film, then
// runs estimateFromHalves on that render's Y and odd-sample means --rounds times on one
// thread. Printed: the render's CPU seconds (all threads), the estimate's milliseconds per
// call (CPU, best and median of the rounds) and their ratio, and the estimate itself.
//
// usage: error_estimate_bench [SCENE.yaml] [--spp N] [--rounds N]   (default 16 spp, 20 rounds)
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/bench_rounds.h"
#include "integrator/measure/bench_metrics.h"
#include "integrator/measure/bench_reference.h"
#include "integrator/render/error_estimate.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"

namespace {

using namespace camsim;

[[noreturn]] void usage() {
  std::fprintf(stderr, "usage: error_estimate_bench [SCENE.yaml] [--spp N] [--rounds N]\n");
  std::exit(2);
}

// A whole decimal number in [low, 1e6], or exit 2 naming the option.
int wholeNumber(const char* option, const char* text, int low) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text, &end, 10);
  if (errno != 0 || end == text || *end != '\0' || v < low || v > 1000000) {
    std::fprintf(stderr,
                 "error_estimate_bench: %s must be a whole number in [%d, 1000000], got '%s'\n",
                 option, low, text);
    std::exit(2);
  }
  return static_cast<int>(v);
}

}  // namespace

int main(int argc, char** argv) {
  std::string scenePath;
  int spp = 16, rounds = 20;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--spp" && i + 1 < argc) {
      spp = wholeNumber("--spp", argv[++i], 2);
    } else if (arg == "--rounds" && i + 1 < argc) {
      rounds = wholeNumber("--rounds", argv[++i], 1);
    } else if (!arg.empty() && arg[0] != '-' && scenePath.empty()) {
      scenePath = arg;
    } else {
      usage();
    }
  }
  if (scenePath.empty()) scenePath = std::string(CAMSIM_SOURCE_DIR) + "/scenes/cornell_box.yaml";
  try {
    const Scene scene(loadScene(scenePath));
    RenderOptions options;
    options.spp = spp;
    const double renderStart = processCpuSeconds();
    const RenderResult result = renderXyz(scene, options);
    const double renderCpu = processCpuSeconds() - renderStart;
    const Image& image = result.image;
    const int y = image.channelIndex("Y");
    std::vector<double> ms;
    ErrorMetrics estimate;
    for (int r = 0; r < rounds; ++r) {
      const double start = bench::threadCpuSeconds();
      estimate = estimateFromHalves(image, y, result.oddHalf, spp);
      ms.push_back(1e3 * (bench::threadCpuSeconds() - start));
    }
    std::sort(ms.begin(), ms.end());
    const double median = ms[ms.size() / 2];
    std::printf(
        "%s: %dx%d, %d spp: render %.3f s CPU; estimate %.2f ms CPU (best %.2f, %d rounds), "
        "%.3f %% of the render; estimated rMSE %.4g, MRAE %.4g\n",
        std::filesystem::path(scenePath).filename().c_str(), image.width, image.height, spp,
        renderCpu, median, ms.front(), rounds, 100.0 * median * 1e-3 / renderCpu, estimate.rmse,
        estimate.mrae);
  } catch (const InputError& e) {
    std::fprintf(stderr, "error_estimate_bench: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error_estimate_bench: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
