// Triangle mesh files: Wavefront OBJ and Stanford PLY. Units are whatever the file holds;
// the scene loader documents them as metres (a `scale` can convert).
//
// OBJ: `v x y z` positions, `vn x y z` normals, `vt u [v]` texture coordinates, `f` faces
//   with 3+ vertices in the forms i, i/t, i//n, i/t/n (1-based, negative = relative);
//   polygons are fan-triangulated. Other statements (vp, o, g, s, usemtl, mtllib, l, p,
//   comments) are ignored. Texture coordinates are kept if every face corner has one; a
//   position used with different ones is split into one vertex per distinct uv.
// PLY: ascii, binary_little_endian and binary_big_endian 1.0; a `vertex` element with
//   float/double x, y, z (optional nx, ny, nz; optional texture coordinates u, v or s, t
//   or texture_u, texture_v) and a `face` element with a list property `vertex_indices`
//   (or `vertex_index`); polygons are fan-triangulated; other elements and properties are
//   skipped.
// Texture coordinates are as stored (OBJ/OpenGL convention: v = 0 at the image's bottom
// row, see integrator/image_texture.h); not range-checked (textures repeat).
// Errors (unreadable file, malformed line, index out of range, no triangles, NaN/Inf
// coordinates) throw InputError with file and line (for binary PLY: the element index).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace camsim {

struct MeshData {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;      // empty, or one per position
  std::vector<glm::vec2> uvs;          // empty, or one per position (texture coordinates)
  std::vector<std::uint32_t> indices;  // 3 per triangle, into positions
};

MeshData readObj(const std::filesystem::path& path);
MeshData parseObj(std::string_view text, const std::string& sourceName);
MeshData readPly(const std::filesystem::path& path);
MeshData parsePly(std::string_view bytes, const std::string& sourceName);
// By extension (.obj / .ply, case-insensitive); InputError otherwise.
MeshData readMeshFile(const std::filesystem::path& path);

}  // namespace camsim
