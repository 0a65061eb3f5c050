// The render loop: images are bit-identical for any thread count (each pixel sample has
// its own random stream), different seeds give different noise, and progress and
// cancellation behave.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"
#include "sensor/io/exr_io.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

SceneDescription smallCornell() {
  SceneDescription d =
      loadScene(std::filesystem::path(CAMSIM_SOURCE_DIR) / "scenes/cornell_box.yaml");
  d.camera.resolution = {48, 40};  // several tiles, one partial
  return d;
}

RenderResult renderWith(const Scene& scene, int threads, std::uint64_t seed) {
  static const SpectralResponse response = SpectralResponse::cieXyz();
  RenderOptions options;
  options.spp = 4;
  options.seed = seed;
  options.threads = threads;
  return render(scene, response, options);
}

TEST(Render, OneAndTwoThreadsGiveBitIdenticalExrs) {
  const Scene scene(smallCornell());
  const RenderResult one = renderWith(scene, 1, 42);
  const RenderResult two = renderWith(scene, 2, 42);
  EXPECT_EQ(one.stats.threads, 1);
  EXPECT_EQ(two.stats.threads, 2);
  ASSERT_EQ(one.image.pixels.size(), two.image.pixels.size());
  EXPECT_EQ(0, std::memcmp(one.image.pixels.data(), two.image.pixels.data(),
                           one.image.pixels.size() * sizeof(float)));
  EXPECT_EQ(one.stats.rays.total(), two.stats.rays.total());
  // Through the EXR writer with the same metadata, the files are byte-identical.
  const test::TempDir temp;
  const std::filesystem::path& dir = temp.path();
  const Metadata meta = {{"camsim:seed", "42"}};
  writeExr(dir / "one.exr", one.image, meta, std::nullopt);
  writeExr(dir / "two.exr", two.image, meta, std::nullopt);
  EXPECT_EQ(test::readFile(dir / "one.exr"), test::readFile(dir / "two.exr"));
}

TEST(Render, DifferentSeedsGiveDifferentNoiseSameSeedSameImage) {
  const Scene scene(smallCornell());
  const RenderResult a = renderWith(scene, 2, 1);
  const RenderResult b = renderWith(scene, 2, 2);
  const RenderResult c = renderWith(scene, 2, 1);
  EXPECT_NE(0, std::memcmp(a.image.pixels.data(), b.image.pixels.data(),
                           a.image.pixels.size() * sizeof(float)));
  EXPECT_EQ(0, std::memcmp(a.image.pixels.data(), c.image.pixels.data(),
                           a.image.pixels.size() * sizeof(float)));
}

TEST(Render, ReportsProgressOverEveryTileAndCountsRays) {
  const Scene scene(smallCornell());
  const SpectralResponse response = SpectralResponse::cieXyz();
  RenderOptions options;
  options.spp = 1;
  int lastDone = 0, calls = 0, total = 0;
  options.progress = [&](int done, int t) {
    EXPECT_GT(done, lastDone);
    lastDone = done;
    total = t;
    ++calls;
  };
  const RenderResult r = render(scene, response, options);
  EXPECT_EQ(total, 3 * 3);  // 48×40 px in 16×16 tiles
  EXPECT_EQ(calls, total);
  EXPECT_EQ(lastDone, total);
  EXPECT_EQ(r.stats.samples, 48u * 40u);
  EXPECT_EQ(r.stats.rays.camera, 48u * 40u);
  EXPECT_GT(r.stats.rays.shadow, 0u);
  EXPECT_GT(r.stats.rays.bounce, 0u);
}

TEST(Render, CancelStopsEarly) {
  const Scene scene(smallCornell());
  const SpectralResponse response = SpectralResponse::cieXyz();
  std::atomic<bool> cancel{true};
  RenderOptions options;
  options.cancel = &cancel;
  const RenderResult r = render(scene, response, options);
  EXPECT_TRUE(r.stats.cancelled);
  EXPECT_EQ(r.stats.samples, 0u);
}

// Sets the cancel flag when the thread has cast `after` camera rays: a cancel that arrives
// in the middle of a pixel of a tile, at a known sample.
class CancelAfterCameraRays final : public RayObserver {
 public:
  CancelAfterCameraRays(std::atomic<bool>& cancel, std::uint64_t after)
      : cancel_(cancel), after_(after) {}
  void observe(RayKind kind, const Ray&) override {
    if (kind == RayKind::kCamera && ++cameraRays_ == after_) cancel_ = true;
  }

 private:
  std::atomic<bool>& cancel_;
  std::uint64_t after_, cameraRays_ = 0;
};

// A cancel part way through a tile stops that tile within 64 samples of its pixel, however
// high the spp (checked only between tiles, the tile ran on to its end: 17 s at 10⁵ spp
// for a 48² image), and the result holds only the finished tiles, as the full render has
// them (film and ground truth), and 0 elsewhere, never a tile with some of its samples.
TEST(Render, CancelInsideATileStopsWithin64SamplesAndKeepsOnlyFinishedTiles) {
  SceneDescription d = smallCornell();
  d.render.aovs = {Aov::kDepth};
  const Scene scene(d);
  const SpectralResponse response = SpectralResponse::cieXyz();
  RenderOptions options;
  options.spp = 128;
  options.threads = 1;  // tiles in order: tile 0 finishes, tile 1 is stopped
  const RenderResult full = render(scene, response, options);

  std::atomic<bool> cancel{false};
  // Tile 0's 256 pixels, then 100 pixels of tile 1 and 10 samples of the next.
  const std::uint64_t at = 256u * 128u + 100u * 128u + 10u;
  CancelAfterCameraRays observer(cancel, at);
  options.cancel = &cancel;
  options.rayObserver = &observer;
  int tilesDone = 0;
  options.progress = [&](int done, int) { tilesDone = done; };
  const RenderResult r = render(scene, response, options);
  EXPECT_TRUE(r.stats.cancelled);
  EXPECT_EQ(tilesDone, 1);
  EXPECT_GE(r.stats.samples, at);
  EXPECT_LT(r.stats.samples, at + 64) << "ran on after the cancel";

  const TileRect first = renderTileRect({48, 40}, 0);
  const int y = r.image.channelIndex("Y");
  ASSERT_GE(y, 0);
  ASSERT_EQ(r.aovs.channels, full.aovs.channels);
  ASSERT_FALSE(r.aovs.pixels.empty());
  int finished = 0;
  for (int py = 0; py < 40; ++py)
    for (int px = 0; px < 48; ++px) {
      const bool inFirst = px < first.hi.x && py < first.hi.y;
      finished += inFirst;
      for (int c = 0; c < r.image.channelCount(); ++c)
        ASSERT_EQ(r.image.at(px, py, c), inFirst ? full.image.at(px, py, c) : 0.0f)
            << px << ", " << py << " channel " << c;
      for (int c = 0; c < r.aovs.channelCount(); ++c)
        ASSERT_EQ(r.aovs.at(px, py, c), inFirst ? full.aovs.at(px, py, c) : 0.0f)
            << px << ", " << py << " " << r.aovs.channels[static_cast<std::size_t>(c)];
    }
  EXPECT_EQ(finished, 256);
  EXPECT_GT(full.image.at(20, 5, y), 0.0f);  // tile 1 is lit in the full render
}

}  // namespace
}  // namespace camsim
