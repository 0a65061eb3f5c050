#include "integrator/measure/bench_limit.h"

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>
#include <random>
#include <stdexcept>

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include "integrator/measure/bench_metrics.h"
#include "integrator/measure/bench_reference.h"
#include "integrator/render/ray_recorder.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "integrator/textures/image_texture.h"
#include "integrator/textures/reflectance_uplift.h"
#include "sensor/io/png_io.h"
#include "sensor/spectra/rgb_uplift.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {
namespace {

constexpr int kRepeats = 3;       // rounds of the limit and thread scaling (see bench_limit.h)
constexpr int kMotionRounds = 9;  // rounds of the motion overhead

RenderResult renderWith(const Scene& scene, int spp, int threads, RayRecorder* recorder = nullptr,
                        bool forceTime = false) {
  RenderOptions o = benchRenderOptions(spp, 1, threads, SamplerKind::kSobol);
  o.rayObserver = recorder;
  o.forceTime = forceTime;
  return renderXyz(scene, o);
}

// The fastest of a series of timed runs (short runs on a shared machine: the minimum is
// the least disturbed), with the process CPU time of that run.
template <typename Stats>
struct Fastest {
  Stats best;
  double cpuSeconds = 0.0;
  bool any = false;
  void offer(const Stats& s, double cpu = 0.0) {
    if (any && !(s.seconds < best.seconds)) return;
    best = s;
    cpuSeconds = cpu;
    any = true;
  }
};

// One more render of a series; returns its figures.
RenderStats renderTimed(Fastest<RenderStats>& series, const Scene& scene, int spp, int threads,
                        bool forceTime = false) {
  const double cpu0 = processCpuSeconds();
  const RenderStats s = renderWith(scene, spp, threads, nullptr, forceTime).stats;
  series.offer(s, processCpuSeconds() - cpu0);
  return s;
}

double residentBytes() {
  std::ifstream statm("/proc/self/statm");
  double pages = 0.0, resident = 0.0;
  statm >> pages >> resident;
  return resident * static_cast<double>(::sysconf(_SC_PAGESIZE));
}

double limitSecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

LimitResult measureLimit(const Scene& scene, const std::string& name, int spp, int threads,
                         std::vector<RecordedRay>* raysOut) {
  LimitResult r;
  r.scene = name;
  r.resolution = scene.camera().resolution();
  r.spp = spp;
  r.threads = threads > 0 ? threads : tbb::info::default_concurrency();
  std::vector<RecordedRay> rays;
  {
    RayRecorder recorder;
    r.capture = renderWith(scene, spp, threads, &recorder).stats;
    rays = recorder.takeRays();
    r.dropped = recorder.dropped();
  }
  r.recorded = rays.size();
  // The tracer and the replay of its mix take turns, kRepeats rounds, so that a change in
  // the machine's other load falls on both; each round times one render and one replay
  // pass (after an untimed warm-up pass), and each side keeps its fastest of the rounds: a
  // minimum over the same number of runs on both sides.
  Fastest<RenderStats> tracer;
  Fastest<ReplayResult> mix;
  std::vector<double> ratios;
  for (int round = 0; round < kRepeats; ++round) {
    const RenderStats t = renderTimed(tracer, scene, spp, threads);
    const ReplayResult m = replayRays(scene.geometry(), rays, threads, 0.0, 1);
    mix.offer(m);
    ratios.push_back(m.raysPerSecond() > 0.0 ? t.raysPerSecond() / m.raysPerSecond() : 0.0);
  }
  const RatioSpread spread = spreadOf(std::move(ratios));
  r.roundRatioLow = spread.low;
  r.roundRatioHigh = spread.high;
  r.tracer = tracer.best;
  r.mix = mix.best;
  for (int k = 0; k < kRayKindCount; ++k)
    r.byKind[static_cast<std::size_t>(k)] =
        replayRays(scene.geometry(), raysOfKind(rays, static_cast<RayKind>(k)), threads, 0.25);
  if (raysOut) *raysOut = std::move(rays);
  return r;
}

ScalingResult measureThreadScaling(const Scene& scene, int spp,
                                   const std::vector<RecordedRay>& rays, int threads) {
  ScalingResult s;
  s.resolution = scene.camera().resolution();
  s.spp = spp;
  s.threads = threads > 0 ? threads : tbb::info::default_concurrency();
  // 1 and N threads take turns (see measureLimit), each keeping its fastest render.
  Fastest<RenderStats> one, many;
  for (int round = 0; round < kRepeats; ++round) {
    renderTimed(one, scene, spp, 1);
    renderTimed(many, scene, spp, s.threads);
  }
  s.one = one.best;
  s.cpuOne = one.cpuSeconds;
  s.many = many.best;
  s.cpuMany = many.cpuSeconds;
  s.rawOne = replayRays(scene.geometry(), rays, 1);
  s.rawMany = replayRays(scene.geometry(), rays, s.threads);
  return s;
}

SceneDescription withoutMotion(const SceneDescription& description) {
  SceneDescription d = description;
  for (ShapeDescription& s : d.shapes)
    if (s.motion.keys().size() > 1) s.motion = RigidMotion({s.motion.keys().front()});
  if (d.camera.motion.keys().size() > 1)
    d.camera.motion = RigidMotion({d.camera.motion.keys().front()});
  return d;
}

RatioSpread spreadOf(std::vector<double> ratios) {
  if (ratios.empty()) return {};
  std::sort(ratios.begin(), ratios.end());
  const std::size_t n = ratios.size();
  const double median = n % 2 == 1 ? ratios[n / 2] : 0.5 * (ratios[n / 2 - 1] + ratios[n / 2]);
  return {median, ratios.front(), ratios.back()};
}

MotionOverhead measureMotionOverhead(const Scene& moving, const SceneDescription& description,
                                     int spp, int threads) {
  MotionOverhead m;
  m.resolution = moving.camera().resolution();
  m.spp = spp;
  m.timeSteps = moving.modelled().timeSteps;
  const Scene still(withoutMotion(description));
  Fastest<RenderStats> series[3];                        // static, static time-sampled, moving
  for (int round = 0; round < kMotionRounds; ++round) {  // taking turns, as in measureLimit
    double seconds[3];
    for (int k = 0; k < 3; ++k) {  // each round starts with the next variant
      const int v = (round + k) % 3;
      seconds[v] = renderTimed(series[v], v == 2 ? moving : still, spp, threads, v == 1).seconds;
    }
    if (!(seconds[0] > 0.0)) continue;  // a clock too coarse for the render: no ratio
    m.stillTimeSampledRatios.push_back(seconds[1] / seconds[0]);
    m.movingRatios.push_back(seconds[2] / seconds[0]);
  }
  m.rounds = static_cast<int>(m.movingRatios.size());
  m.still = series[0].best;
  m.stillTimeSampled = series[1].best;
  m.moving = series[2].best;
  return m;
}

MeshData makeTorusMesh(std::uint64_t triangles) {
  const auto quads = static_cast<double>((triangles + 1) / 2);
  const auto segments = static_cast<std::uint32_t>(std::ceil(std::sqrt(2.0 * quads)));
  const auto rings = static_cast<std::uint32_t>(std::ceil(quads / segments));
  constexpr double kTwoPi = 6.283185307179586;
  MeshData mesh;
  mesh.positions.reserve(static_cast<std::size_t>(segments) * rings);
  for (std::uint32_t i = 0; i < segments; ++i)
    for (std::uint32_t j = 0; j < rings; ++j) {
      const double u = kTwoPi * i / segments, v = kTwoPi * j / rings;
      const double tube = 0.2 * (1.0 + 0.08 * std::sin(13.0 * u) * std::sin(7.0 * v));
      const double ring = 0.5 + tube * std::cos(v);
      mesh.positions.emplace_back(static_cast<float>(ring * std::cos(u)),
                                  static_cast<float>(tube * std::sin(v)),
                                  static_cast<float>(ring * std::sin(u)));
    }
  mesh.indices.reserve(6 * static_cast<std::size_t>(segments) * rings);
  for (std::uint32_t i = 0; i < segments; ++i)
    for (std::uint32_t j = 0; j < rings; ++j) {
      const std::uint32_t a = i * rings + j, b = ((i + 1) % segments) * rings + j;
      const std::uint32_t c = ((i + 1) % segments) * rings + (j + 1) % rings,
                          e = i * rings + (j + 1) % rings;
      mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, e});
    }
  return mesh;
}

