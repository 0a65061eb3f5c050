// Tests for sensor/base/image.h: interleaved layout, channel lookup and extraction.
#include "sensor/base/image.h"

#include <gtest/gtest.h>

namespace camsim {
namespace {

Image numbered() {  // 3×2, channels R, G, B; value = 100·c + pixel index
  Image img(3, 2, {"R", "G", "B"});
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = static_cast<float>(100 * c + y * 3 + x);
  return img;
}

TEST(Image, InterleavedLayoutAndChannelLookup) {
  const Image img = numbered();
  EXPECT_EQ(img.pixels.size(), 18u);
  EXPECT_EQ(img.index(1, 1, 2), 14u);  // (row 1 · 3 + column 1) · 3 channels + 2
  EXPECT_EQ(img.pixels[14], 204.0f);
  EXPECT_EQ(img.channelIndex("G"), 1);
  EXPECT_EQ(img.channelIndex("A"), -1);
}

TEST(Image, ChannelExtractsOnePlaneWithItsOwnOrAGivenName) {
  const Image img = numbered();
  const Image g = img.channel(1);
  EXPECT_EQ(g.width, 3);
  EXPECT_EQ(g.height, 2);
  EXPECT_EQ(g.channels, std::vector<std::string>{"G"});
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) EXPECT_EQ(g.at(x, y, 0), static_cast<float>(100 + y * 3 + x));
  const Image b = img.channel(2, "Y");
  EXPECT_EQ(b.channels, std::vector<std::string>{"Y"});
  EXPECT_EQ(b.at(2, 1, 0), 205.0f);
}

}  // namespace
}  // namespace camsim
