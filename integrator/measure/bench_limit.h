// `camsim bench`: how close the tracer comes to the limit of bare Embree traversal, and
// what threads, motion blur and big meshes cost.
//
// Limit (per scene): one render (Sobol', the scene's resolution, captureSpp) records every
// ray it casts (integrator/render/ray_recorder.h): camera, bounce and shadow rays with their tMax
// and time. They are replayed through the scene's own EmbreeScene (intersect for camera and
// bounce rays, occluded for shadow rays) in 256-ray chunks over tbb::parallel_for in a
// task_arena of the same thread count, timing only the traversal loop: raw rays/s per kind
// (fastest of repeated passes) and for the recorded mix in recorded order. Renders of the
// same settings without the recorder give the tracer's rays/s; their ratio (tracer ÷ raw,
// same mix) is the share of the tracer's time that is traversal.
//
// Thread scaling: a render (spp) and a replay of the limit's recorded rays at 1 and at N
// threads.
// Motion overhead: the moving scene against the same scene with every motion reduced to its
// first keyframe (a static pose), and that static scene with time sampled anyway.
// Timed comparisons run in rounds in which the compared runs take turns (tracer and
// replay; 1 and N threads; moving, still and still time-sampled), so that a change in the
// machine's other load falls on all of them; each round times one run of each (the
// replay: one pass after a warm-up), and each keeps its fastest (the least disturbed). The
// limit also reports the range of the per-round ratios. The limit and thread scaling take 3
// rounds; the motion overhead, whose renders are short and whose variants differ by less
// than the host's noise on one render, takes 9, starting each with the next variant, and
// reports the median of its per-round ratios (each render ÷ its round's static render)
// with their range.
// Mesh build: a generated torus of ≥ N triangles written as binary PLY to a temporary
// directory, loaded through the scene loader (timed), then built into a Scene (timed: the
// TriangleMesh and Embree's BVH at the quality EmbreeScene picks) with the RSS growth measured (/proc/self/statm, after
// malloc_trim and with glibc's mmap threshold fixed at 128 KiB, so that large buffers get
// fresh pages rather than reusing freed ones); and built
// again as a bare Embree scene, at medium and at high BVH quality, with Embree's memory
// monitor counting its bytes (integrator/geometry/embree_probe.h).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "integrator/geometry/embree_probe.h"
#include "integrator/geometry/mesh_io.h"
#include "integrator/render/ray_recorder.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene_description.h"