void writeBinaryPly(const std::filesystem::path& path, const MeshData& mesh) {
  static_assert(std::endian::native == std::endian::little,
                "binary_little_endian is written as in memory");
  std::ofstream out(path, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\nelement vertex " << mesh.positions.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face "
      << mesh.indices.size() / 3 << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const glm::vec3& p : mesh.positions)
    out.write(reinterpret_cast<const char*>(&p.x), 3 * sizeof(float));
  std::vector<char> faces(13 * (mesh.indices.size() / 3));
  for (std::size_t t = 0; t < mesh.indices.size() / 3; ++t) {
    faces[13 * t] = 3;
    for (int k = 0; k < 3; ++k) {
      const auto index =
          static_cast<std::int32_t>(mesh.indices[3 * t + static_cast<std::size_t>(k)]);
      std::memcpy(&faces[13 * t + 1 + 4 * static_cast<std::size_t>(k)], &index, 4);
    }
  }
  out.write(faces.data(), static_cast<std::streamsize>(faces.size()));
  if (!out.flush()) throw std::runtime_error("cannot write the benchmark mesh " + path.string());
}

MeshBuildResult measureMeshBuild(std::uint64_t triangles, int threads,
                                 const std::filesystem::path& tempDir) {
  MeshBuildResult m;
  const std::filesystem::path ply = tempDir / "torus.ply";
  {
    const MeshData mesh = makeTorusMesh(triangles);
    m.triangles = mesh.indices.size() / 3;
    writeBinaryPly(ply, mesh);
  }
  m.plyMegabytes = static_cast<double>(std::filesystem::file_size(ply)) * 1e-6;
  // The torus moving (0.1 m and 10° over a 10 ms shutter); the still scene is the same
  // description at its first keyframe (withoutMotion), so the PLY is read once.
  const std::string text =
      "format: camsim-scene/1\nname: mesh_build\nrender: {spp: 1}\n"
      "camera: {position: [0, 1.5, -1.5], look_at: [0, 0, 0], up: [0, 1, 0], "
      "resolution: [16, 16], shutter: {open: 0, close: 0.01}}\n"
      "materials: {grey: {type: diffuse, reflectance: 0.5}}\n"
      "shapes:\n  - {name: torus, type: mesh, file: torus.ply, material: grey, motion: "
      "[{time: 0}, {time: 0.01, translate: [0.1, 0, 0], rotate: {axis: [0, 1, 0], "
      "angle_deg: 10}}]}\n"
      "  - {name: lamp, type: sphere, centre: [0, 2, 0], radius: 0.1, emission: "
      "{luminance: 1000}}\n";
  const auto start = std::chrono::steady_clock::now();
  const SceneDescription moving = loadSceneFromText(text, "<bench mesh>", tempDir);
  m.loadSeconds = limitSecondsSince(start);
  const SceneDescription desc = withoutMotion(moving);
  tbb::task_arena arena(threads > 0 ? threads : tbb::info::default_concurrency());
  // Builds a Scene on the arena, timed; records what its Embree device holds after the
  // build and at its peak. Returned alive, so the resident set can be read with it.
  const auto build = [&](const SceneDescription& d, double& seconds, std::int64_t& bytes,
                         std::int64_t& peak) {
    const auto t0 = std::chrono::steady_clock::now();
    std::unique_ptr<Scene> scene;
    arena.execute([&] { scene = std::make_unique<Scene>(d); });
    seconds = limitSecondsSince(t0);
    bytes = scene->geometry().embreeBytes();
    peak = scene->geometry().embreePeakBytes();
    return scene;
  };
  {
    // Large blocks straight from mmap (a fixed threshold also stops glibc from raising it
    // after big frees) and free heap pages returned: the resident set then grows by what
    // the Scene really keeps, instead of reusing pages freed earlier in the run.
    mallopt(M_MMAP_THRESHOLD, 128 * 1024);
    malloc_trim(0);
    const double before = residentBytes();
    const auto still = build(desc, m.sceneSeconds, m.sceneEmbreeBytes, m.sceneEmbreePeakBytes);
    m.rssBytesPerTriangle = (residentBytes() - before) / static_cast<double>(m.triangles);
  }
  build(moving, m.movingSceneSeconds, m.movingEmbreeBytes, m.movingEmbreePeakBytes);
  m.embreeMedium = probeMeshBuild(desc.shapes.front().mesh, threads, BvhQuality::kMedium);
  m.embreeHigh = probeMeshBuild(desc.shapes.front().mesh, threads, BvhQuality::kHigh);
  std::error_code ec;
  std::filesystem::remove(ply, ec);
  return m;
}

