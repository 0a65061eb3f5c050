// readInputFile: the bytes of a file named by the user (a scene, sensor description, lens
// prescription, glTF file, spectral table, ptc report), with the checks every such reader
// needs: the path opens, names a regular file or a pipe (`camsim render <(make_scene)`), and
// holds at most kMaxInputFileBytes. A directory or a device (/dev/zero: read forever, growing
// without bound) is an InputError naming the file, as is a larger file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace camsim {

inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{1} << 31;  // 2 GiB

// what: the kind of file, for the messages ("scene file", "lens file", …).
std::string readInputFile(const std::filesystem::path& path, const std::string& what,
                          std::uintmax_t maxBytes = kMaxInputFileBytes);

}  // namespace camsim
