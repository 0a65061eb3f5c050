// `camsim bench --peer cycles`: its options and the exit without Blender (no Blender needed;
// the translation and the comparison: tests/integrator/measure/peer_cycles_test.cpp).
#include "tests/support/env_guard.h"
#include "tests/support/temp_dir.h"

#include <gtest/gtest.h>

#include <sstream>

#include "cli/args.h"
#include "cli/bench_command.h"

namespace camsim {
namespace {

TEST(BenchPeerArgs, OptionsAndDefaults) {
  const BenchArgs none = parseBenchArgs({"bench"});
  EXPECT_FALSE(none.peer.has_value());
  EXPECT_FALSE(none.peerOnly);
  const BenchArgs b = parseBenchArgs(
      {"bench", "--peer", "cycles", "--peer-only", "--peer-scenes", "cornell_box,dof_chart",
       "--peer-resolution", "128", "--peer-ref-spp", "1024", "--peer-spp", "64",
       "--peer-camsim-spp", "512", "--peer-max-depth", "9", "--peer-rounds", "3"});
  EXPECT_EQ(b.peer, "cycles");
  EXPECT_TRUE(b.peerOnly);
  EXPECT_EQ(b.peerScenes, (std::vector<std::string>{"cornell_box", "dof_chart"}));
  EXPECT_EQ(b.peerResolution, 128);
  EXPECT_EQ(b.peerRefSpp, 1024);
  EXPECT_EQ(b.peerSpp, 64);
  EXPECT_EQ(b.peerCamsimSpp, 512);
  EXPECT_EQ(b.peerMaxDepth, 9);
  EXPECT_EQ(b.peerRounds, 3);
  EXPECT_FALSE(none.peerRounds.has_value());  // one round
  EXPECT_THROW(parseBenchArgs({"bench", "--peer-rounds", "0"}), UsageError);
  EXPECT_THROW(parseBenchArgs({"bench", "--peer-rounds", "21"}), UsageError);
  EXPECT_EQ(peerSuite(), (std::vector<std::string>{"cornell_box", "dof_chart", "small_light"}));
  EXPECT_THROW(parseBenchArgs({"bench", "--peer", "mitsuba"}), UsageError);
  EXPECT_THROW(parseBenchArgs({"bench", "--peer-resolution", "3"}), UsageError);
  EXPECT_THROW(parseBenchArgs({"bench", "--peer-scenes", "a,,b"}), UsageError);
  EXPECT_NE(benchUsageText().find("--peer-ref-spp"), std::string::npos);
}

TEST(BenchPeerArgs, WithoutBlenderOnPathExitsTwoNamingTheSetup) {
  const test::TempDir empty;
  const test::EnvGuard path("PATH");
  path.set(empty.path().string());
  std::ostringstream out, log;
  EXPECT_EQ(runBench(parseBenchArgs({"bench", "--peer", "cycles", "--peer-only", "-o",
                                     (empty.path() / "out").string()}),
                     out, log),
            2);
  EXPECT_NE(log.str().find("--peer cycles needs Debian's blender"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("scripts/setup.sh --peer"), std::string::npos) << log.str();
  EXPECT_FALSE(std::filesystem::exists(empty.path() / "out"));
}

}  // namespace
}  // namespace camsim
