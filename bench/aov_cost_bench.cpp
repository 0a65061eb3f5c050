// aov_cost_bench: what the ground truth costs — issue 21's row in docs/performance.md. The
// render seconds of a scene's frames with its render.aovs against the same frames without
// any, in one process: the scene is built once each way (over the whole sequence, as
// captureSequence builds it), and the two renders of each frame alternate, round after
// round, so that this VM's drift (it spreads single runs by ±10 %) falls on both alike.
//
//   ratio of a round   Σ_frames t_with / Σ_frames t_without
//   ratio of a pair    t_with / t_without of one frame in one round (the two renders back to
//                      back, so a burst of load elsewhere on the host moves few pairs)
//   reported           every round's sums and ratio, the median of the rounds' ratios and
//                      the median and quartiles of the pairs' ratios
//   check              the image (the film's XYZ) is the same bytes with and without the AOVs
//                      (asking for ground truth must not change the picture); exit 1 if not
//
// usage: aov_cost_bench SCENE.yaml [--rounds N] [--threads N] [--only with|without]
//        (defaults 5 rounds, all cores; --only renders one side, for a profiler)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "integrator/camera/physical_camera.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"

namespace {

using namespace camsim;

struct Args {
  std::string scene;
  int rounds = 5;
  int threads = 0;
  std::string only;  // "with" or "without": render that side only (no ratio)
};

Args parseArgs(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--rounds" || arg == "--threads") && i + 1 < argc) {
      (arg == "--rounds" ? a.rounds : a.threads) = std::atoi(argv[++i]);
    } else if (arg == "--only" && i + 1 < argc) {
      a.only = argv[++i];
    } else if (!arg.empty() && arg[0] != '-' && a.scene.empty()) {
      a.scene = arg;
    } else {
      std::fprintf(stderr,
                   "usage: aov_cost_bench SCENE.yaml [--rounds N] [--threads N] "
                   "[--only with|without]\n");
      std::exit(2);
    }
  }
  if (a.scene.empty() || a.rounds < 1 || a.threads < 0 ||
      !(a.only.empty() || a.only == "with" || a.only == "without")) {
    std::fprintf(stderr,
                 "usage: aov_cost_bench SCENE.yaml [--rounds N] [--threads N] "
                 "[--only with|without]\n");
    std::exit(2);
  }
  return a;
}

// The scene built over its whole sequence (sequenceWindow), as captureSequence builds it.
struct Built {
  SceneDescription description;
  Scene scene;
  Built(SceneDescription d, glm::dvec2 span)
      : description(std::move(d)), scene(description, span) {}
};

// The q-quantile of sorted values, interpolated between neighbours.
double quantile(const std::vector<double>& sorted, double q) {
  const double at = q * static_cast<double>(sorted.size() - 1);
  const std::size_t i = static_cast<std::size_t>(at);
  const double f = at - static_cast<double>(i);
  return i + 1 < sorted.size() ? sorted[i] + f * (sorted[i + 1] - sorted[i]) : sorted[i];
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = parseArgs(argc, argv);
  SceneDescription with;
  try {
    with = loadScene(args.scene);
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  if (with.render.aovs.empty()) {
    std::fprintf(stderr, "error: %s asks for no render.aovs: nothing to compare\n",
                 args.scene.c_str());
    return 2;
  }
  const int frames = with.frames ? with.frames->count : 1;
  SceneDescription without = with;
  without.render.aovs.clear();
  const glm::dvec2 span = sequenceWindow(with);
  Built a(with, span), b(without, span);
  const SpectralResponse xyz = SpectralResponse::cieXyz();
  RenderOptions o;
  o.spp = with.render.spp;
  o.seed = with.render.seed;
  o.threads = args.threads;

  std::printf("%s: %d frame(s), %d spp, %zu aovs, threads %s; render seconds per round\n",
              args.scene.c_str(), frames, o.spp, with.render.aovs.size(),
              args.threads > 0 ? std::to_string(args.threads).c_str() : "all");
  std::printf("round  without (s)  with (s)  ratio\n");
  std::vector<double> ratios, pairs;
  bool same = true;
  for (int r = 0; r < args.rounds; ++r) {
    double tWithout = 0.0, tWith = 0.0;
    for (int k = 0; k < frames; ++k) {
      // Alternate which goes first, so that neither always follows the other.
      RenderResult rw, rwo;
      const auto renderWithout = [&] {
        b.scene.setCamera(without.frameCamera(k));
        rwo = render(b.scene, xyz, o);
      };
      const auto renderWith = [&] {
        a.scene.setCamera(with.frameCamera(k));
        rw = render(a.scene, xyz, o);
      };
      if (!args.only.empty()) {
        if (args.only == "with") {
          renderWith();
          tWith += rw.stats.seconds;
        } else {
          renderWithout();
          tWithout += rwo.stats.seconds;
        }
        continue;
      }
      if ((r + k) % 2 == 0) {
        renderWithout();
        renderWith();
      } else {
        renderWith();
        renderWithout();
      }
      tWithout += rwo.stats.seconds;
      tWith += rw.stats.seconds;
      pairs.push_back(rw.stats.seconds / rwo.stats.seconds);
      same = same && rw.image.pixels.size() == rwo.image.pixels.size() &&
             std::memcmp(rw.image.pixels.data(), rwo.image.pixels.data(),
                         rw.image.pixels.size() * sizeof(float)) == 0;
    }
    if (!args.only.empty()) {
      std::printf("%5d  %11.3f  %8.3f\n", r + 1, tWithout, tWith);
      continue;
    }
    ratios.push_back(tWith / tWithout);
    std::printf("%5d  %11.3f  %8.3f  %5.3f\n", r + 1, tWithout, tWith, ratios.back());
    std::fflush(stdout);
  }
  if (!args.only.empty()) return 0;
  std::sort(ratios.begin(), ratios.end());
  std::sort(pairs.begin(), pairs.end());
  std::printf("rounds: median ratio %.3f (min %.3f, max %.3f)\n", quantile(ratios, 0.5),
              ratios.front(), ratios.back());
  std::printf("pairs (%zu): median ratio %.3f (quartiles %.3f, %.3f)\n", pairs.size(),
              quantile(pairs, 0.5), quantile(pairs, 0.25), quantile(pairs, 0.75));
  std::printf("image with and without the AOVs: %s\n", same ? "the same bytes" : "DIFFERENT");
  return same ? 0 : 1;
}
