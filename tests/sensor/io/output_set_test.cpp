// Tests for sensor/output_set: a render's files appear all at once or not at all.
#include "sensor/io/output_set.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <gtest/gtest.h>

#include "sensor/base/input_error.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text_file.h"

namespace camsim {
namespace {

// A PID that belonged to a process that has exited and been reaped (a killed run's).
pid_t deadPid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

// A fresh directory per test, removed afterwards.
class OutputSetTest : public testing::Test {
 protected:
  size_t entries() const {
    return static_cast<size_t>(std::distance(std::filesystem::directory_iterator(dir_),
                                             std::filesystem::directory_iterator()));
  }
  test::TempDir tmp_;
  std::filesystem::path dir_ = tmp_.path();
};

TEST_F(OutputSetTest, AddGivesAHiddenTemporaryInTheDirectory) {
  OutputSet set(dir_);
  EXPECT_EQ(set.directory(), dir_);
  const std::filesystem::path temp = set.add("image.exr");
  EXPECT_EQ(temp.parent_path(), dir_);
  EXPECT_NE(temp.filename(), "image.exr");
  EXPECT_EQ(temp.filename().string().front(), '.');
  EXPECT_NE(temp.filename().string().find("image.exr"), std::string::npos);
  EXPECT_NE(set.add("image.png"), temp);
}

TEST_F(OutputSetTest, UncommittedFilesAreRemovedAndNeverAppearUnderTheFinalName) {
  {
    OutputSet set(dir_);
    const std::filesystem::path a = set.add("a.exr");
    const std::filesystem::path b = set.add("b.png");
    test::writeFile(a, "aaa");
    test::writeFile(b, "bbb");
    EXPECT_TRUE(std::filesystem::exists(a));
    EXPECT_TRUE(std::filesystem::exists(b));
    EXPECT_FALSE(std::filesystem::exists(dir_ / "a.exr"));
    EXPECT_FALSE(std::filesystem::exists(dir_ / "b.png"));
    EXPECT_EQ(entries(), 2u);
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ / "a.exr"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "b.png"));
  EXPECT_EQ(entries(), 0u);
}

TEST_F(OutputSetTest, CommitRenamesToTheFinalNames) {
  std::filesystem::path a;
  std::filesystem::path b;
  {
    OutputSet set(dir_);
    a = set.add("a.exr");
    b = set.add("b.png");
    test::writeFile(a, "first");
    test::writeFile(b, "second");
    const std::vector<std::filesystem::path> finals = set.commit();
    ASSERT_EQ(finals.size(), 2u);
    EXPECT_EQ(finals[0], dir_ / "a.exr");
    EXPECT_EQ(finals[1], dir_ / "b.png");
  }
  // Still there after the set is destroyed, with their content; temporaries gone.
  EXPECT_EQ(test::readFile(dir_ / "a.exr"), "first");
  EXPECT_EQ(test::readFile(dir_ / "b.png"), "second");
  EXPECT_FALSE(std::filesystem::exists(a));
  EXPECT_FALSE(std::filesystem::exists(b));
  EXPECT_EQ(entries(), 2u);
}

TEST_F(OutputSetTest, AddTextWritesTheTemporaryAndFailsNamingTheFinalFile) {
  {
    OutputSet set(dir_);
    const std::filesystem::path temp = set.addText("table.csv", "a,b\n1,2\n");
    EXPECT_EQ(test::readFile(temp), "a,b\n1,2\n");
    set.commit();
  }
  EXPECT_EQ(test::readFile(dir_ / "table.csv"), "a,b\n1,2\n");
  // A folder that cannot be made (a file holds its parent's name): a missing one is made
  // again when written to (a failed run beside may have removed it, NewDirectoryCleanup).
  test::writeFile(dir_ / "no", "a file");
  OutputSet missing(dir_ / "no" / "such" / "dir");
  try {
    missing.addText("table.csv", "x");
    FAIL() << "no error for a folder that cannot be made";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(dynamic_cast<const InputError*>(&e), nullptr)
        << "an environment error, not bad input";
    EXPECT_NE(std::string(e.what()).find("cannot write " +
                                         (dir_ / "no" / "such" / "dir" / "table.csv").string()),
              std::string::npos)
        << e.what();
  }
}

TEST_F(OutputSetTest, PrepareDirectoryCreatesItOrNamesItInAnInputError) {
  const std::filesystem::path nested = dir_ / "a" / "b";
  EXPECT_TRUE(OutputSet::prepareDirectory(nested).empty());
  EXPECT_TRUE(std::filesystem::is_directory(nested));
  // An existing directory: a killed run's temporary is cleaned and reported.
  const std::filesystem::path stale = nested / (".a.exr.camsim-tmp-" + std::to_string(deadPid()));
  test::writeFile(stale, "killed run");
  EXPECT_EQ(OutputSet::prepareDirectory(nested), std::vector<std::filesystem::path>{stale});
  EXPECT_FALSE(std::filesystem::exists(stale));
  test::writeFile(dir_ / "file", "x");
  try {
    OutputSet::prepareDirectory(dir_ / "file");
    FAIL() << "no error for a regular file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find((dir_ / "file").string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot create output directory"), std::string::npos);
  }
}

