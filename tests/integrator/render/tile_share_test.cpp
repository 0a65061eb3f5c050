// Tile shares (RenderOptions::tiles, a Share of sensor/base/share.h): the shares of M
// partition the image's tiles — every tile in exactly one share, every pixel in exactly one
// tile — and a share's render is the whole render's pixels, bit for bit, zeros elsewhere
// (film, a second response, and the AOVs with ID mattes), so the shares add up to the whole
// render.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "integrator/render/render.h"
#include "integrator/scene/scene.h"
#include "integrator/scene/scene_loader.h"

namespace camsim {
namespace {

TEST(TilesInShares, SharesPartitionTheTiles) {
  for (const glm::ivec2 res : {glm::ivec2(1, 1), glm::ivec2(16, 16), glm::ivec2(17, 33),
                               glm::ivec2(100, 37), glm::ivec2(320, 240)}) {
    const int tiles = renderTileCount(res);
    EXPECT_EQ(tiles, ((res.x + 15) / 16) * ((res.y + 15) / 16));
    for (const int m : {1, 2, 3, 7, tiles, tiles + 5}) {
      std::vector<int> owners(static_cast<std::size_t>(tiles), 0);
      std::vector<int> pixels(static_cast<std::size_t>(res.x * res.y), 0);
      int listed = 0;
      for (int k = 0; k < m; ++k) {
        const Share share{k, m};
        int owned = 0;
        for (int t = 0; t < tiles; ++t) owned += share.owns(t) ? 1 : 0;
        ASSERT_EQ(share.itemsOf(tiles), owned) << k << " of " << m;
        for (int i = 0; i < share.itemsOf(tiles); ++i) {
          const int t = share.item(i);
          ASSERT_TRUE(t >= 0 && t < tiles && share.owns(t)) << t;
          ++owners[static_cast<std::size_t>(t)];
          ++listed;
          const TileRect r = renderTileRect(res, t);
          ASSERT_TRUE(r.lo.x < r.hi.x && r.lo.y < r.hi.y && r.hi.x <= res.x && r.hi.y <= res.y);
          for (int y = r.lo.y; y < r.hi.y; ++y)
            for (int x = r.lo.x; x < r.hi.x; ++x) ++pixels[static_cast<std::size_t>(y * res.x + x)];
        }
      }
      EXPECT_EQ(listed, tiles);
      for (int t = 0; t < tiles; ++t)
        ASSERT_EQ(owners[static_cast<std::size_t>(t)], 1) << "tile " << t << ", M " << m;
      for (std::size_t p = 0; p < pixels.size(); ++p)
        ASSERT_EQ(pixels[p], 1) << "pixel " << p << ", M " << m << ", " << res.x << "x" << res.y;
    }
  }
}

// 40 × 24 px: 3 × 2 tiles, the last column and row clipped.
const char* kTilesScene =
    "camera: {position: [0, 0, 0], look_at: [0, 0, -1], resolution: [40, 24], f_number: 2,\n"
    "         focal_length_mm: 20, focus_distance_m: 3, aperture: {blades: 6}}\n"
    "render: {spp: 4, max_depth: 2, aovs: [depth, normal, albedo, instance_id, class_id]}\n"
    "materials: {grey: {type: diffuse, reflectance: 0.5}, red: {type: plastic, reflectance: "
    "{rgb: [0.7, 0.1, 0.1]}, roughness: 0.3}}\n"
    "shapes:\n"
    "  - {name: lamp, type: sphere, centre: [0, 3, -3], radius: 0.5, emission: {luminance: "
    "2000}}\n"
    "  - {name: wall, type: rectangle, corner: [-5, -5, -4], edge_u: [10, 0, 0], edge_v: [0, 10, "
    "0], material: grey}\n"
    "  - {name: ball, class: ball, type: sphere, centre: [0.3, 0, -2.5], radius: 0.4, material: "
    "red,\n"
    "     motion: [{time: 0, translate: [0, 0, 0]}, {time: 1, translate: [2, 0, 0]}]}\n";

bool sameBits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(TilesInShares, SharesAddUpToTheWholeRenderBitForBit) {
  const SceneDescription desc = loadSceneFromText(kTilesScene, "tiles.yaml", ".");
  const Scene scene(desc);
  ASSERT_TRUE(scene.modelled().time);
  const SpectralResponse xyz = SpectralResponse::cieXyz();
  const SpectralResponse luminance = SpectralResponse::cieXyz();  // a second response
  const std::vector<const SpectralResponse*> responses = {&xyz, &luminance};
  RenderOptions options;
  options.spp = 4;
  options.seed = 7;
  const RenderResult whole = render(scene, responses, options);
  ASSERT_FALSE(whole.aovs.pixels.empty());
  const glm::ivec2 res = desc.camera.resolution;
  const int tiles = renderTileCount(res);
  ASSERT_EQ(tiles, 6);
  for (const int m : {2, 4, 9}) {  // 9: three shares without a tile
    std::uint64_t samples = 0;
    std::vector<Image> images = {whole.images[0], whole.images[1], whole.aovs};
    for (Image& image : images) std::fill(image.pixels.begin(), image.pixels.end(), -1.0f);
    for (int k = 0; k < m; ++k) {
      options.tiles = {k, m};
      int progressTotal = -1;
      options.progress = [&](int, int total) { progressTotal = total; };
      const RenderResult part = render(scene, responses, options);
      samples += part.stats.samples;
      if (options.tiles.itemsOf(tiles) > 0) {
        EXPECT_EQ(progressTotal, options.tiles.itemsOf(tiles));
      }
      const Image* from[3] = {&part.images[0], &part.images[1], &part.aovs};
      for (int t = 0; t < tiles; ++t) {
        const TileRect r = renderTileRect(res, t);
        for (int i = 0; i < 3; ++i)
          for (int y = r.lo.y; y < r.hi.y; ++y)
            for (int x = r.lo.x; x < r.hi.x; ++x)
              for (int c = 0; c < from[i]->channelCount(); ++c) {
                const float v = from[i]->at(x, y, c);
                if (options.tiles.owns(t)) {
                  images[static_cast<std::size_t>(i)].at(x, y, c) = v;
                } else {
                  ASSERT_EQ(v, 0.0f) << "share " << k << " of " << m << " wrote tile " << t;
                }
              }
      }
    }
    options.tiles = {};
    options.progress = nullptr;
    EXPECT_EQ(samples, whole.stats.samples) << m;
    const Image* expected[3] = {&whole.images[0], &whole.images[1], &whole.aovs};
    for (int i = 0; i < 3; ++i) {
      const Image& got = images[static_cast<std::size_t>(i)];
      ASSERT_EQ(got.channels, expected[i]->channels);
      for (std::size_t p = 0; p < got.pixels.size(); ++p)
        ASSERT_TRUE(sameBits(got.pixels[p], expected[i]->pixels[p]))
            << "image " << i << " value " << p << " (" << got.channels[p % got.channels.size()]
            << "), M " << m << ": " << got.pixels[p] << " vs " << expected[i]->pixels[p];
    }
  }
}

}  // namespace
}  // namespace camsim
