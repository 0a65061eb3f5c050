#include "cli/bench_command.h"

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "cli/args.h"
#include "cli/python_script.h"
#include "integrator/capture/progress.h"
#include "integrator/measure/bench_limit.h"
#include "integrator/measure/bench_metrics.h"
#include "integrator/measure/bench_reference.h"
#include "integrator/measure/peer_bench.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/file_status.h"
#include "sensor/base/input_error.h"
#include "sensor/io/output_set.h"

namespace camsim {
namespace {

std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  double one = 0.0;
  in >> one;
  return formatNumber(one, 3);
}

struct LoadedBenchScene {
  std::string name, text;
  std::filesystem::path baseDir;
  SceneDescription description;
  glm::ivec2 original{0};
};

LoadedBenchScene loadBenchScene(const std::string& name, int longSide) {
  LoadedBenchScene s;
  const std::filesystem::path path = benchScenePath(name);
  s.name = path.stem().string();
  s.text = readSceneFile(path);
  s.baseDir = sceneBaseDir(path);
  s.description = loadSceneFromText(s.text, path.string(), s.baseDir);
  s.original = s.description.camera.resolution;
  s.description.camera.resolution = reducedResolution(s.original, longSide);
  return s;
}

// The sweep of one scene: both samplers at every budget, against the reference; with
// --adaptive-threshold, Sobol' with adaptive sampling too (sampler "sobol+adaptive").
std::vector<BenchRow> sweep(const LoadedBenchScene& s, const Scene& scene, const Reference& ref,
                            const BenchPlan& plan, std::ostream& log) {
  std::vector<BenchRow> rows;
  for (const std::string_view sampler : benchSamplers(plan.adaptiveThreshold.has_value()))
    for (const int spp : plan.budgets()) {
      const bool adaptive = sampler == kAdaptiveSampler;
      RenderOptions o =
          benchRenderOptions(spp, 1, plan.threads,
                             adaptive ? SamplerKind::kSobol : *enumFromName<SamplerKind>(sampler));
      if (adaptive)
        o.adaptive = AdaptiveSampling{*plan.adaptiveThreshold, adaptiveMinSppFor(spp, 0)};
      const double cpu0 = processCpuSeconds();
      if (plan.guiding) o.guiding = true;
      const RenderResult r = renderXyz(scene, o);
      BenchRow row;
      row.cpuSeconds = processCpuSeconds() - cpu0;
      row.scene = s.name;
      row.sampler = std::string(sampler);
      row.spp = spp;
      row.width = r.image.width;
      row.height = r.image.height;
      row.seconds = r.stats.seconds;
      row.samples = r.stats.samples;
      row.rays = r.stats.rays.total();
      row.error = compareImages(luminanceOf(r.image), ref.image, 0);
      row.floor = ref.noise;
      if (r.stats.estimatedError) row.estimate = r.stats.estimatedError->error;
      log << "bench: " << s.name << " " << row.sampler << " " << spp
          << " spp: " << formatNumber(row.seconds, 3) << " s, rMSE "
          << formatNumber(row.error.rmse, 3) << "\n";
      rows.push_back(row);
    }
  return rows;
}

// The limit, thread scaling (cornell_box) and motion overhead (motion_blur) of one scene.
void measureFeatures(const std::string& name, const Scene& scene,
                     const SceneDescription& description, const BenchPlan& plan,
                     std::vector<LimitResult>& limits, std::ostream& extras, std::ostream& log) {
  const glm::ivec2 res = scene.camera().resolution();
  log << "bench: " << name << ": recording and replaying rays at " << formatSize(res.x, res.y)
      << "\n";
  const bool scaling = name == "cornell_box";  // thread scaling replays the limit's rays
  std::vector<RecordedRay> rays;
  limits.push_back(
      measureLimit(scene, name, plan.captureSpp, plan.threads, scaling ? &rays : nullptr));
  if (scaling) {
    log << "bench: thread scaling on " << name << "\n";
    extras << formatScaling(name, measureThreadScaling(scene, plan.featureSpp, rays, plan.threads))
           << "\n";
  }
  if (name == "motion_blur") {
    log << "bench: motion-blur overhead on " << name << "\n";
    extras << formatMotionOverhead(
                  name, measureMotionOverhead(scene, description, plan.featureSpp, plan.threads))
           << "\n";
  }
}

// The --peer settings (the refSpp the report names is the one rendered: rounded up to even).
PeerPlan peerPlanOf(const BenchArgs& args, const BenchPlan& plan,
                    const std::filesystem::path& cacheDir, const std::filesystem::path& scratch) {
  PeerPlan p;
  if (args.peerRefSpp) p.refSpp = *args.peerRefSpp + *args.peerRefSpp % 2;
  if (args.peerSpp) p.cyclesMaxSpp = *args.peerSpp;
  p.camsimMaxSpp = args.peerCamsimSpp ? *args.peerCamsimSpp : 4 * p.cyclesMaxSpp;
  p.minSpp = std::min({p.minSpp, p.cyclesMaxSpp, p.camsimMaxSpp});
  p.threads = plan.threads;
  p.maxDepth = args.peerMaxDepth;
  p.rounds = args.peerRounds.value_or(1);
  p.cacheDir = cacheDir;
  p.scratchDir = scratch / "peer";
  p.blender = *findBlender();
  return p;
}

// --peer cycles: each peer scene at the peer resolution, camsim and Cycles side by side.
std::vector<PeerSceneResult> runPeer(const BenchArgs& args, const PeerPlan& p,
                                     std::vector<std::string>& failed, std::ostream& log) {
  std::filesystem::create_directories(p.scratchDir);
  std::vector<PeerSceneResult> results;
  for (const std::string& name : args.peerScenes.empty() ? peerSuite() : args.peerScenes) {
    try {
      const LoadedBenchScene s = loadBenchScene(name, args.peerResolution.value_or(512));
      log << "bench: peer " << s.name << " at "
          << formatSize(s.description.camera.resolution.x, s.description.camera.resolution.y)
          << "\n";
      results.push_back(runPeerScene({s.name, s.text, s.description}, p, log));
    } catch (const InputError& e) {
      log << "bench: peer: skipping " << name << ": " << e.what() << "\n";
      failed.push_back("peer " + name + ": " + e.what());
    }
  }
  return results;
}

// bench.png from bench.csv (a full run's rows, at least one) by `python`, which has
// matplotlib.
void plotBench(const std::string& python, const BenchPlan& plan, const std::filesystem::path& csv,
               OutputSet& outputs) {
  const std::filesystem::path png = outputs.add("bench.png");
  const std::string note = std::to_string(plan.threads) + " threads, long side " +
                           std::to_string(plan.longSide) + " px, reference " +
                           std::to_string(plan.refSpp) + " spp";
  runPythonScript(python, benchPlotScriptFile("bench_plot.py"), {csv.string(), png.string(), note});
}

// bench_peer.png from bench_peer.csv and bench_peer_equal.csv (scripts/peer_plot.py draws
// the report's equal-error figures, it computes none).
void plotPeers(const std::string& python, int threads, const std::filesystem::path& csv,
               const std::filesystem::path& equalCsv, OutputSet& outputs) {
  const std::filesystem::path png = outputs.add("bench_peer.png");
  runPythonScript(
      python, benchPlotScriptFile("peer_plot.py"),
      {csv.string(), equalCsv.string(), png.string(), std::to_string(threads) + " threads"});
}

}  // namespace

