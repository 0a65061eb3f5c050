// camera_model_bench: what each camera model costs per camera ray, against the pinhole —
// issue 36's row in docs/performance.md. For each model (a typical calibration of each,
// 1280 × 960 px, static, no aperture) it times PhysicalCamera::generateRay over the whole
// film (one film point per pixel, jittered, in pixel order), and measures the mapping's
// error on the same camera: the largest distance between a pixel centre and where the
// camera projects (PhysicalCamera::project) a point 10 m along that pixel's ray, over a
// 64 × 48 grid of the valid image. Models alternate, round after round, so the VM's drift
// falls on all alike; the median of the rounds is reported.
//
//   rays/s       film points that got a ray (outside the image: counted, not traced)
//   vs pinhole   time per film point ÷ the ideal pinhole's (its float fast path)
//   round trip   px, worst over the grid
//
// usage: camera_model_bench [--rounds N]   (default 7)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "bench/bench_rounds.h"
#include "integrator/camera/physical_camera.h"
#include "integrator/scene/scene_loader.h"

namespace {

using camsim::CameraSample;
using camsim::PhysicalCamera;

struct Model {
  const char* name;
  std::string projection;  // the scene's camera.projection block ("" = none: the pinhole)
  std::string lens;        // focal length and sensor
};

const std::string kPinholeLens =
    "focal_length_mm: 4.2, sensor_width_mm: 6.4, sensor_height_mm: 4.8";
const std::string kFisheyeLens =
    "focal_length_mm: 1.8, sensor_width_mm: 6.4, sensor_height_mm: 4.8";

std::vector<Model> models() {
  return {
      {"pinhole (ideal)", "", kPinholeLens},
      {"opencv k1 k2 p1 p2", "{model: opencv, k1: -0.28, k2: 0.07, p1: 0.001, p2: -0.0005}",
       kPinholeLens},
      {"opencv rational+prism+tilt",
       "{model: opencv, k1: -0.21, k2: 0.05, k3: 0.001, k4: 0.1, k5: 0.01, k6: 0.001, p1: 0.001, "
       "p2: -0.0005, s1: 0.002, s2: -0.0003, s3: 0.001, s4: 0.0002, tau_x: 0.05, tau_y: -0.03}",
       kPinholeLens},
      {"kannala_brandt",
       "{model: kannala_brandt, k1: 0.02, k2: -0.003, k3: 0.0005, k4: -0.00005, "
       "max_field_angle_deg: 100}",
       kFisheyeLens},
      {"equidistant", "{model: equidistant, max_field_angle_deg: 100}", kFisheyeLens},
      {"equisolid", "{model: equisolid, max_field_angle_deg: 100}", kFisheyeLens},
      {"stereographic", "{model: stereographic, max_field_angle_deg: 100}", kFisheyeLens},
      {"orthographic", "{model: orthographic, max_field_angle_deg: 90}", kFisheyeLens},
      {"ftheta", "{model: ftheta, k1: 0.01, k2: -0.02, k3: 0.001, max_field_angle_deg: 100}",
       kFisheyeLens},
      {"unified (Mei)", "{model: unified, xi: 0.8, k1: -0.05, k2: 0.01, p1: 0.0005}", kFisheyeLens},
      {"double_sphere", "{model: double_sphere, xi: -0.2, alpha: 0.6, max_field_angle_deg: 100}",
       kFisheyeLens},
      {"equirectangular", "{model: equirectangular}", kFisheyeLens},
  };
}

PhysicalCamera makeCamera(const Model& m) {
  const std::string yaml =
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [1280, "
      "960], " +
      m.lens + (m.projection.empty() ? "" : ", projection: " + m.projection) +
      "}\nshapes: [{type: sphere, centre: [0, 0, 5], radius: 1, emission: {luminance: 1}}]\n";
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
      CameraSample s;
      // A fixed jitter per pixel (the R2 sequence), as a sampler's would be.
      const float jx = std::fmod(0.5f + 0.7548777f * float(x + y * res.x), 1.0f);
      const float jy = std::fmod(0.5f + 0.5698403f * float(x + y * res.x), 1.0f);
      s.pFilm = {float(x) + jx, float(y) + jy};
      const std::optional<camsim::CameraRay> r = camera.generateRay(s, lambda);
      if (!r) continue;
      ++p.rays;
      p.checksum += double(r->ray.d.x) + double(r->weight[0]);
    }
  p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return p;
}

// The worst |project(point 10 m along the ray through the pixel centre) − pixel centre|, px.
double roundTrip(const PhysicalCamera& camera, int& valid) {
  const glm::ivec2 res = camera.resolution();
  const camsim::SampledWavelengths lambda = camsim::SampledWavelengths::sampleVisible(0.37f);
  double worst = 0.0;
  valid = 0;
  for (int j = 0; j < 48; ++j)
    for (int i = 0; i < 64; ++i) {
      const glm::dvec2 px((i + 0.5) * res.x / 64.0, (j + 0.5) * res.y / 48.0);
      CameraSample s;
      s.pFilm = glm::vec2(px);
      const std::optional<camsim::CameraRay> r = camera.generateRay(s, lambda);
      if (!r) continue;
      const glm::dvec3 point = glm::dvec3(r->ray.o) + 10.0 * glm::normalize(glm::dvec3(r->ray.d));
      const std::optional<glm::dvec2> q = camera.project(point, 0.0);
      if (!q) continue;
      ++valid;
      worst = std::max(worst, glm::length(*q + 0.5 - px));
    }
  return worst;
}

}  // namespace

int main(int argc, char** argv) {
  const std::optional<int> parsed = camsim::bench::parseRounds(argc, argv, "camera_model_bench", 7);
  if (!parsed) return 2;
  const int rounds = *parsed;
  const std::vector<Model> ms = models();
  std::vector<PhysicalCamera> cameras;
  for (const Model& m : ms) cameras.push_back(makeCamera(m));
  std::vector<std::vector<double>> perPoint(ms.size());  // s per film point, per round
  std::vector<long> rays(ms.size());
  double checksum = 0.0;
  for (int r = 0; r < rounds; ++r)
    for (std::size_t k = 0; k < ms.size(); ++k) {
      const Pass p = timePass(cameras[k]);
      const glm::ivec2 res = cameras[k].resolution();
      perPoint[k].push_back(p.seconds / (double(res.x) * res.y));
      rays[k] = p.rays;
      checksum += p.checksum;
    }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  const double pinhole = median(perPoint[0]);
  std::printf("%-28s %12s %10s %10s %12s\n", "model", "Mrays/s", "vs pinhole", "valid",
              "round trip");
  for (std::size_t k = 0; k < ms.size(); ++k) {
    int valid = 0;
    const double err = roundTrip(cameras[k], valid);
    const glm::ivec2 res = cameras[k].resolution();
    const double t = median(perPoint[k]);
    std::printf("%-28s %12.2f %9.2fx %9.1f%% %9.1e px\n", ms[k].name,
                double(rays[k]) / (t * double(res.x) * res.y) * 1e-6, t / pinhole,
                100.0 * double(rays[k]) / (double(res.x) * res.y), err);
  }
  std::printf("(%d rounds, 1280 x 960 film points each, 1 thread; checksum %.6g)\n", rounds,
              checksum);
  return 0;
}
