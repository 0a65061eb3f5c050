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
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "integrator/render/error_estimate.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"

namespace {

using namespace camsim;

double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

[[noreturn]] void usage() {
  std::fprintf(stderr, "usage: error_estimate_bench [SCENE.yaml] [--spp N] [--rounds N]\n");
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  std::string scenePath = std::string(CAMSIM_SOURCE_DIR) + "/scenes/cornell_box.yaml";
  int spp = 16, rounds = 20;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--spp" || arg == "--rounds") && i + 1 < argc) {
      (arg == "--spp" ? spp : rounds) = std::atoi(argv[++i]);
    } else if (!arg.empty() && arg[0] != '-') {
      scenePath = arg;
    } else {
      usage();
    }
  }
  if (spp < 2 || rounds < 1) {
    std::fprintf(stderr, "error_estimate_bench: --spp must be at least 2, --rounds at least 1\n");
    return 2;
  }
  try {
    const Scene scene(loadScene(scenePath));
    RenderOptions options;
    options.spp = spp;
    const SpectralResponse xyz = SpectralResponse::cieXyz();
    const double renderStart = cpuSeconds();
    const RenderResult result = render(scene, xyz, options);
    const double renderCpu = cpuSeconds() - renderStart;
    const Image& image = result.image;
    const int y = image.channelIndex("Y");
    std::vector<double> ms;
    ErrorMetrics estimate;
    for (int r = 0; r < rounds; ++r) {
      const double start = threadCpuSeconds();
      estimate = estimateFromHalves(image, y, result.oddHalf, spp);
      ms.push_back(1e3 * (threadCpuSeconds() - start));
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
  }
  return 0;
}
