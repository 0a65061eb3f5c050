// aovPreviews(): which layers get a picture, and that each mapping shows what it says:
// near is brighter than far, no hit is black, ids get distinct colours and id 0 black,
// opposite motions get different hues and no motion is white.
#include "integrator/capture/aov_previews.h"

#include <gtest/gtest.h>

namespace camsim {
namespace {

TEST(AovPreviews, MappingsShowWhatTheySay) {
  Image a(4, 1, {"coverage.A", "depth.Z", "instance.id", "motion_fw.X", "motion_fw.Y"});
  const float px[4][5] = {
      {1, 1.0f, 1, 3, 0}, {1, 4.0f, 2, -3, 0}, {0, 0, 0, 0, 0}, {1, 2.0f, 1, 0, 0}};
  for (int x = 0; x < 4; ++x)
    for (int c = 0; c < 5; ++c) a.at(x, 0, c) = px[x][c];
  const std::vector<AovPreview> p = aovPreviews(a);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[0].suffix, "depth");
  EXPECT_EQ(p[1].suffix, "instance");
  EXPECT_EQ(p[2].suffix, "motion");
  const auto rgb = [&](int i, int x) {
    const std::size_t o = static_cast<std::size_t>(x) * 3;
    return std::array<int, 3>{p[static_cast<std::size_t>(i)].rgb[o],
                              p[static_cast<std::size_t>(i)].rgb[o + 1],
                              p[static_cast<std::size_t>(i)].rgb[o + 2]};
  };
  EXPECT_GT(rgb(0, 0)[0], rgb(0, 3)[0]);                      // 1 m brighter than 2 m
  EXPECT_GT(rgb(0, 3)[0], rgb(0, 1)[0]);                      // 2 m brighter than 4 m
  EXPECT_EQ(rgb(0, 2), (std::array<int, 3>{0, 0, 0}));        // no hit
  EXPECT_NE(rgb(1, 0), rgb(1, 1));                            // ids 1 and 2 differ
  EXPECT_EQ(rgb(1, 0), rgb(1, 3));                            // the same id, the same colour
  EXPECT_EQ(rgb(1, 2), (std::array<int, 3>{0, 0, 0}));        // id 0
  EXPECT_NE(rgb(2, 0), rgb(2, 1));                            // right and left
  EXPECT_EQ(rgb(2, 3), (std::array<int, 3>{255, 255, 255}));  // still
}

}  // namespace
}  // namespace camsim
