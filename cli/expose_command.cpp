// `camsim expose`: a render's expected electrons → N raw frames (sensor/io/expose_file.h).
#include "cli/expose_command.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <ostream>

#include "cli/args.h"
#include "cli/command_line.h"
#include "integrator/capture/progress.h"
#include "sensor/base/format.h"
#include "sensor/base/luts_directory.h"
#include "sensor/io/output_set.h"

namespace camsim {
namespace {

std::unique_ptr<CLI::App> exposeApp(ExposeArgs& a) {
  auto app = newCommandApp(
      "expose",
      "Re-exposes a render's noise-free electrons (NAME_raw.exr) into N raw frames without\n"
      "rendering again: the layers electrons.<channel> (one for a Bayer or mono sensor) become\n"
      "N raw frames NAME_f<NNNN>.dng and NAME_f<NNNN>_raw.exr in DIR, written as\n"
      "`camsim render` writes its raw outputs; frame f draws its noise from (seed, f), so the\n"
      "same seed gives the same bytes. --exposure-scale X multiplies the electrons and the\n"
      "recorded exposure time (exact for a static scene; a scene that moved during the\n"
      "exposure, camsim:static_scene 0, is refused unless X = 1). docs/expose.md.");
  app->add_option("electrons", a.input, "a render's NAME_raw.exr (electrons.<channel> layers)")
      ->type_name("ELECTRONS.exr")
      ->required();
  app->add_option("--sensor", a.settings.sensor,
                  "sensor preset or YAML (default: the file's camsim:sensor); another sensor "
                  "only with the same CFA, photosite area and QE")
      ->type_name("S");
  app->add_option_function<double>(
         "--iso", [&a](double v) { a.settings.iso = v; },
         "ISO in [1, 1e7]: gain and noise at it (default: the file's camsim:iso); within the "
         "sensor's calibrated range")
      ->type_name("N");
  app->add_option("--exposure-scale", a.settings.exposureScale,
                  "X in (0, 1e6]: electrons and exposure time times X (default 1)")
      ->type_name("X");
  app->add_option("--frames", a.settings.frames,
                  "number of frames, 1 to " + std::to_string(kMaxExposeFrames) + " (default 1)")
      ->type_name("N");
  app->add_option_function<std::string>(
         "--seed",
         [&a](const std::string& t) {
           a.settings.seed = static_cast<std::uint64_t>(parseInteger("--seed", t, 0, INT64_MAX));
         },
         "noise seed (default: the file's camsim:noise_seed)")
      ->type_name("N");
  app->add_option("--noise", a.settings.noise, "none, photon or full (default full)")
      ->type_name("MODE");
  addThreadsOption(*app, a.threads, "frames run in parallel; the bytes do not depend on it");
  addOutputOption(*app, a.outputDir, "output directory (created if missing; default: out)");
  return app;
}

}  // namespace

std::string exposeUsageText() {
  ExposeArgs a;
  return commandHelp(*exposeApp(a));
}

ExposeArgs parseExposeArgs(const std::vector<std::string>& args) {
  ExposeArgs a;
  if (!parseCommand(*exposeApp(a), args)) {
    a.help = true;
    return a;
  }
  return a;
}

std::optional<std::vector<std::filesystem::path>> runExpose(const ExposeArgs& args,
                                                            std::ostream& log,
                                                            const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  const ExposeJob job = prepareExpose(args.input, args.settings, lutsDirectory());
  // Destroyed after `outputs` (which removes the temporaries): an interrupted run leaves no
  // folder it made (found by probing: SIGTERM left the new output folder, empty).
  NewDirectoryCleanup cleanup(args.outputDir);
  for (const auto& stale : OutputSet::prepareDirectory(args.outputDir))
    log << "removed " << stale.string() << " (left by a run that was killed)\n";
  OutputSet outputs(args.outputDir);
  // Every frame's temporaries named first (OutputSet is not thread-safe), then the frames
  // exposed and written in parallel, each to its own files.
  std::vector<std::vector<std::filesystem::path>> paths;
  for (long long f = 0; f < job.frames; ++f) {
    paths.emplace_back();
    for (const std::string& name : exposeFrameFiles(job, static_cast<std::uint64_t>(f)))
      paths.back().push_back(outputs.add(name));
  }
  std::mutex logMutex;
  std::atomic<long long> done{0};
  auto lastReport = start;
  tbb::task_arena arena(args.threads > 0 ? args.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(0LL, job.frames, [&](long long f) {
      // Interrupted: no frame starts (found by probing: a SIGINT killed the process and left
      // every frame's temporaries, 11 GB of them for 100 000 frames).
      if (cancel && cancel->load()) return;
      const auto frame = static_cast<std::uint64_t>(f);
      writeExposedFrame(job, frame, exposeJobFrame(job, frame), paths[static_cast<std::size_t>(f)]);
      const long long n = ++done;
      if (job.frames < 4) return;
      const std::lock_guard<std::mutex> lock(logMutex);
      const auto now = std::chrono::steady_clock::now();
      if (n == job.frames || now - lastReport > std::chrono::seconds(1)) {
        lastReport = now;
        log << "exposed " << n << "/" << job.frames << " frames\n" << std::flush;
      }
    });
  });
  if (cancel && cancel->load()) {
    log << "expose interrupted after " << done.load() << " of " << job.frames
        << " frames: nothing written\n";
    cleanup.abandon();
    return std::nullopt;  // `outputs` removes the temporaries, then `cleanup` the new folder
  }
  const std::vector<std::filesystem::path> files = outputs.commit();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  log << "exposed " << job.frames << (job.frames == 1 ? " frame" : " frames") << " of "
      << job.electrons.width << "x" << job.electrons.height << " (sensor " << job.sensor.name
      << ", ISO " << formatShortest(job.exposure.iso) << ", exposure "
      << formatShortest(job.exposure.exposureTimeS) << " s = " << formatShortest(job.exposureScale)
      << " x recorded, noise " << noiseModeName(job.noise) << ", seed " << job.seed << ") in "
      << formatSeconds(seconds) << "\n";
  for (const auto& f : files) log << "wrote " << f.string() << "\n";
  return files;
}

int runExposeCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log,
                     const std::atomic<bool>* cancel, const std::atomic<int>* signal) {
  const ExposeArgs parsed = parseExposeArgs(args);
  if (parsed.help) {
    out << exposeUsageText();
    return 0;
  }
  if (runExpose(parsed, log, cancel)) return 0;
  return 128 + (signal && signal->load() ? signal->load() : 2);
}

}  // namespace camsim
