#include "sensor/io/output_set.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <exception>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <utility>

#include "sensor/base/file_status.h"
#include "sensor/base/fnv1a.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace {

constexpr std::string_view kTempMarker = ".camsim-tmp-";

std::filesystem::path temporaryName(const std::string& fileName, long pid) {
  return "." + fileName + std::string(kTempMarker) + std::to_string(pid) + "@" +
         OutputSet::hostTag();
}

}  // namespace

OutputSet::OutputSet(std::filesystem::path directory) : directory_(std::move(directory)) {}

OutputSet::~OutputSet() {
  if (committed_) return;
  std::error_code ignored;
  for (const auto& [temp, final] : files_) std::filesystem::remove(temp, ignored);
}

std::filesystem::path OutputSet::add(const std::string& fileName) {
  // The folder again, should it have gone since it was prepared: another run into it that
  // failed may remove it while it is still empty (NewDirectoryCleanup).
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  const auto temp = directory_ / temporaryName(fileName, static_cast<long>(::getpid()));
  files_.emplace_back(temp, directory_ / fileName);
  return temp;
}

std::vector<std::filesystem::path> OutputSet::prepareDirectory(
    const std::filesystem::path& directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (!isDirectory(directory))
    throw InputError({directory.string(), 0, 0}, "",
                     "cannot create output directory" + (ec ? ": " + ec.message() : ""));
  return cleanStaleTemporaries(directory);
}

NewDirectoryCleanup::NewDirectoryCleanup(const std::filesystem::path& directory)
    : exceptions_(std::uncaught_exceptions()) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path start = fs::absolute(directory, ec).lexically_normal();
  if (start.filename().empty()) start = start.parent_path();  // "out/"
  // The missing part of the path (nothing there at all: a dangling link is not missing),
  // made top-down here; only what this process made is recorded.
  std::vector<fs::path> missing;
  for (fs::path p = start; !ec && !p.empty() && p != p.parent_path(); p = p.parent_path()) {
    // (A missing path sets ec to ENOENT as well; any other failure is not "missing".)
    if (fs::symlink_status(p, ec).type() != fs::file_type::not_found) break;
    ec.clear();
    missing.push_back(p);
  }
  for (auto p = missing.rbegin(); p != missing.rend(); ++p) {
    if (!fs::create_directory(*p, ec) || ec) break;
    made_.insert(made_.begin(), *p);
  }
}

NewDirectoryCleanup::~NewDirectoryCleanup() {
  namespace fs = std::filesystem;
  if (!abandoned_ && std::uncaught_exceptions() <= exceptions_) return;
  std::error_code ec;
  for (const auto& p : made_) {  // deepest first; remove() removes only an empty folder
    if (!fs::is_directory(fs::symlink_status(p, ec)) || !fs::remove(p, ec)) return;
  }
}

std::filesystem::path OutputSet::addText(const std::string& fileName, const std::string& text) {
  const std::filesystem::path temp = add(fileName);
  std::ofstream f(temp, std::ios::binary);
  f << text;
  if (!f.flush()) throw std::runtime_error("cannot write " + (directory_ / fileName).string());
  return temp;
}

std::vector<std::filesystem::path> OutputSet::commit() {
  // A final name taken by a directory is the one failure a rename cannot recover from that
  // the user can cause (an existing file is replaced): checked for all files before any is
  // renamed, so none appears.
  for (const auto& [temp, final] : files_)
    if (isDirectory(final))
      throw InputError({final.string(), 0, 0}, "", "cannot write: a directory has this name");
  std::vector<std::filesystem::path> finals;
  for (const auto& [temp, final] : files_) {
    std::error_code ec;
    std::filesystem::rename(temp, final, ec);
    if (ec)
      throw std::runtime_error("cannot rename " + temp.string() + " to " + final.string() + ": " +
                               ec.message() + " (" + std::to_string(finals.size()) + " of " +
                               std::to_string(files_.size()) + " outputs already in place)");
    finals.push_back(final);
  }
  committed_ = true;
  return finals;
}

const std::string& OutputSet::hostTag() {
  static const std::string tag = [] {
    char name[256] = {};
    std::string host =
        ::gethostname(name, sizeof name - 1) == 0 && name[0] != '\0' ? name : "local";
    const bool plain =
        host.size() <= 32 && std::all_of(host.begin(), host.end(), [](char c) {
          return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' || c == '_';
        });
    if (!plain) host = fnv1aHex(host);  // a file name's bytes stay few and printable
    // Containers may share the host's name (host networking) but not its PIDs: Linux names
    // the PID namespace "pid:[INODE]" (found in review).
    std::error_code ec;
    const std::string ns = std::filesystem::read_symlink("/proc/self/ns/pid", ec).string();
    const size_t open = ns.find('['), close = ns.find(']');
    if (!ec && open != std::string::npos && close > open + 1)
      host += "~" + ns.substr(open + 1, close - open - 1);
    return host;
  }();
  return tag;
}

namespace {

// The PID and the host of a temporary's name: "." + at least one character of the final
// name + marker + digits, then "@" and the host (without: a temporary of an older camsim).
std::optional<std::pair<long, std::string>> parseTemporary(const std::string& fileName) {
  const size_t marker = fileName.rfind(kTempMarker);
  if (fileName.size() < 2 || fileName[0] != '.' || marker == std::string::npos || marker < 2)
    return std::nullopt;
  const char* first = fileName.data() + marker + kTempMarker.size();
  const char* last = fileName.data() + fileName.size();
  long pid = 0;
  const auto [ptr, ec] = std::from_chars(first, last, pid);
  if (first == last || ec != std::errc() || pid <= 0) return std::nullopt;
  if (ptr == last) return std::pair{pid, std::string()};
  if (*ptr != '@' || ptr + 1 == last) return std::nullopt;
  return std::pair{pid, std::string(ptr + 1, last)};
}

}  // namespace

long OutputSet::temporaryOwner(const std::string& fileName) {
  const auto t = parseTemporary(fileName);
  return t ? t->first : -1;
}

std::vector<std::filesystem::path> OutputSet::cleanStaleTemporaries(
    const std::filesystem::path& directory) {
  // Collect first, remove afterwards: no removal while the directory is being read.
  std::vector<std::filesystem::path> stale;
  const long self = static_cast<long>(::getpid());
  std::error_code ec;
  for (std::filesystem::directory_iterator it(directory, ec), end; !ec && it != end;
       it.increment(ec)) {
    const auto owner = parseTemporary(it->path().filename().string());
    if (!owner) continue;
    // Another machine's (or container's) PIDs mean nothing here: its temporaries are left
    // (found by probing: a live run's part on another node, its PID unused here, was removed
    // as stale and that run's rename failed).
    const auto& [pid, host] = *owner;
    if (pid == self || (!host.empty() && host != hostTag())) continue;
    // Never follow or descend: a temporary is a regular file (or a link, removed as such).
    std::error_code typeError;
    const auto type = it->symlink_status(typeError).type();
    if (typeError || (type != std::filesystem::file_type::regular &&
                      type != std::filesystem::file_type::symlink))
      continue;
    // Alive, or alive under another user (EPERM): not stale.
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    stale.push_back(it->path());
  }
  std::vector<std::filesystem::path> removed;
  for (const auto& path : stale) {
    std::error_code removeError;
    if (std::filesystem::remove(path, removeError)) removed.push_back(path);
  }
  return removed;
}

}  // namespace camsim
