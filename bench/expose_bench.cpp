// expose_bench: re-exposure (sensor/io/expose_file.h, `camsim expose`) against a full render
// of the same scene — issue 37's row in docs/performance.md. It captures SCENE once at the
// given size and spp (render, sensor, ISP, every file written: what `camsim render` does,
// timed whole), then re-exposes that capture's NAME_raw.exr frame after frame, timed two
// ways:
//
//   expose only     exposeJobFrame: electrons → noise → ADC, one frame (DN in memory)
//   expose + write  that plus the frame's DNG and raw EXR (writeExposedFrame), into an
//                   OutputSet committed at the end, as `camsim expose` writes them
//
// Both loops run the frames one after another on one thread (the CLI runs frames in
// parallel; per-frame cost is what this measures). Printed: seconds per frame and frames/s,
// and the capture's seconds, as wall clock and as CPU time (the process's, all threads: the
// fair measure on a shared machine); the ratios are capture seconds ÷ seconds per frame.
//
// usage: expose_bench SCENE.yaml [--size WxH] [--spp N] [--frames N] [--out DIR]
//        (default 4000x3000, 1 spp, 8 frames, DIR a fresh folder under /tmp, removed after)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "integrator/capture/capture.h"
#include "integrator/capture/capture_writer.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "sensor/base/luts_directory.h"
#include "sensor/io/expose_file.h"
#include "sensor/io/output_set.h"

namespace {

using namespace camsim;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Args {
  std::string scene;
  int width = 4000, height = 3000, spp = 1, frames = 8;
  std::string out;
};

[[noreturn]] void usage() {
  std::fprintf(stderr,
               "usage: expose_bench SCENE.yaml [--size WxH] [--spp N] [--frames N] [--out DIR]\n");
  std::exit(2);
}

Args parseArgs(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--size" && i + 1 < argc) {
      if (std::sscanf(argv[++i], "%dx%d", &a.width, &a.height) != 2) usage();
    } else if ((arg == "--spp" || arg == "--frames") && i + 1 < argc) {
      (arg == "--spp" ? a.spp : a.frames) = std::atoi(argv[++i]);
    } else if (arg == "--out" && i + 1 < argc) {
      a.out = argv[++i];
    } else if (!arg.empty() && arg[0] != '-' && a.scene.empty()) {
      a.scene = arg;
    } else {
      usage();
    }
  }
  if (a.scene.empty() || a.width < 1 || a.height < 1 || a.spp < 1 || a.frames < 1) usage();
  return a;
}

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// CPU seconds of the whole process (all threads): on a shared VM the wall clock measures
// the neighbours too; CPU time is what the work cost.
double cpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = parseArgs(argc, argv);
  const bool scratch = args.out.empty();
  const fs::path dir =
      scratch ? fs::temp_directory_path() / ("camsim_expose_bench_" + std::to_string(::getpid()))
              : fs::path(args.out);
  try {
    SceneDescription desc = loadScene(args.scene);
    if (!desc.sensor) {
      std::fprintf(stderr, "error: %s has no sensor: nothing to expose\n", args.scene.c_str());
      return 2;
    }
    desc.camera.resolution = {args.width, args.height};
    desc.render.spp = args.spp;
    const std::string name = desc.name;
    fs::create_directories(dir);

    // The full render: capture (render, expose, develop) and every file written.
    const auto t0 = Clock::now();
    const double c0 = cpuSeconds();
    const CaptureResult result = capture(desc, CaptureOptions{});
    CaptureOutputOptions out;
    out.directory = dir / "render";
    OutputSet::prepareDirectory(out.directory);
    writeCapture(result, out);
    const double renderSeconds = since(t0), renderCpu = cpuSeconds() - c0;
    std::printf(
        "%s at %dx%d, %d spp: capture and write %.2f s wall, %.2f s CPU (render %.2f s "
        "wall)\n",
        args.scene.c_str(), args.width, args.height, args.spp, renderSeconds, renderCpu,
        result.stats.seconds);

    ExposeFileSettings settings;
    settings.frames = args.frames;
    settings.seed = 1;
    const ExposeJob job =
        prepareExpose(dir / "render" / (name + "_raw.exr"), settings, lutsDirectory());
    std::size_t checksum = 0;  // keeps the frames from being optimised away
    auto t = Clock::now();
    double c = cpuSeconds();
    for (int f = 0; f < args.frames; ++f)
      checksum += exposeJobFrame(job, static_cast<std::uint64_t>(f)).front().dn[0];
    const double exposeOnly = since(t) / args.frames;
    const double exposeOnlyCpu = (cpuSeconds() - c) / args.frames;
    t = Clock::now();
    c = cpuSeconds();
    {
      OutputSet outputs(dir / "expose");
      fs::create_directories(dir / "expose");
      writeExposedFrames(job, outputs, {});
      outputs.commit();
    }
    const double exposeWrite = since(t) / args.frames;
    const double exposeWriteCpu = (cpuSeconds() - c) / args.frames;
    std::printf(
        "expose only:    %.3f s/frame wall (%.2f frames/s), %.3f s CPU; the capture "
        "costs %.0fx (wall), %.0fx (CPU) (checksum %zu)\n",
        exposeOnly, 1.0 / exposeOnly, exposeOnlyCpu, renderSeconds / exposeOnly,
        renderCpu / exposeOnlyCpu, checksum);
    std::printf(
        "expose + write: %.3f s/frame wall (%.2f frames/s), %.3f s CPU; the capture "
        "costs %.0fx (wall), %.0fx (CPU)\n",
        exposeWrite, 1.0 / exposeWrite, exposeWriteCpu, renderSeconds / exposeWrite,
        renderCpu / exposeWriteCpu);
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  if (scratch) {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  return 0;
}
