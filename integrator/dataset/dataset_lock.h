// DatasetLock: one run of a shard owns that shard's items in a dataset folder while it runs,
// so that a second run of the same shard into the same folder (a job array submitted twice,
// a hand-started `camsim dataset` beside an array) is refused instead of rendering the same
// items and removing the first run's temporary folders (docs/cluster.md).
//
// The lock is DIR/.camsim-lock, an empty file that every run creates and none writes or
// removes (so a sharded and an unsharded folder hold the same files). A run holds Linux
// open-file-description record locks (fcntl F_OFD_SETLK) on bytes of it:
//   byte count − 1        shared (read) by every shard of a run with `count` shards
//   byte 2³⁰ + index      exclusive (write): shard `index`
// and refuses to start while a run with another shard count holds its byte (two counts
// divide the items differently, so they would overlap). The shards of one run lock different
// bytes and go on side by side. The kernel drops the locks when the process ends, however it
// ends: after a SIGKILL, `--resume` starts at once. Where the file system gives no locks
// (ENOLCK: an NFS mount without a lock service), the run goes on unlocked with a warning.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace camsim {

// The lock file's name in the dataset folder.
inline constexpr const char* kDatasetLockFile = ".camsim-lock";

class DatasetLock {
 public:
  // Creates `directory` if missing. InputError naming the lock file and the folder if another
  // process holds shard index/count of it, or runs with another shard count in it, or if the
  // lock file cannot be opened. count ≤ 2³⁰.
  DatasetLock(const std::filesystem::path& directory, std::size_t index, std::size_t count);
  ~DatasetLock();
  DatasetLock(const DatasetLock&) = delete;
  DatasetLock& operator=(const DatasetLock&) = delete;

  // Why the run is not locked (the file system refused record locks), or empty.
  const std::string& warning() const { return warning_; }

 private:
  int fd_ = -1;
  std::string warning_;
};

}  // namespace camsim
