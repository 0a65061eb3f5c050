// Tests for the limit side of `camsim bench` (integrator/render/ray_recorder.h, integrator/measure/bench_limit.h):
// the recorder captures exactly the rays the render counts, by kind; replaying them finds
// the same hits; the limit times the same rays in each round; motion can be removed; the generated mesh is what the PLY reader reads
// back; and the binary runs end to end into a directory (tables, CSVs), exiting 2 after a
// scene that does not load. No timing is asserted.
#include "tests/support/temp_dir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "cli/bench_command.h"
#include "integrator/measure/bench_limit.h"
#include "integrator/measure/bench_metrics.h"
#include "integrator/measure/bench_reference.h"
#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "tests/support/run_command.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

using test::readFile;

namespace fs = std::filesystem;

SceneDescription suiteScene(const std::string& name, glm::ivec2 resolution) {
  SceneDescription d = loadScene(benchScenePath(name));
  d.camera.resolution = resolution;
  return d;
}

RenderResult renderRecorded(const Scene& scene, int spp, int threads, RayRecorder* recorder) {
  RenderOptions o;
  o.spp = spp;
  o.seed = 3;
  o.threads = threads;
  o.rayObserver = recorder;
  return render(scene, SpectralResponse::cieXyz(), o);
}

TEST(RayRecorder, RecordsEveryCountedRayByKind) {
  const Scene scene(suiteScene("cornell_box", {24, 24}));
  RayRecorder recorder;
  const RenderResult r = renderRecorded(scene, 2, 2, &recorder);
  const std::vector<RecordedRay> rays = recorder.takeRays();
  EXPECT_EQ(recorder.dropped(), 0u);
  ASSERT_EQ(rays.size(), r.stats.rays.total());
  EXPECT_EQ(raysOfKind(rays, RayKind::kCamera).size(), r.stats.rays.camera);
  EXPECT_EQ(raysOfKind(rays, RayKind::kBounce).size(), r.stats.rays.bounce);
  EXPECT_EQ(raysOfKind(rays, RayKind::kShadow).size(), r.stats.rays.shadow);
  EXPECT_GT(r.stats.rays.bounce, 0u);
  EXPECT_GT(r.stats.rays.shadow, 0u);
  // Recording does not change the image.
  const RenderResult plain = renderRecorded(scene, 2, 2, nullptr);
  EXPECT_EQ(plain.image.pixels, r.image.pixels);
}

TEST(RayRecorder, StopsAtItsLimitAndCountsTheRest) {
  const Scene scene(suiteScene("cornell_box", {16, 16}));
  RayRecorder recorder(100);
  const RenderResult r = renderRecorded(scene, 1, 2, &recorder);
  const std::size_t kept = recorder.takeRays().size();
  EXPECT_EQ(kept, 100u);
  EXPECT_EQ(kept + recorder.dropped(), r.stats.rays.total());
  EXPECT_TRUE(recorder.takeRays().empty());  // taken: nothing left
}

TEST(RayReplay, FindsTheSameHitsAsASerialLoop) {
  const Scene scene(suiteScene("cornell_box", {16, 16}));
  RayRecorder recorder;
  renderRecorded(scene, 2, 1, &recorder);
  const std::vector<RecordedRay> rays = recorder.takeRays();
  std::uint64_t expected = 0;
  for (const RecordedRay& rr : rays) {
    Hit hit;
    const bool found = rr.kind == RayKind::kShadow ? scene.geometry().occluded(rr.ray)
                                                   : scene.geometry().intersect(rr.ray, hit);
    expected += found ? 1u : 0u;
  }
  const ReplayResult replay = replayRays(scene.geometry(), rays, 2, 0.0);
  EXPECT_EQ(replay.rays, rays.size());
  EXPECT_EQ(replay.hits, expected);
  EXPECT_GE(replay.passes, 3);
  EXPECT_GT(replay.seconds, 0.0);
  EXPECT_EQ(replayRays(scene.geometry(), rays, 1, 0.0, 1).passes, 1);
  EXPECT_EQ(replayRays(scene.geometry(), rays, 1, 0.0, 5).passes, 5);
  // One kind alone: camera rays, most of which hit the box (its open front lets a few out).
  const auto camera = raysOfKind(rays, RayKind::kCamera);
  std::uint64_t cameraHits = 0;
  for (const RecordedRay& rr : camera) {
    Hit hit;
    cameraHits += scene.geometry().intersect(rr.ray, hit) ? 1u : 0u;
  }
  EXPECT_GT(cameraHits, camera.size() / 2);
  EXPECT_EQ(replayRays(scene.geometry(), camera, 1, 0.0).hits, cameraHits);
  EXPECT_EQ(replayRays(scene.geometry(), {}, 1).rays, 0u);
}

