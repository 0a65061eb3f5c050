// `camsim bench` arguments, plan and paths (bench_command.h).
#include <unistd.h>

#include <cmath>
#include <cstdlib>

#include <tbb/info.h>

#include "cli/args.h"
#include "cli/bench_command.h"

namespace camsim {

const std::vector<std::string>& benchSuite() {
  static const std::vector<std::string> suite = {"cornell_box", "dof_chart", "motion_blur",
                                                 "metals_glass", "small_light"};
  return suite;
}

std::string benchUsageText() {
  return "usage: camsim bench [--quick] [--out DIR] [--threads N] [--scenes a,b,...] [--max-spp "
         "N]\n"
         "                    [--resolution PX] [--ref-spp N] [--cache DIR] [--mesh-triangles N]\n"
         "                    [--texture-size PX]\n"
         "\n"
         "Speed against error: renders each scene of the suite (cornell_box, dof_chart, "
         "motion_blur,\n"
         "metals_glass, small_light from scenes/) at a reduced resolution with both samplers\n"
         "(independent, sobol) at 1, 2, 4, ... max-spp samples per pixel, and measures the error "
         "of\n"
         "luminance Y against a cached high-spp reference: rMSE and MRAE (docs/bench.md). Prints "
         "the\n"
         "table and, per scene and sampler, the log-log slope of rMSE against time; then the "
         "limit:\n"
         "the tracer's rays/s against bare Embree traversal of the same recorded rays, thread "
         "scaling,\n"
         "motion-blur overhead, the build of a 1 M-triangle mesh and the load of a 1024x1024 "
         "texture.\n"
         "\n"
         "  --quick            a quick variant, under a minute (64 px, up to 64 spp, 512-spp "
         "references)\n"
         "  --out DIR          output directory (default bench-out/): bench.csv, bench_limit.csv,\n"
         "                     bench.txt and bench.png (the plot needs python3-matplotlib)\n"
         "  --threads N        worker threads (default: all cores)\n"
         "  --scenes a,b       scenes to run: suite names or scene files (default: the suite)\n"
         "  --max-spp N        largest budget (default 256; --quick 64)\n"
         "  --resolution PX    long side of the sweeps' images in pixels (default 128; --quick "
         "64)\n"
         "  --feature-resolution PX  long side for the limit, thread scaling and motion overhead\n"
         "                     (default 512: the scenes' own sizes; --quick 64)\n"
         "  --ref-spp N        reference samples per pixel (default 8 x max-spp)\n"
         "  --cache DIR        reference cache (default: bench-cache/ in the build directory)\n"
         "  --mesh-triangles N triangles of the mesh-build test (default 1000000; 0 skips it)\n"
         "  --texture-size PX  side of the texture-load test's random-colour PNG (default 1024; 0 "
         "skips it)\n";
}

BenchArgs parseBenchArgs(const std::vector<std::string>& args) {
  BenchArgs b;
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw UsageError(a + " needs a value");
      return args[++i];
    };
    if (a == "--help" || a == "-h") {
      b.help = true;
    } else if (a == "--quick") {
      b.quick = true;
    } else if (a == "--out" || a == "-o") {
      b.outputDir = value();
      if (b.outputDir.empty()) throw UsageError(a + " needs a non-empty directory");
    } else if (a == "--threads") {
      b.threads = static_cast<int>(parseInteger(a, value(), 1, 1024));
    } else if (a == "--scenes") {
      b.scenes.clear();
      const std::string list = value();
      for (std::size_t start = 0; start <= list.size();) {
        const std::size_t comma = std::min(list.find(',', start), list.size());
        const std::string name = list.substr(start, comma - start);
        if (name.empty())
          throw UsageError("--scenes expects names separated by commas, got '" + list + "'");
        b.scenes.push_back(name);
        start = comma + 1;
      }
    } else if (a == "--max-spp") {
      b.maxSpp = static_cast<int>(parseInteger(a, value(), 1, 65536));
    } else if (a == "--resolution") {
      b.resolution = static_cast<int>(parseInteger(a, value(), 4, 8192));
    } else if (a == "--feature-resolution") {
      b.featureResolution = static_cast<int>(parseInteger(a, value(), 4, 8192));
    } else if (a == "--ref-spp") {
      b.refSpp = static_cast<int>(parseInteger(a, value(), 2, 1 << 20));
    } else if (a == "--cache") {
      b.cacheDir = value();
      if (b.cacheDir->empty()) throw UsageError(a + " needs a non-empty directory");
    } else if (a == "--mesh-triangles") {
      b.meshTriangles = static_cast<std::uint64_t>(parseInteger(a, value(), 0, 100000000));
    } else if (a == "--texture-size") {
      b.textureSize = static_cast<int>(parseInteger(a, value(), 0, 16384));
    } else {
      throw UsageError("unknown bench option '" + a + "' (try 'camsim bench --help')");
    }
  }
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
  p.threads = args.threads > 0 ? args.threads : tbb::info::default_concurrency();
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
