// lens_camera_bench: what a traced lens costs per camera sample against the thin lens, how
// many samples it rejects, what building its exit-pupil bounds costs, and what diffraction at
// the stop adds — issue 39's row in docs/performance.md ("Traced lenses").
//
// Cameras, all on a 36 × 24 mm film of 1200 × 800 px (30 µm pitch), focused at infinity,
// static, each with camera.aperture.diffraction off and on:
//   thin lens        50 mm f/2, circular stop (the thin-lens path of PhysicalCamera)
//   dgauss.50mm      luts/lenses/dgauss.50mm.dat wide open (its file's stop, f/2.03)
//   fisheye.10mm     luts/lenses/fisheye.10mm.dat at its file's stop (f/3.95) on the same
//                    36 × 24 mm film: its ≈ 13.6 mm image circle leaves the film's corners
//                    and edges dark (those samples get no ray, counted as rejected)
//   telephoto.250mm  luts/lenses/telephoto.250mm.dat at its file's stop (f/5.42)
// Every camera is made from scene text by the scene loader, as a render makes it, and timed
// through PhysicalCamera::generateRay: the renderer's own path (thin lens, or LensCamera:
// ExitPupilBounds::sample and the trace through every surface at the hero wavelength).
//
// Samples: 2^18 camera samples drawn once from PCG32 (seed 39), the same for every camera:
// film point uniform over the film, lens point, the diffraction offset's two numbers and its
// wavelength choice uniform in [0, 1); the path's wavelengths cycle through 64 stratified
// SampledWavelengths::sampleVisible sets. Cameras alternate, round after round, so the
// machine's drift falls on all alike. Times are the thread's CPU time
// (CLOCK_THREAD_CPUTIME_ID), not wall time: a benchmark run at `nice -n 19` beside other
// builds waits for the core, and that wait is not the camera's cost.
//
//   Mrays/s         camera rays delivered per CPU second (samples that got a ray): median of
//                   the rounds, with the slowest and fastest round
//   µs/sample       CPU time per camera sample (with or without a ray), median
//   vs thin         µs/sample ÷ the thin lens's (diffraction off: ÷ thin off; on: ÷ thin on)
//   rejected        samples with no ray: outside the image circle (no exit-pupil bound for
//                   the film point) + lost in the lens (the traced ray hit a stop or a rim)
//   bounds          CPU seconds to build ExitPupilBounds (64 intervals, the film's half
//                   diagonal), median of one build per round, and the rays it traced
//   on − off        extra µs per sample with diffraction on (median on − median off)
//   jitter          Diffraction::sample alone (the PSF draw and the MIS weights), µs per call
//
// usage: lens_camera_bench [--rounds N]   (default 7)
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "bench/bench_rounds.h"
#include "integrator/camera/physical_camera.h"
#include "integrator/sampling/rng.h"
#include "integrator/scene/scene_loader.h"