TEST(BenchLimit, TracerAndReplayTimeTheSameRaysOnePassPerRound) {
  const Scene scene(suiteScene("cornell_box", {16, 16}));
  const LimitResult r = measureLimit(scene, "cornell_box", 2, 2);
  // The timed renders are the recorded one without the recorder: the same rays.
  EXPECT_EQ(r.tracer.rays.total(), r.capture.rays.total());
  EXPECT_EQ(r.recorded, r.capture.rays.total());
  EXPECT_EQ(r.mix.rays, r.recorded);
  EXPECT_EQ(r.resolution, glm::ivec2(16, 16));
  EXPECT_EQ(r.mix.passes, 1);  // one timed pass per round, as the tracer's one render
  EXPECT_GT(r.ratio(), 0.0);
  EXPECT_GT(r.roundRatioLow, 0.0);
  EXPECT_LE(r.roundRatioLow, r.roundRatioHigh);
  const std::string csv = formatLimitCsv({r});
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "scene,kind,width,height,spp,threads,rays,share,raw_rays_per_s,tracer_rays_per_s,ratio,"
            "round_ratio_min,round_ratio_max");
  EXPECT_NE(formatLimitTable({r}).find("rounds"), std::string::npos);
  EXPECT_NE(formatLimitTable({r}).find("16x16"), std::string::npos);
  EXPECT_NE(csv.find("cornell_box,mix,16,16,2,2,"), std::string::npos) << csv;
}

TEST(BenchLimit, ThreadScalingReplaysTheRaysOfTheCaptureRender) {
  const Scene scene(suiteScene("cornell_box", {16, 16}));
  std::vector<RecordedRay> rays;
  const LimitResult limit = measureLimit(scene, "cornell_box", 1, 2, &rays);
  const ScalingResult s = measureThreadScaling(scene, 4, rays, 2);
  // The capture: the bench's render settings at 1 spp.
  const RenderResult capture = renderXyz(scene, benchRenderOptions(1, 1, 2, SamplerKind::kSobol));
  EXPECT_EQ(s.rawOne.rays, capture.stats.rays.total());
  EXPECT_EQ(s.rawMany.rays, s.rawOne.rays);
  EXPECT_EQ(limit.dropped, 0u);
  EXPECT_EQ(s.one.rays.total(), s.many.rays.total());  // the same render at 1 and 2 threads
  EXPECT_GT(s.one.rays.total(), s.rawOne.rays);        // 4 spp against the capture's 1
  EXPECT_NE(formatScaling("cornell_box", s).find("16x16"), std::string::npos);
}

TEST(BenchLimit, WithoutMotionMakesTheMotionBlurSceneStatic) {
  const SceneDescription moving = suiteScene("motion_blur", {32, 21});
  EXPECT_TRUE(Scene(moving).modelled().time);
  const SceneDescription still = withoutMotion(moving);
  const Scene scene(still);
  EXPECT_FALSE(scene.modelled().time);
  EXPECT_EQ(scene.modelled().timeSteps, 1);
  ASSERT_EQ(still.shapes.size(), moving.shapes.size());
  for (std::size_t i = 0; i < still.shapes.size(); ++i) {
    if (moving.shapes[i].motion.empty()) continue;  // the first key's pose is kept
    const RigidMotion& m = moving.shapes[i].motion;
    EXPECT_TRUE(still.shapes[i].motion.at(1.0) == m.at(m.keys().front().time)) << i;
  }
}

TEST(BenchLimit, SpreadOfRatiosIsTheirMedianAndRange) {
  const RatioSpread odd = spreadOf({1.3, 0.9, 1.1, 2.0, 1.0});
  EXPECT_DOUBLE_EQ(odd.median, 1.1);
  EXPECT_DOUBLE_EQ(odd.low, 0.9);
  EXPECT_DOUBLE_EQ(odd.high, 2.0);
  EXPECT_DOUBLE_EQ(spreadOf({1.0, 2.0, 4.0, 3.0}).median, 2.5);
  const RatioSpread none = spreadOf({});
  EXPECT_EQ(none.median, 0.0);
  EXPECT_EQ(none.high, 0.0);
}

