// diffraction_bench: what diffraction at the stop costs per camera ray — issue 39's row in
// docs/performance.md. A thin lens (50 mm f/8, 1280 × 960 px, focused at 3 m, static) with a
// circular and a 6-blade stop, each with camera.aperture.diffraction off and on, times
// PhysicalCamera::generateRay over the whole film (one film point per pixel, jittered, in
// pixel order, the lens and diffraction numbers from the R2 sequence, as a sampler's would
// be). Configurations alternate, round after round, so the machine's drift falls on all
// alike; the median of the rounds is reported. The PSF tables are built before timing (once
// per blade count per process: their build time is printed separately).
//
//   rays/s     film points that got a ray, per second
//   vs off     time per film point ÷ the same stop's without diffraction
//
// usage: diffraction_bench [--rounds N]   (default 7)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "bench/bench_rounds.h"
#include "integrator/camera/physical_camera.h"
#include "integrator/camera/psf_grid.h"
#include "integrator/scene/scene_loader.h"

namespace {

using camsim::CameraSample;
using camsim::PhysicalCamera;

struct Config {
  const char* name;
  int blades;
  bool diffraction;
};

PhysicalCamera makeCamera(const Config& c) {
  const std::string yaml =
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [1280, 960], "
      "focal_length_mm: 50, f_number: 8, focus_distance_m: 3, aperture: {blades: " +
      std::to_string(c.blades) + ", diffraction: " + (c.diffraction ? "true" : "false") +
      "}}\nshapes: [{type: sphere, centre: [0, 0, 5], radius: 1, emission: {luminance: 1}}]\n";
  return PhysicalCamera(camsim::loadSceneFromText(yaml, "bench.yaml", ".").camera);
}

struct Pass {
  double seconds;
  long rays;
  double checksum;
};

Pass timePass(const PhysicalCamera& camera) {
  const glm::ivec2 res = camera.resolution();
  const camsim::SampledWavelengths lambda = camsim::SampledWavelengths::sampleVisible(0.37f);
  Pass p{0.0, 0, 0.0};
  const auto start = std::chrono::steady_clock::now();
  for (int y = 0; y < res.y; ++y)
    for (int x = 0; x < res.x; ++x) {
      const double i = double(x + y * res.x);
      // frac(0.5 + a·i) (floor, not fmod: fmodf of large arguments would cost more than the
      // camera ray)
      auto r2 = [i](double a) {
        const double v = 0.5 + a * i;
        return static_cast<float>(v - std::floor(v));
      };
      CameraSample s;
      s.pPhotosite = {r2(0.7548777f) - 0.5f, r2(0.5698403f) - 0.5f};
      s.pFilm = glm::vec2(float(x) + 0.5f, float(y) + 0.5f) + s.pPhotosite;
      s.pLens = {r2(0.8191725f), r2(0.6710436f)};
      s.pDiffraction = {r2(0.5497004f), r2(0.4501678f)};
      s.uDiffractionWavelength = r2(0.6180340f);
      const std::optional<camsim::CameraRay> r = camera.generateRay(s, lambda);
      if (!r) continue;
      ++p.rays;
      p.checksum += double(r->ray.d.x) + double(r->weight[0]);
    }
  p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  const std::optional<int> parsed = camsim::bench::parseRounds(argc, argv, "diffraction_bench", 7);
  if (!parsed) return 2;
  const int rounds = *parsed;
  for (int blades : {0, 6}) {
    const auto start = std::chrono::steady_clock::now();
    const camsim::PsfGrid table(camsim::ApertureShape{blades, 0.0});
    std::printf("PSF table, %s: built in %.3f s (%d × %d cells, %.3f %% of the energy left out)\n",
                blades ? "6 blades" : "circular",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                table.cellsPerAxis(), table.cellsPerAxis(), 100.0 * table.truncatedEnergy());
  }
  const std::vector<Config> configs = {{"circular, off", 0, false},
                                       {"circular, diffraction", 0, true},
                                       {"6 blades, off", 6, false},
                                       {"6 blades, diffraction", 6, true}};
  std::vector<PhysicalCamera> cameras;
  for (const Config& c : configs) cameras.push_back(makeCamera(c));
  std::vector<std::vector<double>> perPoint(configs.size());  // s per film point, per round
  std::vector<long> rays(configs.size());
  double checksum = 0.0;
  for (int round = 0; round < rounds; ++round)
    for (size_t m = 0; m < configs.size(); ++m) {
      const Pass p = timePass(cameras[m]);
      const glm::ivec2 res = cameras[m].resolution();
      perPoint[m].push_back(p.seconds / (double(res.x) * res.y));
      rays[m] = p.rays;
      checksum += p.checksum;
    }
  std::printf("%-24s %14s %10s\n", "camera", "rays/s", "vs off");
  for (size_t m = 0; m < configs.size(); ++m) {
    std::vector<double>& t = perPoint[m];
    std::sort(t.begin(), t.end());
    std::vector<double>& off = perPoint[m - m % 2];  // sorted already: the off row comes first
    const double median = t[t.size() / 2], offMedian = off[off.size() / 2];
    const glm::ivec2 res = cameras[m].resolution();
    const double points = double(res.x) * res.y;
    std::printf("%-24s %14.3e %9.2fx\n", configs[m].name, double(rays[m]) / points / median,
                median / offMedian);
  }
  std::printf("(checksum %.6g; median of %d rounds)\n", checksum, rounds);
  return 0;
}
