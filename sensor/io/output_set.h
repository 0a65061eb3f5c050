// OutputSet: a render's output files appear all at once or not at all.
// Each file is written under a temporary name in the target directory
// (".<name>.camsim-tmp-<pid>@<host>") and renamed to its final name by commit(); an OutputSet
// destroyed before commit() (an error, an exception) removes its temporaries, so a
// failed run never leaves a file under a final name.
//
// A run killed outright (SIGKILL, power loss) cannot remove its temporaries; the next run
// into the same directory does, with cleanStaleTemporaries(): a temporary of this host (and
// PID namespace) whose writer's PID no longer exists is stale. Other hosts' temporaries
// (another node or container writing `--tiles` parts or dataset shards into a shared folder:
// its PIDs mean nothing here) are left alone; a node that died leaves its own, hidden files
// `.*.camsim-tmp-*@HOST`, for the user to remove.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace camsim {

class OutputSet {
 public:
  explicit OutputSet(std::filesystem::path directory);
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // The temporary path to write `fileName` to; it becomes directory/fileName on commit.
  std::filesystem::path add(const std::string& fileName);
  // add() and write `text` to it; std::runtime_error "cannot write <final path>" on failure.
  std::filesystem::path addText(const std::string& fileName, const std::string& text);
  // Renames every temporary to its final name. Returns the final paths.
  std::vector<std::filesystem::path> commit();

  const std::filesystem::path& directory() const { return directory_; }

  // Removes the files `.<name>.camsim-tmp-<pid>@<host>` (or `-<pid>`, an older camsim's) in
  // `directory` (not in subdirectories) of this host whose process <pid> is gone (kill(pid,
  // 0) fails with ESRCH); a live process's temporaries, including this process's, other
  // hosts' and every other file are left alone. Returns the removed paths. A missing
  // directory has nothing to clean.
  static std::vector<std::filesystem::path> cleanStaleTemporaries(
      const std::filesystem::path& directory);
  // Creates `directory` if missing (InputError naming it if that fails or it is not a
  // directory), then cleanStaleTemporaries(directory): what a command does before writing.
  static std::vector<std::filesystem::path> prepareDirectory(
      const std::filesystem::path& directory);
  // The PID in a temporary's file name, or -1 if `fileName` is not one.
  static long temporaryOwner(const std::string& fileName);
  // This host in temporaries' names: its host name (at most 32 of [A-Za-z0-9._-]), else
  // that name's FNV-1a 64 hash in hex; then "~" and the PID namespace's inode (Linux).
  static const std::string& hostTag();

 private:
  std::filesystem::path directory_;
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> files_;  // temp, final
  bool committed_ = false;
};

// Makes the folders missing for a command's output (`directory` and its missing parents)
// and removes those it made again if the command ends by an exception while they are still
// empty: a run refused after making its folder (a bad view name, a sensor without a curve)
// left the empty folder behind. A folder that existed, another process made, or holds
// anything is kept; a symbolic link is never removed. Another run into the same new folder
// recreates it when it writes (OutputSet::add); `--tiles` parts, written by many processes
// into one folder, do not use it.
class NewDirectoryCleanup {
 public:
  explicit NewDirectoryCleanup(const std::filesystem::path& directory);
  ~NewDirectoryCleanup();
  NewDirectoryCleanup(const NewDirectoryCleanup&) = delete;
  NewDirectoryCleanup& operator=(const NewDirectoryCleanup&) = delete;
  // The command ends without an exception but writes nothing (interrupted): the folders it
  // made are removed too, if empty, when this is destroyed.
  void abandon() { abandoned_ = true; }

 private:
  std::vector<std::filesystem::path> made_;  // deepest first
  int exceptions_;                           // std::uncaught_exceptions() when made
  bool abandoned_ = false;
};

}  // namespace camsim