// Every round renders the three variants; the time-sampled static render traces the same
// paths as the static one (time has its own sampler dimension, and nothing moves).
TEST(BenchLimit, MotionOverheadComparesTheVariantsRoundByRound) {
  const SceneDescription description = suiteScene("motion_blur", {32, 21});
  const Scene moving(description);
  const MotionOverhead m = measureMotionOverhead(moving, description, 2, 2);
  EXPECT_EQ(m.resolution, glm::ivec2(32, 21));
  EXPECT_GT(m.timeSteps, 1);
  EXPECT_GE(m.rounds, 5);
  EXPECT_EQ(m.movingRatios.size(), static_cast<std::size_t>(m.rounds));
  EXPECT_EQ(m.stillTimeSampledRatios.size(), static_cast<std::size_t>(m.rounds));
  EXPECT_EQ(m.still.rays.total(), m.stillTimeSampled.rays.total());
  EXPECT_TRUE(m.moving.modelled.time);
  EXPECT_TRUE(m.stillTimeSampled.modelled.time);
  EXPECT_FALSE(m.still.modelled.time);
  for (const double r : m.movingRatios) EXPECT_GT(r, 0.0);
  const std::string table = formatMotionOverhead("motion_blur", m);
  EXPECT_NE(table.find("32x21"), std::string::npos) << table;
  EXPECT_NE(table.find("rounds"), std::string::npos) << table;
}

TEST(BenchLimit, TorusMeshRoundTripsThroughBinaryPly) {
  const MeshData mesh = makeTorusMesh(5000);
  EXPECT_GE(mesh.indices.size() / 3, 5000u);
  EXPECT_LT(mesh.indices.size() / 3, 5400u);
  for (std::uint32_t i : mesh.indices) ASSERT_LT(i, mesh.positions.size());
  test::TempDir dir;
  writeBinaryPly(dir.path() / "t.ply", mesh);
  const MeshData back = readPly(dir.path() / "t.ply");
  EXPECT_EQ(back.indices, mesh.indices);
  EXPECT_EQ(back.positions, mesh.positions);
  const MeshBuildResult m = measureMeshBuild(2000, 1, dir.path());
  EXPECT_GE(m.triangles, 2000u);
  // Embree's memory monitor reports frees too: the build's temporaries are gone afterwards,
  // so the peak is above what stays; what stays is at least the BVH's leaves (> 8 B/triangle).
  for (const MeshBuildProbe* p : {&m.embreeMedium, &m.embreeHigh}) {
    EXPECT_EQ(p->triangles, m.triangles);
    EXPECT_GT(p->bytesAfterBuild, static_cast<std::int64_t>(8 * m.triangles));
    EXPECT_GT(p->bytesPeak, p->bytesAfterBuild);
  }
  // Below 250 k triangles the Scene builds at high quality, like the probe's high build
  // (same arrays shared, plus the lamp sphere's buffer: within 5 %).
  EXPECT_NEAR(static_cast<double>(m.sceneEmbreeBytes),
              static_cast<double>(m.embreeHigh.bytesAfterBuild),
              0.05 * static_cast<double>(m.embreeHigh.bytesAfterBuild));
  EXPECT_GT(m.sceneEmbreePeakBytes, m.sceneEmbreeBytes);
  // Moving, the mesh is an instance of one pose: Embree holds no more than at rest, but for
  // the instance and its top-level scene (within 5 %).
  EXPECT_GT(m.movingSceneSeconds, 0.0);
  EXPECT_NEAR(static_cast<double>(m.movingEmbreeBytes), static_cast<double>(m.sceneEmbreeBytes),
              0.05 * static_cast<double>(m.sceneEmbreeBytes));
}

TEST(BenchLimit, TextureLoadUpliftsEveryTexelWithinItsStatedError) {
  test::TempDir dir;
  const TextureLoadResult t = measureTextureLoad(64, 1, dir.path());
  EXPECT_EQ(t.size, 64);
  EXPECT_GE(t.decodeSeconds, 0.0);
  EXPECT_GE(t.upliftSeconds, 0.0);
  EXPECT_GT(t.maxRgbError, 0.0);   // a fit, not a copy
  EXPECT_LT(t.maxRgbError, 5e-5);  // reflectance_uplift.h's round-trip bound
  EXPECT_FALSE(fs::exists(dir.path() / "random.png"));
  EXPECT_NE(formatTextureLoad(t).find("64 x 64 random-colour"), std::string::npos);
}

