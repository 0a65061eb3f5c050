// captureScene(): one frame or a sequence behind one call, progress over the whole run;
// CaptureRunWriter: a sequence's frames and camera exports, one frame's files alone.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "integrator/capture/capture_run.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/base/input_error.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

// A 40×24 image of a lit sphere moving along x (3 tiles of 16×16 across, 2 down: every
// frame of a sequence is rendered); `frames` adds a frames block of that many frames,
// `extra` top-level lines.
SceneDescription tinyScene(int frames, const std::string& extra = "") {
  std::string text =
      extra +
      "name: tiny\n"
      "camera: {position: [0, 0, 0], look_at: [0, 0, 1], resolution: [40, 24]}\n"
      "render: {spp: 1, max_depth: 1}\n"
      "materials: {white: {type: diffuse, reflectance: 0.8}}\n"
      "shapes: [{type: sphere, centre: [0, 0, 3], radius: 0.5, material: white,\n"
      "          motion: [{time: 0, translate: [0, 0, 0]}, {time: 1, translate: [0.2, 0, 0]}]}]\n"
      "lights: [{type: point, position: [0, 0, 0], intensity: 50}]\n";
  if (frames > 0)
    text += "frames: {count: " + std::to_string(frames) + ", rate_hz: 10, shutter_angle_deg: 36}\n";
  return loadSceneFromText(text, "tiny.yaml", ".");
}

struct RunLog {
  std::vector<int> frames;                    // k of each onFrame, in order
  std::vector<std::pair<int, int>> progress;  // (done, total) as reported
  SequenceSummary summary;
};

RunLog runScene(int frames) {
  RunLog r;
  CaptureOptions options;
  options.threads = 1;  // one thread: progress is reported in order
  options.progress = [&r](int done, int total) { r.progress.emplace_back(done, total); };
  r.summary = captureScene(tinyScene(frames), options, [&r](CaptureResult&& c, int k) {
    EXPECT_FALSE(c.cancelled);
    r.frames.push_back(k);
  });
  return r;
}

TEST(CaptureScene, OneFrameIsOneCaptureHandedOnAsFrameZero) {
  const RunLog r = runScene(0);
  EXPECT_EQ(r.frames, (std::vector<int>{0}));
  EXPECT_EQ(r.summary.frames, 1);
  EXPECT_EQ(r.summary.rendered, 1);
  EXPECT_FALSE(r.summary.cancelled);
  ASSERT_FALSE(r.progress.empty());
  EXPECT_EQ(r.progress.back(), std::make_pair(6, 6));  // 3 × 2 tiles
}

// Frame k's tile d of T is reported as k·T + d of count·T: one count from 0 to the end,
// never going back (fails if each frame restarted at 0 or the total were per frame).
TEST(CaptureScene, ASequenceReportsProgressOverAllItsFrames) {
  const RunLog r = runScene(3);
  EXPECT_EQ(r.frames, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(r.summary.frames, 3);
  ASSERT_FALSE(r.progress.empty());
  int last = -1;
  for (const auto& [done, total] : r.progress) {
    EXPECT_EQ(total, 18);
    EXPECT_GE(done, last);
    last = done;
  }
  EXPECT_EQ(r.progress.back().first, 18);
}

TEST(CaptureRunWriter, ASequenceWritesItsFramesThenItsCameraExports) {
  const test::TempDir temp;
  const std::filesystem::path& dir = temp.path();
  CaptureOutputOptions out;
  out.directory = dir;
  out.reproducible = true;
  const SceneDescription d = tinyScene(2);
  CaptureRunWriter writer(out, d);
  captureScene(d, {}, [&](CaptureResult&& c, int) { writer.write(c); });
  const std::size_t frameFiles = writer.files().size();
  const std::vector<std::filesystem::path> exports = writer.finish();
  EXPECT_FALSE(exports.empty());
  EXPECT_EQ(writer.files().size(), frameFiles + exports.size());
  EXPECT_TRUE(std::filesystem::exists(dir / "tiny_0000.exr"));
  EXPECT_TRUE(std::filesystem::exists(dir / "tiny_0001.exr"));
  EXPECT_TRUE(std::filesystem::exists(dir / "cameras.json"));
}

TEST(CaptureRunWriter, OneFrameHasNoCameraExports) {
  const test::TempDir temp;
  const std::filesystem::path& dir = temp.path();
  CaptureOutputOptions out;
  out.directory = dir;
  out.reproducible = true;
  const SceneDescription d = tinyScene(0);
  CaptureRunWriter writer(out, d);
  captureScene(d, {}, [&](CaptureResult&& c, int) { writer.write(c); });
  EXPECT_TRUE(writer.finish().empty());
  EXPECT_TRUE(std::filesystem::exists(dir / "tiny.exr"));
  EXPECT_FALSE(std::filesystem::exists(dir / "cameras.json"));
}

// A sequence with `exports: [bop]` cancelled during frame 1: its BOP scene is finished over
// frame 0 — image 0's files and its JSON entries, no image without them — and the camera
// exports are not written (fails if finish() left the BOP JSON out after a cancel, or listed
// the cancelled frame).
TEST(CaptureRunWriter, ACancelledSequenceFinishesItsBopSceneOverTheFramesDone) {
  const test::TempDir temp;
  const std::filesystem::path& dir = temp.path();
  CaptureOutputOptions out;
  out.directory = dir;
  out.reproducible = true;
  SceneDescription d = tinyScene(3, "exports: [bop]\n");
  CaptureRunWriter writer(out, d);
  std::atomic<bool> cancel{false};
  CaptureOptions options;
  options.threads = 1;
  options.cancel = &cancel;
  const SequenceSummary summary = captureScene(std::move(d), options, [&](CaptureResult&& c, int) {
    writer.write(c);
    cancel = true;  // frame 1 is cancelled
  });
  ASSERT_TRUE(summary.cancelled);
  writer.finish();
  const std::filesystem::path scene = dir / "bop" / "train_pbr" / "000000";
  EXPECT_TRUE(std::filesystem::exists(scene / "rgb" / "000000.png"));
  EXPECT_FALSE(std::filesystem::exists(scene / "rgb" / "000001.png"));
  for (const char* name : {"scene_camera.json", "scene_gt.json"}) {
    const std::string text = test::readFile(scene / name);
    ASSERT_FALSE(text.empty()) << name;
    EXPECT_NE(text.find("\"0\""), std::string::npos) << name << ": " << text;
    EXPECT_EQ(text.find("\"1\""), std::string::npos) << name << ": " << text;
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "bop" / "models" / "models_info.json"));
  EXPECT_FALSE(std::filesystem::exists(dir / "cameras.json"));
}

// The run's pose-export models are made by the writer's constructor, before anything renders:
// a scene whose BOP export cannot be written (two spheres of obj_id 1, of different radii) is
// an InputError at its `exports` then, with nothing written (fails if the models were made
// at the first frame instead).
TEST(CaptureRunWriter, RefusesASceneWhosePoseExportsCannotBeWrittenOnConstruction) {
  const test::TempDir temp;
  CaptureOutputOptions out;
  out.directory = temp.path() / "out";
  SceneDescription d = tinyScene(2, "exports: [bop]\n");
  d.shapes[0].classNumber = 1u;
  d.shapes[0].className = "1";
  d.shapes.push_back(d.shapes[0]);
  d.shapes[1].label = "small";
  d.shapes[1].radius = 0.25;
  try {
    const CaptureRunWriter writer(out, d);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "exports") << e.what();
    EXPECT_NE(std::string(e.what()).find("different models"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(out.directory));
}

}  // namespace
}  // namespace camsim
