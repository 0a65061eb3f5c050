// Mesh file entry points shared by the OBJ and PLY readers: reading a whole file into memory
// and choosing the parser by file extension. The parsers live in obj_reader.cpp and
// ply_reader.cpp.
#include "integrator/geometry/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "sensor/base/input_error.h"

namespace camsim {

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
