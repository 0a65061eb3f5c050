// `camsim bench` arguments, plan and paths (bench_command.h).
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <memory>

#include <tbb/info.h>

#include "cli/args.h"
#include "cli/bench_command.h"
#include "cli/command_line.h"

namespace camsim {

const std::vector<std::string>& benchSuite() {
  static const std::vector<std::string> suite = {"cornell_box", "dof_chart", "motion_blur",
                                                 "metals_glass", "small_light"};
  return suite;
}

const std::vector<std::string>& peerSuite() {
  static const std::vector<std::string> suite = {"cornell_box", "dof_chart", "small_light"};
  return suite;
}

namespace {

// Names separated by commas into `target`.
void addListOption(CLI::App& app, const std::string& name, std::vector<std::string>& target,
                   const std::string& help) {
  app.add_option_function<std::string>(
         name,
         [&target, name](const std::string& list) {
           target.clear();
           for (std::size_t start = 0; start <= list.size();) {
             const std::size_t comma = std::min(list.find(',', start), list.size());
             const std::string item = list.substr(start, comma - start);
             if (item.empty())
               throw UsageError(name + " expects names separated by commas, got '" + list + "'");
             target.push_back(item);
             start = comma + 1;
           }
         },
         help)
      ->type_name("a,b");
}

// An integer option in [lo, hi] into `target` (a std::optional of an integer type); the
// range ends the help text, so --help states it.
template <class Target>
void addIntegerOption(CLI::App& app, const std::string& name, Target& target, std::int64_t lo,
                      std::int64_t hi, const std::string& help, const std::string& valueName) {
  const std::string flag = name.substr(name.rfind(',') + 1);
  app.add_option_function<std::string>(
         name,
         [&target, flag, lo, hi](const std::string& text) {
           target = static_cast<typename Target::value_type>(parseInteger(flag, text, lo, hi));
         },
         help + " [" + std::to_string(lo) + ", " + std::to_string(hi) + "]")
      ->type_name(valueName);
}

// A directory option: a non-empty path into `target` (a std::string or an optional one).
template <class Target>
void addDirectoryOption(CLI::App& app, const std::string& name, Target& target,
                        const std::string& help) {
  const std::string flag = name.substr(name.rfind(',') + 1);
  app.add_option_function<std::string>(
         name,
         [&target, flag](const std::string& text) {
           if (text.empty()) throw UsageError(flag + " needs a non-empty directory");
           target = text;
         },
         help)
      ->type_name("DIR");
}

std::unique_ptr<CLI::App> benchApp(BenchArgs& b) {
  auto app = newCommandApp(
      "bench",
      "Speed against error: renders each scene of the suite (cornell_box, dof_chart,\n"
      "motion_blur, metals_glass, small_light from scenes/) at a reduced resolution with both\n"
      "samplers (independent, sobol) at 1, 2, 4, ... max-spp samples per pixel, and measures\n"
      "the error of luminance Y against a cached high-spp reference: rMSE and MRAE\n"
      "(docs/bench.md). Prints the table and, per scene and sampler, the log-log slope of rMSE\n"
      "against time; then the limit: the tracer's rays/s against bare Embree traversal of the\n"
      "same recorded rays, thread scaling, motion-blur overhead, the build of a 1 M-triangle\n"
      "mesh and the load of a 1024x1024 texture.");
  app->add_flag("--guiding", b.guiding,
                "the sweeps render with path guiding (its training time included; the "
                "references stay unguided)");
  app->add_flag("--quick", b.quick,
                "a quick variant, under a minute (64 px, up to 64 spp, 512-spp references)");
  addDirectoryOption(*app, "-o,--out", b.outputDir,
                     "output directory (default bench-out/): bench.csv, bench_limit.csv, "
                     "bench.txt and bench.png (the plot needs python3-matplotlib)");
  addThreadsOption(*app, b.threads, "each scene's renders use them");
  addListOption(*app, "--scenes", b.scenes,
                "scenes to run: suite names or scene files (default: the suite)");
  addIntegerOption(*app, "--max-spp", b.maxSpp, 1, 65536,
                   "largest budget (default 256; --quick 64)", "N");
  addIntegerOption(*app, "--resolution", b.resolution, 4, 8192,
                   "long side of the sweeps' images in pixels (default 128; --quick 64)", "PX");
  addIntegerOption(*app, "--feature-resolution", b.featureResolution, 4, 8192,
                   "long side for the limit, thread scaling and motion overhead (default 512: "
                   "the scenes' own sizes; --quick 64)",
                   "PX");
  addIntegerOption(*app, "--ref-spp", b.refSpp, 2, 1 << 20,
                   "reference samples per pixel (default 8 x max-spp)", "N");
  addDirectoryOption(*app, "--cache", b.cacheDir,
                     "reference cache (default: bench-cache/ in the build directory)");
  addIntegerOption(*app, "--mesh-triangles", b.meshTriangles, 0, 100000000,
                   "triangles of the mesh-build test (default 1000000; 0 skips it)", "N");
  addIntegerOption(*app, "--texture-size", b.textureSize, 0, 16384,
                   "side of the texture-load test's random-colour PNG (default 1024; 0 skips it)",
                   "PX");
  CLI::Option* peer =
      app->add_option_function<std::string>(
             "--peer",
             [&b](const std::string& name) {
               if (name != "cycles")
                 throw UsageError("--peer expects 'cycles' (the only peer renderer), got '" + name +
                                  "'");
               b.peer = name;
             },
             "also render the peer scenes with Blender's Cycles (Debian's blender on PATH: "
             "scripts/setup.sh --peer) and compare the time each renderer needs for the same error "
             "(docs/bench.md)")
          ->type_name("cycles");
  app->add_flag("--peer-only", b.peerOnly,
                "with --peer: only the comparison (no sweeps, limit, mesh or texture tests)");
  addListOption(*app, "--peer-scenes", b.peerScenes,
                "scenes for --peer (default: cornell_box,dof_chart,small_light)");
  addIntegerOption(*app, "--peer-resolution", b.peerResolution, 4, 8192,
                   "long side of the --peer images (default 512: the scenes' own sizes)", "PX");
  addIntegerOption(*app, "--peer-ref-spp", b.peerRefSpp, 2, 1 << 20,
                   "--peer references' samples per pixel, each renderer (default 4096)", "N");
  addIntegerOption(*app, "--peer-spp", b.peerSpp, 1, 65536,
                   "Cycles' top spp, the target error (default 256; ladders start at 16)", "N");
  addIntegerOption(*app, "--peer-camsim-spp", b.peerCamsimSpp, 1, 1 << 20,
                   "camsim's top spp (default 4 x --peer-spp)", "N");
  {
    const OverrideSetting& setting = *findOverrideSetting("adaptive_threshold");
    app->add_option_function<std::string>(
           "--adaptive-threshold",
           [&b, &setting](const std::string& text) {
             Overrides o;
             parseOverride(o, setting, "--adaptive-threshold", text);
             b.adaptiveThreshold = o.adaptiveThreshold;
           },
           "also sweep Sobol' with adaptive sampling at threshold T (sampler sobol+adaptive; "
           "each budget is the most samples a pixel gets) and compare its time with plain "
           "Sobol' at the same error (docs/bench.md) " +
               overrideRangeText(setting))
        ->type_name("T");
  }
  addIntegerOption(*app, "--peer-rounds", b.peerRounds, 1, 20,
                   "with --peer: time each renderer's ladder K times, taking turns, each rung "
                   "keeping its fastest time (the report gives the range of the rounds' own "
                   "ratios; default 1)",
                   "K");
  addIntegerOption(*app, "--peer-max-depth", b.peerMaxDepth, 1, 1024,
                   "scattering events per path for both (Cycles: max_bounces = N - 1; "
                   "default: each scene's max_depth)",
                   "N");
  // Each --peer-* option is for --peer: without it the default bench ran, silently.
  for (const char* name : {"--peer-only", "--peer-scenes", "--peer-resolution", "--peer-ref-spp",
                           "--peer-spp", "--peer-camsim-spp", "--peer-rounds", "--peer-max-depth"})
    app->get_option(name)->needs(peer);
  app->footer(
      "Exit codes: 0 success, 1 internal error, 2 bad arguments or a scene that failed to\n"
      "load (the others' results are written).");
  return app;
}

}  // namespace

std::string benchUsageText() {
  BenchArgs b;
  return commandHelp(*benchApp(b));
}

BenchArgs parseBenchArgs(const std::vector<std::string>& args) {
  BenchArgs b;
  if (!parseCommand(*benchApp(b), args)) b.help = true;
  return b;
}

std::vector<int> BenchPlan::budgets() const {
  std::vector<int> spp;
  for (int n = 1; n <= maxSpp; n *= 2) spp.push_back(n);
  if (spp.back() != maxSpp) spp.push_back(maxSpp);
  return spp;
}

glm::ivec2 reducedResolution(glm::ivec2 res, int longSide) {
  const int side = std::max(res.x, res.y);
  if (side <= longSide) return res;
  const auto scaled = [&](int v) {
    return std::max(1, static_cast<int>(std::lround(static_cast<double>(v) * longSide / side)));
  };
  return {scaled(res.x), scaled(res.y)};
}

BenchPlan planBench(const BenchArgs& args) {
  BenchPlan p;
  if (args.quick) {
    p.longSide = 64;
    p.maxSpp = 64;
    p.featureLongSide = 64;
    p.captureSpp = 2;
    p.featureSpp = 8;
  }
  if (args.resolution) p.longSide = *args.resolution;
  if (args.featureResolution) p.featureLongSide = *args.featureResolution;
  if (args.maxSpp) p.maxSpp = *args.maxSpp;
  p.refSpp = args.refSpp ? *args.refSpp : 8 * p.maxSpp;
  p.refSpp += p.refSpp % 2;  // two equal halves
  if (args.meshTriangles) p.meshTriangles = *args.meshTriangles;
  if (args.textureSize) p.textureSize = *args.textureSize;
  p.adaptiveThreshold = args.adaptiveThreshold;
  p.threads = args.threads > 0 ? args.threads : tbb::info::default_concurrency();
  p.guiding = args.guiding;
  return p;
}

std::filesystem::path benchScenePath(const std::string& name) {
  const std::filesystem::path p(name);
  const std::string ext = p.extension().string();
  if (name.find('/') != std::string::npos || ext == ".yaml" || ext == ".yml" || ext == ".json")
    return p;
  const char* env = std::getenv("CAMSIM_SCENES");
  const std::filesystem::path dir =
      env && *env ? std::filesystem::path(env) : std::filesystem::path(CAMSIM_SCENES_DIR);
  return dir / (name + ".yaml");
}

std::filesystem::path defaultBenchCacheDir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return (ec ? std::filesystem::current_path() : exe.parent_path()) / "bench-cache";
}

}  // namespace camsim
