#include "integrator/dataset/dataset_lock.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>

#include "sensor/base/check.h"
#include "sensor/base/input_error.h"

namespace fs = std::filesystem;

namespace camsim {
namespace {

constexpr off_t kShardBase = off_t{1} << 30;  // below 2³¹: NFS lock services of 32-bit offsets

struct flock byteRange(short type, off_t start, off_t length) {
  struct flock f;
  std::memset(&f, 0, sizeof f);
  f.l_type = type;
  f.l_whence = SEEK_SET;
  f.l_start = start;
  f.l_len = length;
  return f;
}

// 0, or the errno of a lock that could not be taken.
int setLock(int fd, short type, off_t at) {
  struct flock f = byteRange(type, at, 1);
  return ::fcntl(fd, F_OFD_SETLK, &f) == 0 ? 0 : errno;
}

// The shard count of another run that holds its count byte in [start, start + length), if any.
std::optional<std::size_t> otherCount(int fd, off_t start, off_t length) {
  if (length <= 0) return std::nullopt;
  struct flock f = byteRange(F_WRLCK, start, length);
  if (::fcntl(fd, F_OFD_GETLK, &f) != 0 || f.l_type == F_UNLCK) return std::nullopt;
  return static_cast<std::size_t>(f.l_start) + 1;
}

bool heldByAnother(int error) {
  return error == EAGAIN || error == EACCES;
}

}  // namespace

DatasetLock::DatasetLock(const fs::path& directory, std::size_t index, std::size_t count) {
  CAMSIM_CHECK(count >= 1 && index < count && count <= (std::size_t{1} << 30));
  const fs::path file = directory / kDatasetLockFile;
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec && !fs::is_directory(directory, ec))
    throw InputError({directory.string(), 0, 0}, "", "cannot create output directory");
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw InputError(
        {file.string(), 0, 0}, "",
        std::string("cannot open the dataset folder's lock file: ") + std::strerror(errno));
  const std::string shard = std::to_string(index) + "/" + std::to_string(count);
  const auto refuse = [&](const std::string& why) {
    ::close(fd_);
    fd_ = -1;
    throw InputError({file.string(), 0, 0}, "", "not started: " + why);
  };
  const auto unlocked = [&](int error) {
    warning_ = file.string() + ": the file system gives no record locks (" + std::strerror(error) +
               "): this run of shard " + shard + " cannot tell whether another run writes into " +
               directory.string() + " at the same time: never start two runs of one shard";
  };
  const off_t countByte = static_cast<off_t>(count) - 1;
  if (const int e = setLock(fd_, F_RDLCK, countByte); e != 0) {
    unlocked(e);  // a read lock conflicts with nothing camsim takes: no lock service
    return;
  }
  // Every other count byte, below and above ours (after our own is held, so that of two runs
  // with different counts starting at once at least one sees the other).
  std::optional<std::size_t> other = otherCount(fd_, 0, countByte);
  if (!other) other = otherCount(fd_, countByte + 1, kShardBase - countByte - 1);
  if (other)
    refuse("a camsim dataset run with a shard count of " + std::to_string(*other) +
           " is writing into " + directory.string() +
           " and holds a lock on this file until it ends; this run's count is " +
           std::to_string(count) +
           ": runs with different shard counts divide the items differently and would render "
           "the same items; give every run into one folder the same shard count");
  if (const int e = setLock(fd_, F_WRLCK, kShardBase + static_cast<off_t>(index)); e != 0) {
    if (!heldByAnother(e)) {
      unlocked(e);
      return;
    }
    refuse("shard " + shard + " of " + directory.string() +
           " is being rendered by another camsim dataset run, which holds a lock on this "
           "file until it ends: two runs of one shard would "
           "render the same items and remove each other's temporary folders; wait for it to "
           "end (or stop it), then run again with --resume");
  }
}

DatasetLock::~DatasetLock() {
  if (fd_ >= 0) ::close(fd_);  // drops the locks
}

}  // namespace camsim
