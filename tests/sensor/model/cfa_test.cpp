// Tests for sensor/cfa: the named layouts and the tile lookup.
#include "sensor/model/cfa.h"

#include <string>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"

namespace camsim {
namespace {

std::string at(const CfaLayout& cfa, int x, int y) {
  return cfa.channels[static_cast<size_t>(cfa.channelAt(x, y))];
}

// The 2×2 tile as "(0,0)(1,0)(0,1)(1,1)", i.e. row-major from the top-left photosite.
std::string tileString(const CfaLayout& cfa) {
  return at(cfa, 0, 0) + at(cfa, 1, 0) + at(cfa, 0, 1) + at(cfa, 1, 1);
}

TEST(CfaLayout, BayerLayoutsReadRowMajorFromTheTopLeft) {
  for (const std::string name : {"RGGB", "BGGR", "GRBG", "GBRG"}) {
    const CfaLayout cfa = CfaLayout::fromName(name);
    EXPECT_EQ(cfa.name, name);
    EXPECT_EQ(cfa.width, 2);
    EXPECT_EQ(cfa.height, 2);
    ASSERT_EQ(cfa.tile.size(), 4u);
    EXPECT_EQ(cfa.channels, (std::vector<std::string>{"R", "G", "B"}));
    EXPECT_FALSE(cfa.isMonochrome());
    EXPECT_FALSE(cfa.isStacked());
    EXPECT_EQ(tileString(cfa), name);  // the name spells the tile
  }
}

TEST(CfaLayout, RggbPositions) {
  const CfaLayout cfa = CfaLayout::fromName("RGGB");
  EXPECT_EQ(at(cfa, 0, 0), "R");
  EXPECT_EQ(at(cfa, 1, 0), "G");
  EXPECT_EQ(at(cfa, 0, 1), "G");
  EXPECT_EQ(at(cfa, 1, 1), "B");
}

TEST(CfaLayout, TileRepeatsAcrossTheImage) {
  for (const std::string name : {"RGGB", "BGGR", "GRBG", "GBRG"}) {
    const CfaLayout cfa = CfaLayout::fromName(name);
    int green = 0;
    for (int y = 0; y < 6; ++y) {
      for (int x = 0; x < 8; ++x) {
        EXPECT_EQ(cfa.channelAt(x, y), cfa.channelAt(x % 2, y % 2)) << name << " " << x << "," << y;
        EXPECT_EQ(cfa.channelAt(x + 100, y + 202), cfa.channelAt(x, y));
        green += at(cfa, x, y) == "G";
      }
    }
    EXPECT_EQ(green, 24) << name;  // half of the 48 photosites are green
  }
}

TEST(CfaLayout, MonoAndXyz) {
  const CfaLayout mono = CfaLayout::fromName("mono");
  EXPECT_TRUE(mono.isMonochrome());
  EXPECT_FALSE(mono.isStacked());
  EXPECT_EQ(mono.channels, std::vector<std::string>{"Y"});
  EXPECT_EQ(mono.channelAt(7, 3), 0);
  const CfaLayout xyz = CfaLayout::fromName("xyz");
  EXPECT_TRUE(xyz.isStacked());
  EXPECT_FALSE(xyz.isMonochrome());
  EXPECT_EQ(xyz.width, 1);
  EXPECT_EQ(xyz.height, 1);
  EXPECT_EQ(xyz.channels, (std::vector<std::string>{"X", "Y", "Z"}));
}

TEST(CfaLayout, DefaultIsMono) {
  const CfaLayout cfa;
  EXPECT_TRUE(cfa.isMonochrome());
  EXPECT_EQ(cfa.channelAt(5, 9), 0);
}

TEST(CfaLayout, UnknownNamesAreInputErrors) {
  for (const std::string name : {"RGBG", "rggb", "", "Bayer", "RGGBW", "XYZ"}) {
    try {
      CfaLayout::fromName(name);
      ADD_FAILURE() << "accepted '" << name << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), "cfa");
      EXPECT_NE(e.message().find("RGGB"), std::string::npos) << "should list the known layouts";
    }
  }
}

}  // namespace
}  // namespace camsim