namespace camsim {

struct LimitResult {
  std::string scene;
  glm::ivec2 resolution{0};  // px
  int spp = 0, threads = 0;
  std::uint64_t recorded = 0, dropped = 0;
  RenderStats capture;  // the recording render
  RenderStats tracer;   // the same render without the recorder: the fastest of the rounds
  ReplayResult mix;     // all recorded rays, recorded order: the fastest of the rounds
  // tracer ÷ raw rays/s within each round (tracer and replay alternate): its range
  // shows how much the machine's other load moved the ratio.
  double roundRatioLow = 0.0, roundRatioHigh = 0.0;
  std::array<ReplayResult, kRayKindCount> byKind;  // RayKind order
  double tracerRaysPerSecond() const { return tracer.raysPerSecond(); }
  double ratio() const {
    const double raw = mix.raysPerSecond();
    return raw > 0.0 ? tracerRaysPerSecond() / raw : 0.0;
  }
};
// raysOut, if given, receives the recorded rays (for measureThreadScaling).
LimitResult measureLimit(const Scene& scene, const std::string& name, int spp, int threads,
                         std::vector<RecordedRay>* raysOut = nullptr);

struct ScalingResult {
  glm::ivec2 resolution{0};  // px
  int threads = 0, spp = 0;
  RenderStats one, many;
  double cpuOne = 0.0, cpuMany = 0.0;  // process CPU seconds of each render
  ReplayResult rawOne, rawMany;        // the limit's recorded rays
};
// rays: those measureLimit recorded on this scene (raysOut).
ScalingResult measureThreadScaling(const Scene& scene, int spp,
                                   const std::vector<RecordedRay>& rays, int threads);

// Every shape's and the camera's motion reduced to its first keyframe.
SceneDescription withoutMotion(const SceneDescription& description);

// The median, lowest and highest of a set of ratios (all 0 if it is empty).
struct RatioSpread {
  double median = 0.0, low = 0.0, high = 0.0;
};
RatioSpread spreadOf(std::vector<double> ratios);

struct MotionOverhead {
  glm::ivec2 resolution{0};  // px
  int spp = 0;
  int timeSteps = 0;
  int rounds = 0;                               // rounds with a ratio (all, but for a 0 s clock)
  RenderStats moving, still, stillTimeSampled;  // the fastest of the rounds
  // Per round: seconds ÷ that round's static render.
  std::vector<double> movingRatios, stillTimeSampledRatios;
};
// `moving` is the Scene built from `description` (the bench's own; not built again here).
MotionOverhead measureMotionOverhead(const Scene& moving, const SceneDescription& description,
                                     int spp, int threads);

// A torus of 2·segments·rings ≥ triangles triangles with a bumpy tube.
MeshData makeTorusMesh(std::uint64_t triangles);
void writeBinaryPly(const std::filesystem::path& path, const MeshData& mesh);

struct MeshBuildResult {
  std::uint64_t triangles = 0;
  double plyMegabytes = 0.0;
  double loadSeconds = 0.0;          // scene loader incl. PLY parsing
  double sceneSeconds = 0.0;         // Scene: TriangleMesh + EmbreeScene (BVH build)
  double rssBytesPerTriangle = 0.0;  // RSS growth over Scene construction / triangles
  // The Scene's own Embree device (memory monitor: BVH and build temporaries; bytes
  // allocated, which includes reserved blocks not yet touched): in use after the build, peak.
  std::int64_t sceneEmbreeBytes = 0, sceneEmbreePeakBytes = 0;
  // The same mesh as a bare Embree scene at RTC_BUILD_QUALITY_MEDIUM and _HIGH.
  MeshBuildProbe embreeMedium, embreeHigh;
  // The same mesh moving (two keyframes over the shutter: an Embree instance of one pose,
  // whose BVH is built at the Scene's quality): Scene build time and Embree's bytes.
  double movingSceneSeconds = 0.0;
  std::int64_t movingEmbreeBytes = 0, movingEmbreePeakBytes = 0;
};
MeshBuildResult measureMeshBuild(std::uint64_t triangles, int threads,
                                 const std::filesystem::path& tempDir);

// Loading an image texture for reflectance: a size² 8-bit sRGB PNG of random colours (every
// texel a new colour, the worst case for the per-texel uplift) decoded, then every texel
// uplifted to a sigmoid polynomial (ImageSpectrumTexture). Error: the largest |RGB − RGB'| of
// 256 random texels, RGB' the uplifted spectrum's linear Rec.709 reflectance under D65.
struct TextureLoadResult {
  int size = 0;
  double decodeSeconds = 0.0;
  double upliftSeconds = 0.0;
  double upliftCpuSeconds = 0.0;  // process CPU time over the uplift, all threads
  double maxRgbError = 0.0;
};
TextureLoadResult measureTextureLoad(int size, int threads, const std::filesystem::path& tempDir);

// Printed reports and the limit CSV.
std::string formatLimitTable(const std::vector<LimitResult>& results);
std::string formatLimitCsv(const std::vector<LimitResult>& results);
std::string formatScaling(const std::string& scene, const ScalingResult& s);
std::string formatMotionOverhead(const std::string& scene, const MotionOverhead& m);
std::string formatMeshBuild(const MeshBuildResult& m);
std::string formatTextureLoad(const TextureLoadResult& t);

}  // namespace camsim