BenchScratchDirectory::BenchScratchDirectory(std::filesystem::path base) {
  std::error_code ec;
  if (base.empty()) base = std::filesystem::temp_directory_path(ec);
  if (ec) {  // name the variable temp_directory_path took (libstdc++'s order), else /tmp
    std::string where = "/tmp";
    for (const char* name : {"TMPDIR", "TMP", "TEMP", "TEMPDIR"})
      if (const char* v = std::getenv(name)) {
        where = std::string(name) + "=" + v;
        break;
      }
    throw InputError(
        {where, 0, 0}, "",
        "not a usable temporary directory for the bench's generated files: " + ec.message());
  }
  path_ = base / ("camsim-bench-" + std::to_string(::getpid()));
  std::filesystem::create_directories(path_, ec);
  if (ec || !isDirectory(path_))
    throw InputError({path_.string(), 0, 0}, "",
                     "cannot create the bench's temporary directory" +
                         (ec ? ": " + ec.message() : std::string()));
}

BenchScratchDirectory::~BenchScratchDirectory() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

int runBench(const BenchArgs& args, std::ostream& out, std::ostream& log) {
  const auto start = std::chrono::steady_clock::now();
  const double cpuStart = processCpuSeconds();
  const BenchPlan plan = planBench(args);
  std::vector<std::string> names = args.scenes.empty() ? benchSuite() : args.scenes;
  const std::filesystem::path outDir(args.outputDir);
  const std::filesystem::path cacheDir =
      args.cacheDir ? std::filesystem::path(*args.cacheDir) : defaultBenchCacheDir();
  if (args.peer && !findBlender()) {
    log << "camsim bench: --peer cycles needs Debian's blender on PATH (scripts/setup.sh "
           "--peer installs it)\n";
    return 2;
  }
  const bool full = !(args.peer && args.peerOnly);  // the sweeps, the limit and the rest
  if (!full) names.clear();
  std::optional<BenchScratchDirectory> scratch;  // made first: fail before any output or render
  if ((full && (plan.meshTriangles > 0 || plan.textureSize > 0)) || args.peer) scratch.emplace();
  for (const auto& stale : OutputSet::prepareDirectory(outDir))
    log << "removed " << stale.string() << " (left by a run that was killed)\n";
  const std::string loadBefore = loadAverage();

  std::ostringstream report;
  std::string budgets;
  for (int spp : plan.budgets()) budgets += (budgets.empty() ? "" : ",") + std::to_string(spp);
  if (!full)
    report << "camsim " << CAMSIM_VERSION << " bench --peer cycles --peer-only: " << plan.threads
           << " threads\n";
  else
    report << "camsim " << CAMSIM_VERSION << " bench" << (args.quick ? " --quick" : "") << ": "
           << plan.threads << " threads; images reduced to a long side of " << plan.longSide
           << " px; budgets " << budgets << " spp per sampler (seed 1"
           << (plan.guiding ? ", path guiding" : "") << ")\n"
           << "error: luminance Y against a reference of " << plan.refSpp
           << " Sobol' spp (two halves, seeds 1001/1002); rMSE = mean (x-r)^2/(r^2+eps^2), MRAE = "
              "mean |x-r|/(|r|+eps),"
              " eps = 1% of mean Y\n\n";

  std::vector<BenchRow> rows;
  std::vector<SamplerSlopes> slopes;
  std::vector<LimitResult> limits;
  std::ostringstream extras, refs;
  std::vector<std::string> failed;
  for (const std::string& name : names) {
    LoadedBenchScene s;
    try {
      s = loadBenchScene(name, plan.longSide);
    } catch (const InputError& e) {
      log << "bench: skipping " << name << ": " << e.what() << "\n";
      failed.push_back(name + ": " + e.what());
      continue;
    }
    const glm::ivec2 sweepRes = s.description.camera.resolution;
    log << "bench: " << s.name << " at " << formatSize(sweepRes.x, sweepRes.y)
        << " (scene: " << formatSize(s.original.x, s.original.y) << ")\n";
    // The limit, thread scaling and motion overhead run at the scene's own resolution
    // (reduced to featureLongSide): on the sweep's Scene if that is the same size.
    const glm::ivec2 featureRes = reducedResolution(s.original, plan.featureLongSide);
    {
      const Scene scene(s.description);
      const ReferenceRequest request{s.name,
                                     s.text,
                                     s.description.inputFiles,
                                     s.description.camera.resolution,
                                     s.description.sourceFile,
                                     plan.refSpp,
                                     plan.threads};
      ProgressBar bar("reference " + s.name);
      const Reference ref =
          obtainReference(request, scene, cacheDir, log, [&](int d, int t) { bar.update(d, t); });
      bar.finish();
      // A black reference (no light reaches the camera) has no relative error: eps is 1 % of
      // a mean of 0, and every ratio was NaN in bench.txt (the plot script then failed).
      double total = 0.0;
      for (const float v : ref.image.pixels) total += static_cast<double>(v);
      if (!(total > 0.0)) {
        const std::string why =
            "its reference image is black (no light reaches the camera): "
            "relative errors are undefined";
        log << "bench: skipping " << s.name << ": " << why << "\n";
        failed.push_back(s.name + ": " + why);
        continue;
      }
      refs << "  " << s.name << " "
           << formatSize(s.description.camera.resolution.x, s.description.camera.resolution.y)
           << ": rMSE floor " << formatNumber(ref.noise.rmse, 3) << ", MRAE floor "
           << formatNumber(ref.noise.mrae, 3)
           << (ref.fromCache ? " (cached "
                             : " (rendered in " + formatNumber(ref.seconds, 3) + " s, ")
           << ref.file.filename().string() << ")\n";
      std::vector<BenchRow> sceneRows = sweep(s, scene, ref, plan, log);
      for (const std::string_view sampler : benchSamplers(plan.adaptiveThreshold.has_value())) {
        std::vector<BenchRow*> mine;
        for (BenchRow& r : sceneRows)
          if (r.sampler == sampler) mine.push_back(&r);
        slopes.push_back(fitRows(mine));
      }
      rows.insert(rows.end(), sceneRows.begin(), sceneRows.end());
      if (featureRes == s.description.camera.resolution)
        measureFeatures(s.name, scene, s.description, plan, limits, extras, log);
    }
    if (featureRes != s.description.camera.resolution) {
      s.description.camera.resolution = featureRes;  // the sweep's Scene is gone by now
      measureFeatures(s.name, Scene(s.description), s.description, plan, limits, extras, log);
    }
  }
  std::vector<PeerSceneResult> peers;
  std::optional<PeerPlan> peerPlan;
  if (args.peer) {
    peerPlan = peerPlanOf(args, plan, cacheDir, scratch->path());
    peers = runPeer(args, *peerPlan, failed, log);
  }
  if (scratch && full) {
    const std::filesystem::path& temp = scratch->path();
    if (plan.meshTriangles > 0) {
      log << "bench: building a " << plan.meshTriangles << "-triangle mesh\n";
      extras << formatMeshBuild(measureMeshBuild(plan.meshTriangles, plan.threads, temp));
    }
    if (plan.textureSize > 0) {
      log << "bench: loading a " << plan.textureSize << "-pixel-square random-colour texture\n";
      extras << formatTextureLoad(measureTextureLoad(plan.textureSize, plan.threads, temp));
    }
  }

  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpu = processCpuSeconds() - cpuStart;
  if (full)
    report
        << "references (noise floor of each; rMSE below " << formatNumber(kFloorFactor, 2)
        << "x the floor is left out of the fit):\n"
        << refs.str() << "\n"
        << formatBenchTable(rows) << "(* = in the fit)\n\n"
        << "log-log slope of rMSE against render time (least squares over the budgets marked *):\n"
        << formatSlopeTable(slopes) << "\n"
        << "each render's estimate of its own error (two half-sample images) against its "
           "error beyond the reference's noise (MRAE* = sqrt(MRAE^2 - floor^2)):\n"
        << formatEstimateTable(rows) << "\n";
  if (full && plan.adaptiveThreshold)
    report << "adaptive sampling (threshold " << formatNumber(*plan.adaptiveThreshold, 3)
           << ", min spp max(4, sqrt(budget))) against plain Sobol': the CPU time plain "
              "Sobol' needs for the same error, interpolated log-log between its budgets; ratio = "
              "adaptive CPU time / that (below 1: adaptive is faster):\n"
           << formatAdaptiveTable(rows) << "\n";
  if (full)
    report << "the limit: the rays of a " << plan.captureSpp
           << "-spp Sobol' render, replayed through EmbreeScene alone (traversal only), "
           << plan.threads << " threads; ratio = tracer rays/s / raw rays/s of the same mix:\n"
           << formatLimitTable(limits) << "\n"
           << extras.str() << "\n";
  if (args.peer) report << formatPeerReport(peers, plan.threads, peerPlan->refSpp) << "\n";
  report << "total: " << formatSeconds(wall) << " wall, " << formatNumber(cpu, 4) << " CPU-s ("
         << formatNumber(100.0 * cpu / (wall * plan.threads), 3) << "% of " << plan.threads
         << " cores); load average " << loadBefore << " before, " << loadAverage() << " after\n";
  for (const std::string& f : failed) report << "failed: " << f << "\n";
  out << report.str();
  out.flush();

  // The measurements first, then the plots from them: a plot that fails (its script's
  // error) is skipped with a note and never costs the run's tables.
  OutputSet outputs(outDir);
  if (full) outputs.addText("bench.csv", formatBenchCsv(rows));
  if (full) outputs.addText("bench_limit.csv", formatLimitCsv(limits));
  if (args.peer) outputs.addText("bench_peer.csv", formatPeerCsv(peers));
  if (args.peer) outputs.addText("bench_peer_equal.csv", formatPeerEqualCsv(peers));
  outputs.addText("bench.txt", report.str());
  for (const auto& f : outputs.commit()) log << "bench: wrote " << f.string() << "\n";
  if (full && rows.empty()) log << "bench: no rows: plot skipped\n";
  const bool benchPlot = full && !rows.empty(), peerPlot = args.peer && !peers.empty();
  const std::optional<std::string> python =
      benchPlot || peerPlot ? pythonWithMatplotlib() : std::nullopt;
  if ((benchPlot || peerPlot) && !python)
    log << "bench: python3 with matplotlib not found ($CAMSIM_PYTHON or /usr/bin/python3; Debian: "
           "apt-get install python3-matplotlib): plots skipped\n";
  // Each plot on its own: one whose script fails costs neither the other nor the tables.
  const auto plot = [&](const std::function<void(OutputSet&)>& draw) {
    try {
      OutputSet plots(outDir);
      draw(plots);
      for (const auto& f : plots.commit()) log << "bench: wrote " << f.string() << "\n";
    } catch (const std::runtime_error& e) {
      log << "bench: plot skipped: " << e.what() << "\n";
    }
  };
  if (python && benchPlot)
    plot([&](OutputSet& plots) { plotBench(*python, plan, outDir / "bench.csv", plots); });
  if (python && peerPlot)
    plot([&](OutputSet& plots) {
      plotPeers(*python, plan.threads, outDir / "bench_peer.csv", outDir / "bench_peer_equal.csv",
                plots);
    });
  return failed.empty() ? 0 : 2;
}

int runBenchCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log) {
  const BenchArgs parsed = parseBenchArgs(args);
  if (parsed.help) {
    out << benchUsageText();
    return 0;
  }
  return runBench(parsed, out, log);
}

}  // namespace camsim
