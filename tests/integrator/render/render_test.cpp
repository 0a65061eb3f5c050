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

}  // namespace
}  // namespace camsim
