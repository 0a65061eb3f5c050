#include "integrator/measure/peer_bench.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "integrator/measure/bench_reference.h"
#include "integrator/measure/peer_cycles.h"
#include "integrator/scene/scene.h"
#include "sensor/base/check.h"
#include "sensor/base/fnv1a.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/io/exr_io.h"
#include "sensor/io/output_set.h"

namespace camsim {
namespace {

constexpr std::uint64_t kLadderSeed = 1;

struct Halves {
  Image a, b;  // R, G, B, Y each
  double seconds = 0.0;
  bool cached = false;
};

Image average(const Image& a, const Image& b) {
  Image r = a;
  for (std::size_t i = 0; i < r.pixels.size(); ++i)
    r.pixels[i] = 0.5f * (a.pixels[i] + b.pixels[i]);
  return r;
}

std::optional<Halves> readHalves(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
  try {
    const ExrFile exr = readExr(file);
    Halves h;
    h.cached = true;
    for (auto [prefix, out] : {std::pair<const char*, Image*>{"A.", &h.a}, {"B.", &h.b}}) {
      *out = Image(exr.image.width, exr.image.height, {"R", "G", "B", "Y"});
      for (int c = 0; c < 4; ++c) {
        const int src = exr.image.channelIndex(prefix + out->channels[static_cast<std::size_t>(c)]);
        if (src < 0) return std::nullopt;
        for (int y = 0; y < out->height; ++y)
          for (int x = 0; x < out->width; ++x) out->at(x, y, c) = exr.image.at(x, y, src);
      }
    }
    return h;
  } catch (const InputError&) {
    return std::nullopt;
  }
}

void writeHalves(const std::filesystem::path& file, const Halves& h, std::ostream& log) {
  Image img(h.a.width, h.a.height, {"A.R", "A.G", "A.B", "A.Y", "B.R", "B.G", "B.B", "B.Y"});
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 4; ++c) {
        img.at(x, y, c) = h.a.at(x, y, c);
        img.at(x, y, 4 + c) = h.b.at(x, y, c);
      }
  try {
    OutputSet::prepareDirectory(file.parent_path());
    OutputSet out(file.parent_path());
    writeExr(
        out.add(file.filename().string()), img,
        {{"camsim:version", CAMSIM_VERSION}, {"camsim:render_seconds", formatNumber(h.seconds, 6)}},
        std::nullopt);
    out.commit();
  } catch (const InputError& e) {
    log << "warning: cannot write the peer reference cache (" << e.what() << "): not cached\n";
  }
}

// Runs blender on the script; returns the seconds each render printed, by index.
std::map<int, double> runBlender(const PeerPlan& plan, const std::string& script,
                                 const std::string& tag) {
  const std::filesystem::path py = plan.scratchDir / (tag + ".py");
  const std::filesystem::path logFile = plan.scratchDir / (tag + ".log");
  std::ofstream(py) << script;
  const std::vector<std::string> argv = {
      plan.blender,         "-b", "--factory-startup", "-noaudio",
      "--python-exit-code", "3",  "--python",          py.string()};
  std::vector<char*> cargv;
  for (const std::string& a : argv) cargv.push_back(const_cast<char*>(a.c_str()));
  cargv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, logFile.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, argv[0].c_str(), &actions, nullptr, cargv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  int status = -1;
  if (rc == 0)
    while (waitpid(pid, &status, 0) < 0)
      if (errno != EINTR) break;
  std::ifstream in(logFile);
  std::map<int, double> seconds;
  std::string line, tail;
  while (std::getline(in, line)) {
    tail += line + "\n";
    if (tail.size() > 2000) tail.erase(0, tail.size() - 2000);
    int index = 0;
    double s = 0.0;
    if (std::sscanf(line.c_str(), "camsim-peer: %d %lf", &index, &s) == 2) seconds[index] = s;
  }
  if (rc != 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("blender failed on " + py.string() + " (log " + logFile.string() +
                             "):\n" + tail);
  return seconds;
}

Image readCyclesImage(const std::filesystem::path& file) {
  return peerRgbyFromRgb(readExr(file).image);
}

// A renderer's reference run from its two halves: cached or not, their time, the noise floor
// they leave, and the reference image (the halves' mean).
PeerRun referenceRun(const std::string& renderer, const Halves& ref, Image& reference) {
  PeerRun run;
  run.renderer = renderer;
  run.referenceCached = ref.cached;
  run.referenceSeconds = ref.seconds;
  run.floor = peerNoise(ref.a, ref.b);
  reference = average(ref.a, ref.b);
  return run;
}

// camsim's reference (rendered, or read from the cache): the run without its ladder, and the
// reference image (the halves' mean).
PeerRun camsimReference(const PeerInput& in, const Scene& scene, const PeerPlan& plan,
                        const std::string& key, std::ostream& log, Image& reference) {
  const std::filesystem::path cache =
      plan.cacheDir / ("peer-" + in.name + "-camsim-" + key + ".exr");
  std::optional<Halves> ref = readHalves(cache);
  if (!ref) {
    log << "peer: " << in.name << ": camsim reference, " << plan.refSpp << " spp\n";
    ref.emplace();
    for (auto [seed, out] :
         {std::pair<std::uint64_t, Image*>{kReferenceSeedA, &ref->a}, {kReferenceSeedB, &ref->b}}) {
      const RenderResult r = renderXyz(
          scene, benchRenderOptions(plan.refSpp / 2, seed, plan.threads, SamplerKind::kSobol));
      ref->seconds += r.stats.seconds;
      *out = peerRgbyFromXyz(r.image);
    }
    writeHalves(cache, *ref, log);
  }
  return referenceRun("camsim", *ref, reference);
}

// One timed camsim ladder (seed 1), each render against the reference.
std::vector<PeerLadderPoint> camsimLadder(const PeerInput& in, const Scene& scene,
                                          const PeerPlan& plan, const Image& reference,
                                          std::ostream& log) {
  std::vector<PeerLadderPoint> ladder;
  for (int spp = plan.minSpp; spp <= plan.camsimMaxSpp; spp *= 2) {
    const RenderResult r =
        renderXyz(scene, benchRenderOptions(spp, kLadderSeed, plan.threads, SamplerKind::kSobol));
    PeerLadderPoint p{spp, r.stats.seconds, peerCompare(peerRgbyFromXyz(r.image), reference),
                      r.stats.seconds};
    log << "peer: " << in.name << " camsim " << spp << " spp: " << formatNumber(p.seconds, 3)
        << " s, rMSE RGB " << formatNumber(p.error.rgb.rmse, 3) << "\n";
    ladder.push_back(p);
  }
  return ladder;
}

// Cycles' reference (rendered, or read from the cache): the run without its ladder, and the
// reference image. settings: the translation's (threads, bounces).
PeerRun cyclesReference(const PeerInput& in, const SceneDescription& d, const PeerPlan& plan,
                        const CyclesSettings& settings, const std::string& camsimKey,
                        std::ostream& log, Image& reference) {
  const CyclesTranslation bare = translateToCycles(d, settings);  // the key's script
  std::error_code ec;
  std::string stamp;
  if (const std::optional<std::string> exe = findBlender()) {
    const std::filesystem::path p = std::filesystem::canonical(*exe, ec);
    stamp = p.string() + " " + std::to_string(std::filesystem::file_size(p, ec)) + " " +
            std::to_string(std::filesystem::last_write_time(p, ec).time_since_epoch().count());
  }
  const std::string key = fnv1aHex(camsimKey + "\n" + bare.script + "\n" + stamp);
  const std::filesystem::path cache =
      plan.cacheDir / ("peer-" + in.name + "-cycles-" + key + ".exr");
  const std::filesystem::path dir = plan.scratchDir;
  std::optional<Halves> ref = readHalves(cache);
  if (!ref) {
    log << "peer: " << in.name << ": Cycles reference, " << plan.refSpp << " spp\n";
    CyclesSettings s = settings;
    s.renders = {{plan.refSpp / 2, kReferenceSeedA, (dir / (in.name + "-ref-a.exr")).string()},
                 {plan.refSpp / 2, kReferenceSeedB, (dir / (in.name + "-ref-b.exr")).string()}};
    const std::map<int, double> t =
        runBlender(plan, translateToCycles(d, s).script, in.name + "-ref");
    ref.emplace();
    ref->a = readCyclesImage(s.renders[0].file);
    ref->b = readCyclesImage(s.renders[1].file);
    for (const auto& [i, sec] : t) ref->seconds += i >= 0 ? sec : 0.0;
    writeHalves(cache, *ref, log);
  }
  return referenceRun("cycles", *ref, reference);
}

// One timed Cycles ladder (seed 1, one Blender process after a warm-up render), each render
// against the reference.
std::vector<PeerLadderPoint> cyclesLadder(const PeerInput& in, const SceneDescription& d,
                                          const PeerPlan& plan, const CyclesSettings& settings,
                                          const Image& reference, std::ostream& log) {
  const std::filesystem::path dir = plan.scratchDir;
  CyclesSettings s = settings;
  s.warmupFile = (dir / (in.name + "-warmup.exr")).string();
  for (int spp = plan.minSpp; spp <= plan.cyclesMaxSpp; spp *= 2)
    s.renders.push_back(
        {spp, kLadderSeed, (dir / (in.name + "-" + std::to_string(spp) + ".exr")).string()});
  log << "peer: " << in.name << ": Cycles ladder\n";
  const std::map<int, double> t =
      runBlender(plan, translateToCycles(d, s).script, in.name + "-ladder");
  std::vector<PeerLadderPoint> ladder;
  for (std::size_t i = 0; i < s.renders.size(); ++i) {
    const auto found = t.find(static_cast<int>(i));
    if (found == t.end())
      throw std::runtime_error("blender printed no time for render " + std::to_string(i));
    PeerLadderPoint p{s.renders[i].spp, found->second,
                      peerCompare(readCyclesImage(s.renders[i].file), reference), found->second};
    log << "peer: " << in.name << " cycles " << p.spp << " spp: " << formatNumber(p.seconds, 3)
        << " s, rMSE RGB " << formatNumber(p.error.rgb.rmse, 3) << "\n";
    ladder.push_back(p);
  }
  return ladder;
}

}  // namespace

std::optional<std::string> findBlender() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::filesystem::path p = std::filesystem::path(dir.empty() ? "." : dir) / "blender";
    if (::access(p.c_str(), X_OK) == 0) return p.string();
  }
  return std::nullopt;
}

