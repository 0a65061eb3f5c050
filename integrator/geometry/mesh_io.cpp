// Mesh file entry points shared by the OBJ and PLY readers: reading a whole file into memory
// and choosing the parser by file extension. The parsers live in obj_reader.cpp and
// ply_reader.cpp.
#include "integrator/geometry/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <memory>
#include <string>
#include <system_error>

#include "sensor/base/file_status.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace mesh_io_detail {

// Declared (without a shared header) in obj_reader.cpp and ply_reader.cpp.
std::string readWholeFile(const std::filesystem::path& path);

std::string readWholeFile(const std::filesystem::path& path) {
  const std::string name = path.string();
  if (!isRegularFile(path))
    throw InputError({name, 0, 0}, "", "mesh file does not exist or is not a regular file");
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError({name, 0, 0}, "", "cannot read mesh file size: " + ec.message());
  if (size > std::string().max_size()) throw InputError({name, 0, 0}, "", "mesh file is too large");

  const auto closer = [](std::FILE* f) { std::fclose(f); };
  const std::unique_ptr<std::FILE, decltype(closer)> file(std::fopen(name.c_str(), "rb"), closer);
  if (!file) throw InputError({name, 0, 0}, "", "cannot open mesh file");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  const std::size_t got = std::fread(bytes.data(), 1, bytes.size(), file.get());
  if (got != bytes.size() || std::ferror(file.get()))
    throw InputError({name, 0, 0}, "", "error reading mesh file (changed while reading?)");
  return bytes;
}

}  // namespace mesh_io_detail

MeshData readMeshFile(const std::filesystem::path& path, const MeshPlacement& placement) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".obj") return readObj(path, placement);
  if (ext == ".ply") return readPly(path, placement);
  throw InputError(
      {path.string(), 0, 0}, "",
      "unknown mesh file extension '" + path.extension().string() + "' (expected .obj or .ply)");
}

}  // namespace camsim
