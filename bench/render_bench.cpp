// render_bench: speed *and* error of the path tracer on the default scene (Cornell box,
// 512×512), in one run.
//
// Reference: the mean of two independent renders at --ref-spp each (seeds 1001, 1002,
// Sobol' sampler). Rows: both samplers at each spp.
// Its own noise is estimated from their difference: rel. RMSE(ref) = RMSE(A − B) / 2 /
// mean(Y). Each benchmark row renders with seed 1 and reports
//   rel. RMSE = sqrt(mean over pixels (Y − Y_ref)²) / mean(Y_ref)
// which includes the reference's noise (subtract in quadrature for the render's own).
//
// Then the cost of the measurement-equation features on the same scene and spp, relative to
// the static pinhole render: a thin lens (f/2.8, 6 blades, focused at 1 m) and motion blur
// (the short block translating 5 cm and the camera panning during the 1/60 s exposure).
//
// usage: render_bench [--threads N] [--ref-spp N] [--spp a,b,c,...] [--feature-spp N]
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/render_command.h"
#include "integrator/render.h"
#include "integrator/scene.h"
#include "integrator/scene_loader.h"

using namespace camsim;

namespace {

double relRmse(const Image& a, const Image& ref, int channel) {
  double se = 0.0, sum = 0.0;
  const size_t n = static_cast<size_t>(a.width) * static_cast<size_t>(a.height);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const double d = static_cast<double>(a.at(x, y, channel)) - static_cast<double>(ref.at(x, y, channel));
      se += d * d;
      sum += static_cast<double>(ref.at(x, y, channel));
    }
  return std::sqrt(se / static_cast<double>(n)) / (sum / static_cast<double>(n));
}

int parseInt(const char* s) {
  int v = 0;
  std::from_chars(s, s + std::char_traits<char>::length(s), v);
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 0, refSpp = 256, featureSpp = 16;
  std::vector<int> spps = {1, 4, 16, 64};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--threads") threads = parseInt(argv[i + 1]);
    else if (a == "--ref-spp") refSpp = parseInt(argv[i + 1]);
    else if (a == "--feature-spp") featureSpp = parseInt(argv[i + 1]);
    else if (a == "--spp") {
      spps.clear();
      for (std::string list = argv[i + 1]; !list.empty();) {
        const size_t comma = list.find(',');
        spps.push_back(parseInt(list.substr(0, comma).c_str()));
        list = comma == std::string::npos ? "" : list.substr(comma + 1);
      }
    } else {
      std::fprintf(stderr, "usage: render_bench [--threads N] [--ref-spp N] [--spp a,b,...]\n");
      return 2;
    }
  }
  SceneDescription desc = loadSceneFromText(std::string(defaultSceneText()), "<default>", ".");
  desc.camera.resolution = {512, 512};
  const Scene scene(desc);
  const SpectralResponse response = SpectralResponse::cieXyz();
  auto run = [&](int spp, std::uint64_t seed, SamplerKind sampler = SamplerKind::kSobol) {
    RenderOptions o;
    o.sampler = sampler;
    o.spp = spp;
    o.seed = seed;
    o.threads = threads;
    return render(scene, response, o);
  };
  const int Y = 1;
  std::printf("camsim render_bench: default scene (Cornell box) 512x512, error on Y (luminance)\n");
  std::printf("reference: 2 x %d spp ...\n", refSpp);
  std::fflush(stdout);
  RenderResult refA = run(refSpp, 1001);
  const RenderResult refB = run(refSpp, 1002);
  const double refNoise = relRmse(refA.image, refB.image, Y) / 2.0;
  for (size_t i = 0; i < refA.image.pixels.size(); ++i)
    refA.image.pixels[i] = 0.5f * (refA.image.pixels[i] + refB.image.pixels[i]);
  std::printf("reference: %.1f s, its own rel. RMSE ~ %.4f\n\n", refA.stats.seconds + refB.stats.seconds, refNoise);
  std::printf("%-12s %6s %9s %12s %12s %10s %10s %10s %12s\n", "sampler", "spp", "seconds", "samples/s", "rays/s",
              "camera", "shadow", "bounce", "rel.RMSE(Y)");
  for (const SamplerKind sampler : {SamplerKind::kIndependent, SamplerKind::kSobol})
  for (int spp : spps) {
    const RenderResult r = run(spp, 1, sampler);
    const RenderStats& s = r.stats;
    const double rays = static_cast<double>(s.rays.total());
    std::printf("%-12s %6d %9.3f %11.3fM %11.3fM %9.1f%% %9.1f%% %9.1f%% %12.4f\n",
                sampler == SamplerKind::kSobol ? "sobol" : "independent", spp, s.seconds,
                static_cast<double>(s.samples) / s.seconds * 1e-6, rays / s.seconds * 1e-6,
                100.0 * static_cast<double>(s.rays.camera) / rays, 100.0 * static_cast<double>(s.rays.shadow) / rays,
                100.0 * static_cast<double>(s.rays.bounce) / rays, relRmse(r.image, refA.image, Y));
    std::fflush(stdout);
  }
  std::printf("\nthreads: %d. rel.RMSE includes the reference's noise; expect it to fall as 1/sqrt(spp).\n",
              refA.stats.threads);

  // Feature cost at equal spp, relative to the static pinhole render.
  SceneDescription dof = desc;
  dof.camera.fNumber = 2.8;
  dof.camera.focusDistance = 1.0;
  dof.camera.aperture.emplace(dof.camera.focalLength / dof.camera.fNumber, 6, 0.0);
  SceneDescription motion = desc;
  for (ShapeDescription& s : motion.shapes)
    if (s.label == "short_block") {
      Keyframe k0, k1;
      k1.time = 1.0 / 60.0;
      k1.translate = {0.05, 0.0, 0.0};
      s.motion = RigidMotion({k0, k1});
    }
  Keyframe c0, c1;
  c1.time = 1.0 / 60.0;
  c1.rotate = glm::angleAxis(glm::radians(1.0), glm::dvec3(0.0, 1.0, 0.0));
  motion.camera.motion = RigidMotion({c0, c1});
  std::printf("\nfeature cost at %d spp (same scene, seconds relative to the static pinhole render):\n", featureSpp);
  std::printf("%-22s %9s %12s %8s  %s\n", "variant", "seconds", "samples/s", "ratio", "modelled");
  double baseline = 0.0;
  const std::pair<const char*, const SceneDescription*> variants[] = {
      {"static pinhole", &desc}, {"depth of field", &dof}, {"motion blur", &motion}};
  for (const auto& [name, d] : variants) {
    const Scene variantScene(*d);
    RenderOptions o;
    o.spp = featureSpp;
    o.seed = 1;
    o.threads = threads;
    const RenderResult r = render(variantScene, response, o);
    if (baseline == 0.0) baseline = r.stats.seconds;
    std::printf("%-22s %9.3f %11.3fM %8.3f  %s\n", name, r.stats.seconds,
                static_cast<double>(r.stats.samples) / r.stats.seconds * 1e-6, r.stats.seconds / baseline,
                r.stats.modelled.describe().c_str());
    std::fflush(stdout);
  }
  return 0;
}