// A final name taken by a directory: an input error naming it before any file is renamed,
// so no output appears; the temporaries go with the set.
TEST_F(OutputSetTest, CommitRefusesAFinalNameTakenByADirectoryBeforeRenamingAny) {
  std::filesystem::create_directory(dir_ / "b.png");
  {
    OutputSet set(dir_);
    test::writeFile(set.add("a.exr"), "new");
    test::writeFile(set.add("b.png"), "new");
    try {
      set.commit();
      FAIL() << "no error for a directory in the way";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, (dir_ / "b.png").string());
    }
    EXPECT_FALSE(std::filesystem::exists(dir_ / "a.exr"));
  }
  EXPECT_EQ(entries(), 1u);  // only the directory
}

TEST_F(OutputSetTest, CommitReplacesAnExistingFile) {
  test::writeFile(dir_ / "a.exr", "old");
  {
    OutputSet set(dir_);
    test::writeFile(set.add("a.exr"), "new");
    EXPECT_EQ(test::readFile(dir_ / "a.exr"), "old");  // untouched until commit
    set.commit();
  }
  EXPECT_EQ(test::readFile(dir_ / "a.exr"), "new");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputSetTest, ExceptionBeforeCommitLeavesTheDirectoryEmpty) {
  try {
    OutputSet set(dir_);
    test::writeFile(set.add("a.exr"), "partial");
    test::writeFile(set.add("b.png"), "partial");
    set.add("c.json");  // never written: removing it must not fail
    throw std::runtime_error("render failed");
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "render failed");
  }
  EXPECT_EQ(entries(), 0u);
}

TEST_F(OutputSetTest, UncommittedSetDoesNotTouchExistingFinalFiles) {
  test::writeFile(dir_ / "a.exr", "previous run");
  {
    OutputSet set(dir_);
    test::writeFile(set.add("a.exr"), "failed run");
  }
  EXPECT_EQ(test::readFile(dir_ / "a.exr"), "previous run");
  EXPECT_EQ(entries(), 1u);
}