PeerSceneResult runPeerScene(const PeerInput& input, const PeerPlan& plan, std::ostream& log) {
  SceneDescription d = input.description;
  if (plan.maxDepth) d.render.maxDepth = *plan.maxDepth;
  PeerSceneResult r;
  r.scene = input.name;
  r.width = d.camera.resolution.x;
  r.height = d.camera.resolution.y;
  r.maxDepth = d.render.maxDepth;
  // The scene text plus the depth: the key of both references.
  const ReferenceRequest request{
      input.name,   input.sceneText + "\nmax_depth " + std::to_string(r.maxDepth),
      d.inputFiles, d.camera.resolution,
      d.sourceFile, plan.refSpp,
      plan.threads};
  const std::string keyText = "camsim-peer/1\n" + referenceKeyText(request);
  CyclesSettings settings;
  settings.threads = plan.threads;
  settings.bounces = r.maxDepth - 1;
  // Translate first: a scene Cycles cannot take fails before any render.
  r.approximations = translateToCycles(d, settings).approximations;
  const Scene scene(d);
  Image cyclesRef, camsimRef;
  r.cycles = cyclesReference(input, d, plan, settings, keyText, log, cyclesRef);
  r.camsim = camsimReference(input, scene, plan, fnv1aHex(keyText), log, camsimRef);
  CAMSIM_CHECK(plan.rounds >= 1);
  r.rounds = plan.rounds;
  for (int round = 1; round <= plan.rounds; ++round) {
    if (plan.rounds > 1)
      log << "peer: " << input.name << ": round " << round << " of " << plan.rounds << "\n";
    PeerRun cycles = r.cycles, camsim = r.camsim;
    cycles.ladder = cyclesLadder(input, d, plan, settings, cyclesRef, log);
    camsim.ladder = camsimLadder(input, scene, plan, camsimRef, log);
    r.rgbRoundRatios.push_back(equalError(camsim, cycles, false).ratio());
    r.yRoundRatios.push_back(equalError(camsim, cycles, true).ratio());
    if (round == 1) {
      r.cycles.ladder = cycles.ladder;
      r.camsim.ladder = camsim.ladder;
    } else {
      keepFastest(r.cycles.ladder, cycles.ladder);
      keepFastest(r.camsim.ladder, camsim.ladder);
    }
  }
  r.rgb = equalError(r.camsim, r.cycles, false);
  r.y = equalError(r.camsim, r.cycles, true);
  return r;
}

}  // namespace camsim
