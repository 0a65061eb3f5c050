// Triangle mesh files: Wavefront OBJ and Stanford PLY. Units are whatever the file holds;
// the scene loader documents them as metres (a `scale` can convert).
//
// OBJ: `v x y z` positions, `vn x y z` normals, `f` faces with 3+ vertices in the forms
//   i, i/t, i//n, i/t/n (1-based, negative = relative); polygons are fan-triangulated.
//   Other statements (vt, o, g, s, usemtl, mtllib, l, p, comments) are ignored.
// PLY: ascii, binary_little_endian and binary_big_endian 1.0; a `vertex` element with
//   float/double x, y, z (optional nx, ny, nz) and a `face` element with a list property
//   `vertex_indices` (or `vertex_index`); polygons are fan-triangulated; other elements
//   and properties are skipped.
// Errors (unreadable file, malformed line, index out of range, no triangles, NaN/Inf
// coordinates) throw InputError with file and line (for binary PLY: the element index).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

namespace camsim {

struct MeshData {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // empty, or one per position
  std::vector<std::uint32_t> indices;  // 3 per triangle, into positions
};

MeshData readObj(const std::filesystem::path& path);
MeshData parseObj(std::string_view text, const std::string& sourceName);
MeshData readPly(const std::filesystem::path& path);
MeshData parsePly(std::string_view bytes, const std::string& sourceName);
// By extension (.obj / .ply, case-insensitive); InputError otherwise.
MeshData readMeshFile(const std::filesystem::path& path);

}  // namespace camsim
