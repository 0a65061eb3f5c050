// DatasetLock (integrator/dataset/dataset_lock.cpp): a shard of a dataset folder is held by
// one run at a time; the shards of one run go on side by side; a run with another shard
// count is refused; the refusal names the lock file, the folder and the shard; a killed
// holder's lock is gone at once (the kernel drops it), and the lock file stays empty.
#include "integrator/dataset/dataset_lock.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <memory>
#include <vector>

#include "sensor/base/input_error.h"
#include "tests/support/temp_dir.h"

namespace camsim {
namespace {

namespace fs = std::filesystem;

// The InputError's text of DatasetLock(dir, index, count), or "" if it was taken.
std::string refusal(const fs::path& dir, std::size_t index, std::size_t count) {
  try {
    DatasetLock lock(dir, index, count);
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

TEST(DatasetLock, ASecondHolderOfTheSameShardIsRefusedNamingTheLockAndTheFolder) {
  test::TempDir tmp;
  const fs::path dir = tmp.path() / "out";
  {
    DatasetLock first(dir, 0, 1);
    EXPECT_TRUE(first.warning().empty()) << first.warning();
    const std::string why = refusal(dir, 0, 1);
    EXPECT_EQ(why.rfind((dir / ".camsim-lock").string() + ": not started: shard 0/1 of " +
                            dir.string() + " is being rendered by another camsim dataset run",
                        0),
              0u)
        << why;
  }
  EXPECT_EQ(refusal(dir, 0, 1), "");  // released with its holder
  EXPECT_EQ(fs::file_size(dir / ".camsim-lock"), 0u);
}

TEST(DatasetLock, TheShardsOfOneRunGoOnSideBySide) {
  test::TempDir tmp;
  std::vector<std::unique_ptr<DatasetLock>> shards;
  for (std::size_t i = 0; i < 4; ++i)
    ASSERT_NO_THROW(shards.push_back(std::make_unique<DatasetLock>(tmp.path(), i, 4))) << i;
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_NE(refusal(tmp.path(), i, 4).find("shard " + std::to_string(i) + "/4"),
              std::string::npos);
  shards[2].reset();
  EXPECT_EQ(refusal(tmp.path(), 2, 4), "");
}

TEST(DatasetLock, ARunWithAnotherShardCountIsRefused) {
  test::TempDir tmp;
  DatasetLock running(tmp.path(), 1, 4);
  // Counts below and above, shards that the running one does and does not hold.
  for (const auto& [index, count] : std::vector<std::pair<std::size_t, std::size_t>>{
           {0, 1}, {1, 2}, {0, 3}, {1, 5}, {7, 8}, {0, std::size_t{1} << 30}}) {
    const std::string why = refusal(tmp.path(), index, count);
    EXPECT_NE(why.find("a camsim dataset run with a shard count of 4 is writing into " +
                       tmp.path().string() +
                       " and holds a lock on this file until it ends; this run's count is " +
                       std::to_string(count) + ":"),
              std::string::npos)
        << index << "/" << count << ": " << why;
  }
}

TEST(DatasetLock, AKilledHoldersLockIsReleasedAtOnce) {
  test::TempDir tmp;
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // holds shard 0/1 until killed; never returns into the test
    try {
      DatasetLock lock(tmp.path(), 0, 1);
      const char c = 'x';
      if (::write(ready[1], &c, 1) != 1) ::_exit(1);
      for (;;) ::pause();
    } catch (...) {
      ::_exit(1);
    }
  }
  ::close(ready[1]);
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  ::close(ready[0]);
  EXPECT_NE(refusal(tmp.path(), 0, 1), "");
  ::kill(child, SIGKILL);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_EQ(refusal(tmp.path(), 0, 1), "");
}

}  // namespace
}  // namespace camsim