// The folders a command created for its output go again, if still empty, when it ends by an
// exception; folders that existed, or hold a file, or a command that ends normally, stay.
TEST_F(OutputSetTest, NewDirectoryCleanupRemovesOnlyTheEmptyFoldersItsRunMade) {
  namespace fs = std::filesystem;
  const fs::path nested = dir_ / "a" / "b" / "c";
  const auto failAfterMaking = [](const fs::path& out, bool writeAFile) {
    try {
      const NewDirectoryCleanup cleanup(out);
      OutputSet::prepareDirectory(out);
      if (writeAFile) test::writeFile(out / "kept.txt", "x");
      throw std::runtime_error("refused");
    } catch (const std::runtime_error&) {
    }
  };
  failAfterMaking(nested, false);
  EXPECT_FALSE(fs::exists(dir_ / "a"));  // all three made by the run, all three removed
  EXPECT_TRUE(fs::is_directory(dir_));   // the existing parent stays
  fs::create_directories(dir_ / "a");
  failAfterMaking(nested.string() + "/", false);
  EXPECT_FALSE(fs::exists(dir_ / "a" / "b"));
  EXPECT_TRUE(fs::is_directory(dir_ / "a"));  // existed before the run
  failAfterMaking(nested, true);
  EXPECT_TRUE(fs::exists(nested / "kept.txt"));  // not empty: kept, and its parents
  {
    const NewDirectoryCleanup cleanup(dir_ / "ok");
    OutputSet::prepareDirectory(dir_ / "ok");
  }
  EXPECT_TRUE(fs::is_directory(dir_ / "ok"));  // no exception: kept, even empty
  // A dangling symbolic link is not a missing folder: never removed (the review found
  // `-o dangling` unlinked).
  fs::create_symlink(dir_ / "nowhere" / "x", dir_ / "dangling");
  try {
    const NewDirectoryCleanup cleanup(dir_ / "dangling");
    throw std::runtime_error("refused");
  } catch (const std::runtime_error&) {
  }
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir_ / "dangling")));
  // A folder removed by a failed run is made again by a run that writes into it.
  OutputSet set(dir_ / "gone");
  const fs::path temp = set.add("a.txt");
  EXPECT_TRUE(fs::is_directory(dir_ / "gone"));
  test::writeFile(temp, "a");
  set.commit();
  EXPECT_TRUE(fs::exists(dir_ / "gone" / "a.txt"));
}

TEST(OutputSetNames, TemporaryOwnerReadsThePidOfTemporaryNamesOnly) {
  EXPECT_EQ(OutputSet::temporaryOwner(".a.exr.camsim-tmp-1234"), 1234);
  EXPECT_EQ(OutputSet::temporaryOwner(".cornell_box.partial.exr.camsim-tmp-7"), 7);
  EXPECT_EQ(OutputSet::temporaryOwner("a.exr.camsim-tmp-1234"), -1);  // not hidden
  EXPECT_EQ(OutputSet::temporaryOwner(".camsim-tmp-1234"), -1);       // no final name
  EXPECT_EQ(OutputSet::temporaryOwner(".a.exr.camsim-tmp-"), -1);     // no pid
  EXPECT_EQ(OutputSet::temporaryOwner(".a.exr.camsim-tmp-12x"), -1);
  EXPECT_EQ(OutputSet::temporaryOwner(".a.exr.camsim-tmp--5"), -1);
  EXPECT_EQ(OutputSet::temporaryOwner(".a.exr.camsim-tmp-0"), -1);
  EXPECT_EQ(OutputSet::temporaryOwner(".a.exr.camsim-tmp-99999999999999999999999"), -1);
  EXPECT_EQ(OutputSet::temporaryOwner("a.exr"), -1);
  EXPECT_EQ(OutputSet::temporaryOwner(".a.exr.camsim-tmp-1234@node-7.cluster"), 1234);
  EXPECT_EQ(OutputSet::temporaryOwner(".a.exr.camsim-tmp-1234@"), -1);  // no host
  EXPECT_EQ(OutputSet::temporaryOwner(".a.exr.camsim-tmp-1234#node"), -1);
}

