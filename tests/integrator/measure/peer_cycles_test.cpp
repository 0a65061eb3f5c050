// The Cycles translation of `camsim bench --peer cycles` and its equal-error arithmetic,
// without Blender: the generated script's values for the Cornell box, the RGB of known
// spectra, what is refused, and log-log interpolation on a made-up ladder.
#include "integrator/measure/peer_cycles.h"

#include <gtest/gtest.h>

#include <limits>
#include <sstream>

#include "integrator/measure/peer_compare.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/spectra/cie.h"

namespace camsim {
namespace {

SceneDescription loadBundled(const std::string& name) {
  return loadScene(std::filesystem::path(CAMSIM_SOURCE_DIR) / "scenes" / (name + ".yaml"));
}

// The line of `script` that starts with `prefix` (empty if none).
std::string lineStarting(const std::string& script, const std::string& prefix) {
  std::istringstream in(script);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(prefix, 0) == 0) return line;
  return {};
}

// The number after `prefix` on the line that starts with it (NaN if none).
double valueOf(const std::string& script, const std::string& prefix) {
  const std::string line = lineStarting(script, prefix);
  if (line.empty()) return std::nan("");
  return std::stod(line.substr(prefix.size()));
}

// The first "(a, b, c)" after `after` in `line`.
glm::dvec3 tupleAfter(const std::string& line, const std::string& after) {
  glm::dvec3 v(-1.0);
  const std::size_t at = line.find(after);
  if (at == std::string::npos) return v;
  std::sscanf(line.c_str() + line.find('(', at + after.size()), "(%lf, %lf, %lf)", &v.x, &v.y,
              &v.z);
  return v;
}

TEST(PeerCycles, ReflectanceRgbOfAFlatSpectrumIsItsValue) {
  const glm::dvec3 rgb = cyclesReflectanceRgb(Spectrum::constant(0.5));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c], 0.5, 1e-3) << c;
}

TEST(PeerCycles, CornellBoxScriptHasTheSceneValues) {
  const SceneDescription scene = loadBundled("cornell_box");
  CyclesSettings settings;
  settings.threads = 2;
  settings.bounces = scene.render.maxDepth - 1;
  settings.renders = {{256, 1, "/tmp/out \"x\".exr"}};
  const CyclesTranslation t = translateToCycles(scene, settings);
  const std::string& py = t.script;
  EXPECT_NEAR(valueOf(py, "cam.lens = "), 33.6, 1e-5);  // mm (camsim's floats: 1e-7 relative)
  EXPECT_NEAR(valueOf(py, "cam.sensor_width = "), 24.0, 1e-5);
  EXPECT_EQ(lineStarting(py, "cam.dof.use_dof"), "cam.dof.use_dof = False");
  EXPECT_EQ(lineStarting(py, "r.resolution_x"), "r.resolution_x = 512");
  EXPECT_EQ(lineStarting(py, "r.threads = "), "r.threads = 2");
  EXPECT_EQ(lineStarting(py, "c.max_bounces"),
            "c.max_bounces = c.diffuse_bounces = c.glossy_bounces = 15");
  EXPECT_EQ(lineStarting(py, "c.use_denoising"), "c.use_denoising = False");
  EXPECT_EQ(lineStarting(py, "c.use_adaptive_sampling"), "c.use_adaptive_sampling = False");
  EXPECT_EQ(lineStarting(py, "render(0, "), "render(0, 256, 1, \"/tmp/out \\\"x\\\".exr\")");
  // The camera looks along +z with image right = world −x: Blender's camera matrix has
  // columns right, up, −forward (a proper rotation), at the render origin (the camera).
  EXPECT_NE(py.find("cam_ob.matrix_world = Matrix(((-1, 0, -0)[:] + (0,), (0, 1, -0)[:] + "
                    "(0,), (0, -0, -1)[:] + (0,), (0.0, 0.0, 0.0, 1.0)))"),
            std::string::npos)
      << lineStarting(py, "cam_ob.matrix_world");
  // The walls' RGB round-trips through camsim's uplift.
  const glm::dvec3 red =
      tupleAfter(lineStarting(py, "materials.append(material(\"red\""), "'diffuse', ");
  EXPECT_NEAR(red.x, 0.63, 2e-3);
  EXPECT_NEAR(red.y, 0.065, 2e-3);
  EXPECT_NEAR(red.z, 0.05, 2e-3);
  const glm::dvec3 white =
      tupleAfter(lineStarting(py, "materials.append(material(\"white\""), "'diffuse', ");
  EXPECT_NEAR(white.x, 0.73, 1e-3);
  // The light: D65 of luminance 10,000 cd/m² is Rec.709 white with Y = 10000/683.
  const glm::dvec3 light = tupleAfter(lineStarting(py, "m = emitter(\"light.emission\""), "None, ");
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(light[c] / (10000.0 / kMaxLuminousEfficacy), 1.0, 5e-3);
  // The light is one-sided; the block vertices are in render space (camera at the origin).
  EXPECT_NE(py.find("nt.links.new(geo.outputs['Backfacing'], front.inputs[1])"), std::string::npos);
  const std::string block = lineStarting(py, "shape(\"short_block\", [");
  const glm::dvec3 corner = tupleAfter(block, "[");  // (0.13, 0.165, 0.065) − camera position
  EXPECT_NEAR(corner.x, -0.148, 1e-6);
  EXPECT_NEAR(corner.y, -0.108, 1e-6);
  EXPECT_NEAR(corner.z, 0.865, 1e-6);
}

