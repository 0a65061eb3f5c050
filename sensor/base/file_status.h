// Non-throwing file tests for paths that come from user input. The one-argument forms of
// std::filesystem::is_regular_file / is_directory throw filesystem_error when the system
// rejects the name itself (a component longer than NAME_MAX: "File name too long"), which
// would end camsim with std::terminate instead of the input error naming the file, line
// and key. These report such a path as "not there", so the caller's own clear error
// ("mesh file '…' not found") follows. Found by fuzzing the sensor description parser.
#pragma once

#include <filesystem>
#include <system_error>

namespace camsim {

inline bool isRegularFile(const std::filesystem::path& p) {
  std::error_code ec;
  return std::filesystem::is_regular_file(p, ec);
}

inline bool isDirectory(const std::filesystem::path& p) {
  std::error_code ec;
  return std::filesystem::is_directory(p, ec);
}

}  // namespace camsim