// A temporary names its host: PIDs of another node or container sharing the folder (`--tiles`
// parts, dataset shards) mean nothing here, so its temporaries are left even where no
// process here has its PID (found by probing: a live run's part on another node was removed
// as stale, and its rename failed).
TEST_F(OutputSetTest, CleanStaleTemporariesLeavesThoseOfOtherHosts) {
  const std::string dead = std::to_string(deadPid());
  const std::string other = OutputSet::hostTag() + "x";
  test::writeFile(dir_ / (".a.exr.camsim-tmp-" + dead + "@" + OutputSet::hostTag()), "killed");
  test::writeFile(dir_ / (".b.exr.camsim-tmp-" + dead + "@" + other), "another node's run");
  const std::vector<std::filesystem::path> removed = OutputSet::cleanStaleTemporaries(dir_);
  ASSERT_EQ(removed.size(), 1u);
  EXPECT_EQ(removed[0], dir_ / (".a.exr.camsim-tmp-" + dead + "@" + OutputSet::hostTag()));
  EXPECT_TRUE(std::filesystem::exists(dir_ / (".b.exr.camsim-tmp-" + dead + "@" + other)));
  OutputSet set(dir_);
  EXPECT_EQ(set.add("c.exr").filename().string(),
            ".c.exr.camsim-tmp-" + std::to_string(::getpid()) + "@" + OutputSet::hostTag());
}

TEST_F(OutputSetTest, TemporariesCarryThisProcessPid) {
  OutputSet set(dir_);
  EXPECT_EQ(OutputSet::temporaryOwner(set.add("a.exr").filename().string()),
            static_cast<long>(::getpid()));
}

TEST_F(OutputSetTest, CleanStaleTemporariesRemovesOnlyThoseOfDeadProcesses) {
  const std::string dead = std::to_string(deadPid());
  const std::string parent = std::to_string(::getppid());  // alive while we run
  test::writeFile(dir_ / (".a.exr.camsim-tmp-" + dead), "killed run");
  test::writeFile(dir_ / (".a.png.camsim-tmp-" + dead), "killed run");
  test::writeFile(dir_ / (".a.exr.camsim-tmp-" + parent), "another run, still writing");
  test::writeFile(dir_ / "a.exr", "a finished run");
  test::writeFile(dir_ / ".hidden", "not ours");
  test::writeFile(dir_ / ".a.exr.camsim-tmp-abc", "not a pid");
  std::filesystem::create_directory(dir_ / (".dir.camsim-tmp-" + dead));  // never descended
  OutputSet current(dir_);
  test::writeFile(current.add("b.exr"), "this run, still writing");

  std::vector<std::filesystem::path> removed = OutputSet::cleanStaleTemporaries(dir_);
  std::sort(removed.begin(), removed.end());
  ASSERT_EQ(removed.size(), 2u);
  EXPECT_EQ(removed[0], dir_ / (".a.exr.camsim-tmp-" + dead));
  EXPECT_EQ(removed[1], dir_ / (".a.png.camsim-tmp-" + dead));
  EXPECT_FALSE(std::filesystem::exists(removed[0]));
  EXPECT_FALSE(std::filesystem::exists(removed[1]));
  EXPECT_TRUE(std::filesystem::exists(dir_ / (".a.exr.camsim-tmp-" + parent)));
  EXPECT_EQ(test::readFile(dir_ / "a.exr"), "a finished run");
  EXPECT_TRUE(std::filesystem::exists(dir_ / ".hidden"));
  EXPECT_TRUE(std::filesystem::exists(dir_ / ".a.exr.camsim-tmp-abc"));
  EXPECT_TRUE(std::filesystem::is_directory(dir_ / (".dir.camsim-tmp-" + dead)));
  EXPECT_EQ(entries(), 6u);  // 8 before, minus the 2 stale ones
  current.commit();
  EXPECT_EQ(test::readFile(dir_ / "b.exr"), "this run, still writing");
  EXPECT_TRUE(OutputSet::cleanStaleTemporaries(dir_).empty());  // idempotent
}

TEST_F(OutputSetTest, CleanStaleTemporariesOfAMissingDirectoryDoesNothing) {
  EXPECT_TRUE(OutputSet::cleanStaleTemporaries(dir_ / "missing").empty());
}

}  // namespace
}  // namespace camsim