TEST(PeerCycles, ThinLensKeepsFieldOfViewAndPupil) {
  const SceneDescription scene = loadBundled("dof_chart");
  const std::string py = translateToCycles(scene, {}).script;
  // 85 mm focused at 1.2 m: z_i = 85 · 1200 / 1115 mm; f-stop z_i / (85 / 1.8).
  const double zi = 85.0 * 1200.0 / 1115.0;
  EXPECT_NEAR(valueOf(py, "cam.lens = "), zi, 1e-4);
  EXPECT_NEAR(valueOf(py, "cam.dof.aperture_fstop = "), zi / (85.0 / 1.8), 1e-5);
  EXPECT_NEAR(valueOf(py, "cam.dof.focus_distance = "), 1.2, 1e-6);
  EXPECT_EQ(lineStarting(py, "cam.dof.aperture_blades"), "cam.dof.aperture_blades = 6");
}

TEST(PeerCycles, MotionDuringTheShutterIsRefused) {
  const SceneDescription scene = loadBundled("motion_blur");
  try {
    translateToCycles(scene, {});
    FAIL() << "motion_blur translated";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("moves during the shutter"), std::string::npos)
        << e.what();
  }
}

TEST(PeerCycles, PythonStringEscapes) {
  EXPECT_EQ(pythonString("a\"b\\c\n"), "\"a\\\"b\\\\c\\x0a\"");
}

TEST(PeerCompare, TimeToReachInterpolatesInLogLog) {
  // error = 8 / t: between (2, 4) and (4, 2) the target 3 is reached at t = 8/3.
  const std::vector<double> t = {1, 2, 4, 8}, e = {8, 4, 2, 1};
  bool extrapolated = true;
  EXPECT_NEAR(timeToReach(t, e, 3.0, extrapolated), 8.0 / 3.0, 1e-12);
  EXPECT_FALSE(extrapolated);
  EXPECT_NEAR(timeToReach(t, e, 0.5, extrapolated), 16.0, 1e-12);
  EXPECT_TRUE(extrapolated);
  EXPECT_NEAR(timeToReach(t, e, 16.0, extrapolated), 0.5, 1e-12);
  EXPECT_TRUE(extrapolated);
}