namespace {

using camsim::CameraSample;
using camsim::PhysicalCamera;

constexpr int kSamples = 1 << 18;
constexpr int kWavelengthSets = 64;
constexpr int kWidth = 1200, kHeight = 800;  // px on 36 × 24 mm

struct Model {
  const char* name;
  std::string optics;  // the camera's lens keys: a thin lens's or `lens: {file}`
};

std::vector<Model> models() {
  return {{"thin lens 50 mm f/2", "focal_length_mm: 50, f_number: 2"},
          {"dgauss.50mm (f/2.03)", "lens: {file: dgauss.50mm.dat}"},
          {"fisheye.10mm (f/3.95)", "lens: {file: fisheye.10mm.dat}"},
          {"telephoto.250mm (f/5.42)", "lens: {file: telephoto.250mm.dat}"}};
}

PhysicalCamera makeCamera(const Model& m, bool diffraction) {
  const std::string yaml =
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [" + std::to_string(kWidth) +
      ", " + std::to_string(kHeight) + "], sensor_width_mm: 36, sensor_height_mm: 24, " + m.optics +
      ", aperture: {diffraction: " + (diffraction ? "true" : "false") +
      "}}\nshapes: [{type: sphere, centre: [0, 0, 5], radius: 1, emission: {luminance: 1}}]\n";
  return PhysicalCamera(camsim::loadSceneFromText(yaml, "bench.yaml", ".").camera);
}

using camsim::bench::threadCpuSeconds;  // the clock: this thread's CPU time, s

struct Samples {
  std::vector<CameraSample> camera;
  std::vector<camsim::SampledWavelengths> lambda;  // kWavelengthSets of them
};

Samples makeSamples() {
  Samples s;
  camsim::Pcg32 rng(39, 0);
  s.camera.resize(kSamples);
  for (CameraSample& c : s.camera) {
    c.pFilm = {rng.uniform() * float(kWidth), rng.uniform() * float(kHeight)};
    c.pPhotosite = c.pFilm - glm::floor(c.pFilm) - 0.5f;
    c.pLens = {rng.uniform(), rng.uniform()};
    c.pDiffraction = {rng.uniform(), rng.uniform()};
    c.uDiffractionWavelength = rng.uniform();
  }
  for (int k = 0; k < kWavelengthSets; ++k)
    s.lambda.push_back(
        camsim::SampledWavelengths::sampleVisible((float(k) + 0.5f) / float(kWavelengthSets)));
  return s;
}

const camsim::SampledWavelengths& lambdaOf(const Samples& s, int i) {
  return s.lambda[static_cast<size_t>(i % kWavelengthSets)];
}

struct Pass {
  double seconds;
  long rays;
  double checksum;
};

Pass timePass(const PhysicalCamera& camera, const Samples& s) {
  Pass p{0.0, 0, 0.0};
  const double start = threadCpuSeconds();
  for (int i = 0; i < kSamples; ++i) {
    const std::optional<camsim::CameraRay> r =
        camera.generateRay(s.camera[static_cast<size_t>(i)], lambdaOf(s, i));
    if (!r) continue;
    ++p.rays;
    p.checksum += double(r->ray.d.x) + double(r->weight[0]);
  }
  p.seconds = threadCpuSeconds() - start;
  return p;
}

// Diffraction::sample alone over the samples: s per call (photosites of `pitch` m).
double timeJitter(const camsim::Diffraction& d, const Samples& s, double pitch, double& checksum) {
  const double start = threadCpuSeconds();
  for (int i = 0; i < kSamples; ++i) {
    const CameraSample& c = s.camera[static_cast<size_t>(i)];
    const camsim::DiffractionSample j =
        d.sample(c.pDiffraction, c.uDiffractionWavelength, lambdaOf(s, i),
                 {pitch * glm::dvec2(c.pPhotosite), glm::dvec2(0.5 * pitch)});
    checksum += j.offset.x + double(j.weight[0]);
  }
  return (threadCpuSeconds() - start) / kSamples;
}

// Samples that get no exit-pupil bound (outside the image circle): the film point as
// PhysicalCamera::generateTracedRay makes it, inverted as LensCamera::generate does.
long outsideImageCircle(const PhysicalCamera& camera, const Samples& s) {
  const camsim::LensCamera* lens = camera.lensCamera();
  if (!lens) return 0;
  const glm::dvec2 size = camera.params().sensorSize;
  long none = 0;
  for (const CameraSample& c : s.camera) {
    const glm::dvec2 ndc = glm::dvec2(c.pFilm) / glm::dvec2(kWidth, kHeight);
    const glm::dvec2 film(-(ndc.x - 0.5) * size.x, -(0.5 - ndc.y) * size.y);
    if (!lens->pupil().sample(film, glm::dvec2(c.pLens))) ++none;
  }
  return none;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const std::optional<int> parsed = camsim::bench::parseRounds(argc, argv, "lens_camera_bench", 7);
  if (!parsed) return 2;
  const int rounds = *parsed;
  const std::vector<Model> ms = models();
  const Samples samples = makeSamples();
  // cameras[2k] diffraction off, cameras[2k + 1] on.
  std::vector<PhysicalCamera> cameras;
  for (const Model& m : ms)
    for (bool diffraction : {false, true}) cameras.push_back(makeCamera(m, diffraction));
  const size_t n = cameras.size();
  std::vector<std::vector<double>> perSample(n), jitter(n), bounds(ms.size());
  std::vector<long> rays(n), traced(ms.size());
  double checksum = 0.0;
  for (int round = 0; round < rounds; ++round) {
    for (size_t k = 0; k < n; ++k) {
      const Pass p = timePass(cameras[k], samples);
      perSample[k].push_back(p.seconds / kSamples);
      rays[k] = p.rays;
      checksum += p.checksum;
      if (const camsim::Diffraction* d = cameras[k].diffraction())
        jitter[k].push_back(timeJitter(*d, samples, 30e-6, checksum));  // 30 µm pitch
    }
    for (size_t m = 0; m < ms.size(); ++m) {
      const camsim::LensCamera* lens = cameras[2 * m].lensCamera();
      if (!lens) continue;
      const double start = threadCpuSeconds();
      const camsim::ExitPupilBounds b(lens->lens(), lens->sensorDistance(),
                                      0.5 * glm::length(cameras[2 * m].params().sensorSize));
      bounds[m].push_back(threadCpuSeconds() - start);
      traced[m] = b.raysTraced();
      checksum += b.area(0);
    }
  }

  std::printf("%-34s %24s %10s %8s %26s %22s\n", "camera", "Mrays/s (min-max)", "us/sample",
              "vs thin", "rejected (circle + lens)", "bounds s (rays)");
  for (size_t m = 0; m < ms.size(); ++m) {
    const size_t k = 2 * m;
    const std::vector<double>& t = perSample[k];
    const double med = median(t);
    const double mrays = 1e-6 * double(rays[k]) / kSamples;  // × 1/(s per sample)
    const long rejected = kSamples - rays[k];
    const long circle = outsideImageCircle(cameras[k], samples);
    char rej[64], bnd[64];
    std::snprintf(rej, sizeof rej, "%.1f %% (%.1f + %.1f)", 100.0 * rejected / kSamples,
                  100.0 * circle / kSamples, 100.0 * (rejected - circle) / kSamples);
    if (bounds[m].empty())
      std::snprintf(bnd, sizeof bnd, "-");
    else
      std::snprintf(bnd, sizeof bnd, "%.3f (%ld)", median(bounds[m]), traced[m]);
    std::printf("%-34s %8.3f (%6.3f-%6.3f) %10.4f %7.1fx %26s %22s\n", ms[m].name, mrays / med,
                mrays / *std::max_element(t.begin(), t.end()),
                mrays / *std::min_element(t.begin(), t.end()), 1e6 * med,
                med / median(perSample[0]), rej, bnd);
  }
  std::printf("\n%-34s %24s %10s %8s %12s %12s %10s\n", "camera, diffraction on",
              "Mrays/s (min-max)", "us/sample", "vs thin", "on - off us", "jitter us", "rejected");
  for (size_t m = 0; m < ms.size(); ++m) {
    const size_t k = 2 * m + 1;
    const std::vector<double>& t = perSample[k];
    const double med = median(t);
    const double mrays = 1e-6 * double(rays[k]) / kSamples;
    std::printf("%-34s %8.3f (%6.3f-%6.3f) %10.4f %7.1fx %12.4f %12.4f %9.1f%%\n", ms[m].name,
                mrays / med, mrays / *std::max_element(t.begin(), t.end()),
                mrays / *std::min_element(t.begin(), t.end()), 1e6 * med,
                med / median(perSample[1]), 1e6 * (med - median(perSample[k - 1])),
                1e6 * median(jitter[k]), 100.0 * double(kSamples - rays[k]) / kSamples);
  }
  std::printf("(%d rounds of %d samples per camera, 1 thread, thread CPU time; checksum %.6g)\n",
              rounds, kSamples, checksum);
  return 0;
}