// ---- the binary ------------------------------------------------------------------------

int runBench(const std::string& args, const fs::path& logDir) {
  // No plot: CAMSIM_PYTHON names no interpreter (the plot script is the PtcBinary tests' kind
  // of concern; here only the numbers' files are checked).
  return test::runCamsim("bench " + args, logDir, "CAMSIM_PYTHON=/nonexistent").exitCode;
}

TEST(BenchBinary, SmallRunWritesTablesAndCsvs) {
  test::TempDir dir;
  const fs::path out = dir.path() / "out";
  ASSERT_EQ(runBench("--scenes cornell_box --resolution 16 --max-spp 2 --ref-spp 4 "
                     "--feature-resolution 16 --mesh-triangles 1000 --texture-size 16 --out " +
                         out.string() + " --cache " + (dir.path() / "cache").string(),
                     dir.path()),
            0)
      << readFile(dir.path() / "stderr.txt");
  const std::string stdoutText = readFile(dir.path() / "stdout.txt");
  for (const char* needle :
       {"slope rMSE/time", "raw mix/s", "thread scaling", "mesh build", "texture load", "total:"})
    EXPECT_NE(stdoutText.find(needle), std::string::npos) << needle;
  const std::string csv = readFile(out / "bench.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "scene,sampler,spp,width,height,seconds,cpu_seconds,samples_per_s,"
            "rays_per_s,rmse_rel,mrae,ref_rmse_rel,ref_mrae,in_fit,est_rmse_rel,est_mrae");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'),
            1 + 2 * 2);  // header + 2 samplers × budgets 1, 2
  EXPECT_NE(readFile(out / "bench_limit.csv").find("cornell_box,mix,"), std::string::npos);
  EXPECT_EQ(readFile(out / "bench.txt"), stdoutText);
  EXPECT_TRUE(fs::is_directory(dir.path() / "cache"));
}

TEST(BenchBinary, AMissingSceneExitsTwoAfterTheOthers) {
  test::TempDir dir;
  const fs::path out = dir.path() / "out";
  EXPECT_EQ(runBench("--scenes cornell_box,no_such_scene --resolution 8 --max-spp 1 --ref-spp 2 "
                     "--feature-resolution 8 --mesh-triangles 0 --out " +
                         out.string() + " --cache " + (dir.path() / "cache").string(),
                     dir.path()),
            2);
  EXPECT_NE(readFile(dir.path() / "stderr.txt").find("no_such_scene"), std::string::npos);
  EXPECT_TRUE(fs::is_regular_file(out / "bench.csv"));
  EXPECT_EQ(runBench("--max-spp nope", dir.path()), 2);
  // A scene without light: its reference is black, every relative error 0/0 — bench.txt
  // held "-nan" ratios and the run exited 0 (found by probing). Skipped, exit 2.
  test::writeFile(dir.path() / "dark.yaml",
                  "name: dark\ncamera: {position: [0, 0, -3], look_at: [0, 0, 0], resolution: "
                  "[8, 8]}\nmaterials: {m: {type: diffuse}}\nshapes: [{type: sphere, centre: "
                  "[0, 0, 0], radius: 1, material: m}]\n");
  EXPECT_EQ(runBench("--scenes cornell_box," + (dir.path() / "dark.yaml").string() +
                         " --resolution 8 --max-spp 1 --ref-spp 2 --feature-resolution 8 "
                         "--mesh-triangles 0 --texture-size 0 --out " +
                         out.string() + " --cache " + (dir.path() / "cache").string(),
                     dir.path()),
            2);
  EXPECT_NE(readFile(dir.path() / "stderr.txt").find("skipping dark: its reference image is black"),
            std::string::npos)
      << readFile(dir.path() / "stderr.txt");
  const std::string text = readFile(out / "bench.txt");
  EXPECT_EQ(text.find(" -nan"), std::string::npos) << text;
  EXPECT_EQ(text.find(" nan"), std::string::npos) << text;
  EXPECT_NE(readFile(out / "bench.txt").find("cornell_box"), std::string::npos);
}

}  // namespace
}  // namespace camsim