TextureLoadResult measureTextureLoad(int size, int threads, const std::filesystem::path& tempDir) {
  TextureLoadResult t;
  t.size = size;
  std::mt19937 rng(5);
  PngImage png;
  png.width = png.height = size;
  png.channels = 3;
  png.samples.resize(static_cast<size_t>(size) * static_cast<size_t>(size) * 3);
  for (std::uint16_t& q : png.samples) q = static_cast<std::uint16_t>(rng() & 0xff);
  const std::filesystem::path file = tempDir / "random.png";
  writePng(file, png);
  tbb::task_arena arena(threads > 0 ? threads : tbb::info::default_concurrency());
  ReflectanceUplift::
      linearRec709();  // its start table is built once per process (~0.1 s): not timed
  auto start = std::chrono::steady_clock::now();
  const TextureImage image = loadTextureImage(file, TextureEncoding::kSrgb);
  t.decodeSeconds = limitSecondsSince(start);
  start = std::chrono::steady_clock::now();
  const double cpu0 = processCpuSeconds();
  std::unique_ptr<ImageSpectrumTexture> texture;
  arena.execute([&] {
    texture = std::make_unique<ImageSpectrumTexture>(image, glm::vec2(1.0f), glm::vec2(0.0f));
  });
  t.upliftSeconds = limitSecondsSince(start);
  t.upliftCpuSeconds = processCpuSeconds() - cpu0;
  for (int k = 0; k < 256; ++k) {
    const int x = static_cast<int>(rng() % static_cast<unsigned>(size));
    const int y = static_cast<int>(rng() % static_cast<unsigned>(size));
    Spectrum s;
    for (int i = 0; i < kSpectrumSamples; ++i)
      s.sample(i) = texture->texelValue(x, y, static_cast<float>(kLambdaMinNm + i));
    const glm::dvec3 rgb = reflectanceToRgb(s, RgbColorSpace::linearRec709());
    const size_t at =
        (static_cast<size_t>(y) * static_cast<size_t>(size) + static_cast<size_t>(x)) * 3;
    for (int c = 0; c < 3; ++c)
      t.maxRgbError = std::max(
          t.maxRgbError,
          std::abs(rgb[c] - static_cast<double>(image.values[at + static_cast<size_t>(c)])));
  }
  std::error_code ec;
  std::filesystem::remove(file, ec);
  return t;
}

}  // namespace camsim