TEST(PeerCompare, EqualErrorSubtractsEachFloor) {
  PeerRun cycles, camsim;
  cycles.floor.rgb.rmse = 0.001;
  cycles.ladder = {{16, 1.0, {{0.017, 0.0}, {0.017, 0.0}}},
                   {256, 16.0, {{0.002, 0.0}, {0.002, 0.0}}}};
  camsim.ladder = {{16, 0.5, {{0.004, 0.0}, {0.004, 0.0}}},
                   {64, 2.0, {{0.001, 0.0}, {0.001, 0.0}}}};
  const EqualError e = equalError(camsim, cycles, false);
  EXPECT_NEAR(e.target, 0.001, 1e-15);
  EXPECT_DOUBLE_EQ(e.cyclesSeconds, 16.0);
  EXPECT_NEAR(e.camsimSeconds, 2.0, 1e-12);
  EXPECT_NEAR(e.ratio(), 0.125, 1e-12);
  EXPECT_FALSE(e.extrapolated);
}

TEST(PeerCompare, RoundsKeepEachRungsFastestAndReportTheirRatios) {
  std::vector<PeerLadderPoint> kept = {{16, 1.0, {}, 1.0}, {256, 16.0, {}, 16.0}};
  keepFastest(kept, {{16, 1.2, {}, 1.2}, {256, 14.5, {}, 14.5}});
  keepFastest(kept, {{16, 0.9, {}, 0.9}, {256, 15.0, {}, 15.0}});
  EXPECT_DOUBLE_EQ(kept[0].seconds, 0.9);
  EXPECT_DOUBLE_EQ(kept[0].slowest, 1.2);
  EXPECT_DOUBLE_EQ(kept[1].seconds, 14.5);
  EXPECT_DOUBLE_EQ(kept[1].slowest, 16.0);
  PeerSceneResult r;
  r.scene = "cornell_box";
  r.cycles.renderer = "cycles";
  r.camsim.renderer = "camsim";
  r.cycles.ladder = kept;
  r.camsim.ladder = {{64, 2.0, {}, 2.5}};
  r.rgb = {0.001, 14.5, 7.0, false};
  r.y = {0.001, 14.5, 6.5, false};
  EXPECT_EQ(formatPeerReport({r}, 2, 2048).find("rounds:"), std::string::npos);  // one round
  r.rounds = 3;
  r.rgbRoundRatios = {0.52, 0.46, 0.49};
  r.yRoundRatios = {0.50, 0.45, 0.47};
  const std::string report = formatPeerReport({r}, 2, 2048);
  EXPECT_NE(report.find("rounds: 3 (each rung's time the fastest of its 3 renders; slowest: "
                        "Cycles 256 spp 16.000 s, camsim 64 spp 2.500 s); each round's own "
                        "ratio: RGB 0.460–0.520, Y 0.450–0.500"),
            std::string::npos)
      << report;
  // A round whose camsim ladder did not reach the target has a NaN ratio: left out, counted.
  r.yRoundRatios = {0.50, std::numeric_limits<double>::quiet_NaN(), 0.47};
  EXPECT_NE(formatPeerReport({r}, 2, 2048).find("Y 0.470–0.500 (1 not reached)"),
            std::string::npos);
  r.yRoundRatios.assign(3, std::numeric_limits<double>::quiet_NaN());
  EXPECT_NE(formatPeerReport({r}, 2, 2048).find("Y not reached"), std::string::npos);
}

TEST(PeerCompare, EqualErrorCsvHoldsTheReportsFigures) {
  // What scripts/peer_plot.py draws: RGB reached by interpolation, Y never reached (NaN).
  PeerSceneResult r;
  r.scene = "cornell_box";
  r.cycles.ladder = {{256, 16.0, {}}};
  r.rgb = {0.001, 16.0, 2.0, false};
  r.y = {0.0005, 16.0, std::numeric_limits<double>::quiet_NaN(), true};
  EXPECT_EQ(formatPeerEqualCsv({r}),
            "scene,channel,target,cycles_spp,cycles_seconds,camsim_seconds,extrapolated,ratio\n"
            "cornell_box,rgb,0.001,256,16,2,0,0.125\n"
            "cornell_box,y,5e-04,256,16,,1,\n");
}

}  // namespace
}  // namespace camsim
