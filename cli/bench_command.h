// `camsim bench`: speed against error, and the distance to the limit of bare traversal.
//
//   camsim bench [--quick] [--out DIR] [--threads N] [--scenes a,b] [--max-spp N]
//                [--resolution PX] [--feature-resolution PX] [--ref-spp N] [--cache DIR]
//                [--mesh-triangles N] [--texture-size PX]
//                [--peer cycles [--peer-only] [--peer-scenes a,b] [--peer-resolution PX]
//                 [--peer-ref-spp N] [--peer-spp N] [--peer-camsim-spp N] [--peer-max-depth N]]
// (the option table, with each option's range, is in bench_args.cpp: camsim bench --help)
//
// For each scene of the suite (scenes/NAME.yaml: cornell_box, dof_chart, motion_blur,
// metals_glass, small_light), at a reduced resolution (long side PX), each sampler
// (independent, sobol; seed 1) renders at 1, 2, 4, … max-spp samples per pixel; each image's
// error on luminance Y against the scene's reference (bench_reference.h) is measured
// (bench_metrics.h), and rMSE against seconds is fitted in log-log per sampler. Then the
// limit and the costs of threads, motion blur and mesh building (bench_limit.h).
//
// Output: the tables on stdout; DIR/bench.csv (one row per render), DIR/bench_limit.csv,
// DIR/bench.txt (the report as printed) and, when /usr/bin/python3 has matplotlib,
// DIR/bench.png (scripts/bench_plot.py, embedded; CAMSIM_PYTHON replaces the interpreter).
// Progress on stderr. References are cached in --cache (default: bench-cache/ beside the
// camsim binary, i.e. in the build directory). A scene that fails to load is reported and
// skipped; the command then exits with 2 after writing the others' results.
// --peer cycles adds the side-by-side comparison with Blender's Cycles
// (integrator/measure/peer_bench.h) to the report and writes DIR/bench_peer.csv (the ladders),
// DIR/bench_peer_equal.csv (the equal-error lines) and, with matplotlib, DIR/bench_peer.png
// (scripts/peer_plot.py: error against time); it needs
// `blender` on PATH (exit 2 without it: scripts/setup.sh --peer installs Debian's).
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

namespace camsim {

struct BenchArgs {
  bool quick = false;
  bool help = false;
  bool guiding = false;  // the sweeps render with path guiding (the references never do)
  std::string outputDir = "bench-out";
  int threads = 0;                  // 0: all cores
  std::vector<std::string> scenes;  // empty: benchSuite(); a name or a path to a scene file
  std::optional<int> maxSpp, resolution, refSpp, featureResolution;
  std::optional<std::string> cacheDir;
  std::optional<std::uint64_t> meshTriangles;  // 0: skip the mesh build
  std::optional<int> textureSize;              // 0: skip the texture load
  // --peer cycles (integrator/measure/peer_bench.h): camsim against Blender's Cycles.
  std::optional<std::string> peer;      // "cycles"
  bool peerOnly = false;                // skip the sweeps, the limit and the rest
  std::vector<std::string> peerScenes;  // empty: peerSuite()
  std::optional<int> peerResolution, peerRefSpp, peerSpp, peerCamsimSpp, peerMaxDepth;
  std::optional<int> peerRounds;  // timed ladders per renderer (each rung its fastest)
  // --adaptive-threshold: also sweep Sobol' with adaptive sampling at this threshold.
  std::optional<double> adaptiveThreshold;
};

// args[0] == "bench". UsageError on bad usage. Parsed with the command's option table
// (cli/command_line.h), which also gives benchUsageText(), the --help text.
BenchArgs parseBenchArgs(const std::vector<std::string>& args);
std::string benchUsageText();
const std::vector<std::string>& benchSuite();
// The suite scenes --peer cycles translates: cornell_box, dof_chart, small_light.
const std::vector<std::string>& peerSuite();

// What a run does, from the arguments (defaults differ with --quick).
struct BenchPlan {
  int longSide = 128;  // px: the sweeps' images
  int maxSpp = 256;
  int refSpp = 2048;
  // The limit, thread scaling and motion overhead render each scene at its own resolution,
  // reduced to this long side if larger (the suite's scenes are at most 512 px: as given;
  // the Cornell box is 512 × 512, the size the throughput targets are stated for).
  int featureLongSide = 512;  // px
  int captureSpp = 2;         // the limit's recording render (≤ 4 M rays at 512²)
  int featureSpp = 16;        // thread scaling and motion overhead
  std::uint64_t meshTriangles = 1000000;
  int textureSize = 1024;                   // px, side of the texture-load test's image
  int threads = 0;                          // resolved: never 0
  std::optional<double> adaptiveThreshold;  // a third sweep: Sobol' + adaptive sampling
  bool guiding = false;                     // the sweeps' renders are guided (path_guide.h)
  std::vector<int> budgets() const;         // 1, 2, 4, … up to maxSpp (and maxSpp itself)
};
BenchPlan planBench(const BenchArgs& args);

// res reduced, aspect kept, so that its long side is at most longSide (px).
glm::ivec2 reducedResolution(glm::ivec2 res, int longSide);

// The scene file of a suite name (scenes/NAME.yaml of the source tree, or $CAMSIM_SCENES/NAME.yaml);
// a name containing '/' or ending in .yaml/.json is a path already.
std::filesystem::path benchScenePath(const std::string& name);
std::filesystem::path defaultBenchCacheDir();

// The scratch directory of the mesh-build and texture-load measurements,
// BASE/camsim-bench-PID (BASE: std::filesystem::temp_directory_path(), i.e. $TMPDIR, $TMP,
// $TEMP, $TEMPDIR or /tmp), created; removed with everything in it
// when the object goes. InputError naming the directory when it cannot be created.
class BenchScratchDirectory {
 public:
  explicit BenchScratchDirectory(std::filesystem::path base = {});
  ~BenchScratchDirectory();
  BenchScratchDirectory(const BenchScratchDirectory&) = delete;
  BenchScratchDirectory& operator=(const BenchScratchDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The embedded plot script (scripts/bench_plot.py at build time).
std::string_view benchPlotScriptFile(std::string_view relPath);

// Runs the benchmark; returns the exit code (0, or 2 if a scene failed to load).
int runBench(const BenchArgs& args, std::ostream& out, std::ostream& log);
// Entry point from main(): parses `args` (args[0] == "bench") and runs.
int runBenchCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log);

}  // namespace camsim
