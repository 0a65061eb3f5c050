// Every scene shipped in scenes/ (but the dataset manifests) loads and renders (at a reduced resolution and sample
// count) with finite pixels and zero rejected samples: no NaN or Inf reaches the film.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"

namespace camsim {
namespace {

std::vector<std::filesystem::path> exampleScenes() {
  std::vector<std::filesystem::path> out;
  for (const auto& e :
       std::filesystem::directory_iterator(std::filesystem::path(CAMSIM_SOURCE_DIR) / "scenes"))
    if (e.path().extension() == ".yaml" &&
        readSceneFile(e.path()).find("format: camsim-dataset/1") == std::string::npos)
      out.push_back(e.path());  // dataset manifests: tests/integrator/dataset/manifest_test.cpp
  std::sort(out.begin(), out.end());
  return out;
}

TEST(ExampleScenes, EveryShippedSceneRendersWithoutRejectedSamples) {
  const std::vector<std::filesystem::path> scenes = exampleScenes();
  ASSERT_GE(scenes.size(), 9u);
  for (const auto& path : scenes) {
    SceneDescription d = loadScene(path);
    const glm::ivec2 full = d.camera.resolution;
    d.camera.resolution = glm::ivec2(48, std::max(1, 48 * full.y / full.x));
    const Scene scene(d);
    RenderOptions options;
    options.spp = 8;
    options.threads = 2;
    const RenderResult r = render(scene, SpectralResponse::cieXyz(), options);
    EXPECT_EQ(r.stats.rejectedSamples, 0u) << path;
    double sum = 0.0;
    for (float v : r.image.pixels) {
      ASSERT_TRUE(std::isfinite(v)) << path;
      sum += static_cast<double>(v);
    }
    EXPECT_GT(sum, 0.0) << path << " is black";
  }
}

}  // namespace
}  // namespace camsim
