// Triangle mesh files: Wavefront OBJ and Stanford PLY. Units are whatever the file holds;
// the scene loader documents them as metres (a `scale` can convert).
//
// OBJ: `v x y z` positions, `vn x y z` normals, `vt u [v]` texture coordinates, `f` faces
//   with 3+ vertices in the forms i, i/t, i//n, i/t/n (1-based, negative = relative);
//   polygons are fan-triangulated. `mtllib FILE…` and `usemtl NAME` are recorded
//   (MeshData::materialLibraries, materialGroups) for the scene loader, which reads the .mtl
//   (integrator/geometry/mtl_reader.h) only if it needs it. Other statements (vp, o, g, s,
//   l, p, comments) are ignored. Texture coordinates are kept if every face corner has one;
//   a position used with different ones is split into one vertex per distinct uv.
// PLY: ascii, binary_little_endian and binary_big_endian 1.0; a `vertex` element with
//   float/double x, y, z (optional nx, ny, nz; optional texture coordinates u, v or s, t
//   or texture_u, texture_v) and a `face` element with a list property `vertex_indices`
//   (or `vertex_index`), polygons fan-triangulated, and/or a `tristrips` element with a list
//   property `vertex_indices` (Stanford-era files such as igea.ply): index −1 (or, in a uint
//   list, 4294967295) restarts the strip; a strip s₀ s₁ s₂ s₃ … gives (s₀ s₁ s₂), (s₂ s₁ s₃),
//   (s₂ s₃ s₄), … (alternating winding, so every triangle keeps the first one's orientation);
//   triangles with a repeated index are dropped (they still count for the alternation). With
//   both elements, triangles follow the elements' order in the file. Other elements and
//   properties are skipped.
// Texture coordinates are as stored (OBJ/OpenGL convention: v = 0 at the image's bottom
// row, see integrator/textures/image_texture.h); not range-checked (textures repeat).
// Errors (unreadable file, malformed line, index out of range, no triangles, NaN/Inf
// coordinates) throw InputError with file and line (for binary PLY: the element index).
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace camsim {

// Whitespace within a line of an OBJ or .mtl file (the line break ends the line).
inline bool isObjSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// Where a file's vertices go: p = scale · p_file + offset, computed in double as each
// vertex is read and only then stored in float, so that a mesh modelled or placed 10⁶ m
// from the origin keeps its precision in render space (the loader passes its `scale` and
// `translate` minus the render origin). A placed position beyond the float range is an
// InputError at its line.
struct MeshPlacement {
  double scale = 1.0;
  glm::dvec3 offset{0.0};

  // The placed position in float; false if it leaves the float range.
  bool place(const glm::dvec3& p, glm::vec3& out) const {
    out = glm::vec3(p * scale + offset);
    return std::isfinite(out.x) && std::isfinite(out.y) && std::isfinite(out.z);
  }
};

// OBJ `usemtl NAME`: the triangles [firstTriangle, firstTriangle + triangleCount) use the
// material NAME as spelt in the file (empty: the triangles before the first usemtl, or a
// bare `usemtl`); line: the usemtl line (0 for the leading triangles).
struct MeshMaterialGroup {
  std::string name;
  std::uint32_t firstTriangle = 0;
  std::uint32_t triangleCount = 0;
  int line = 0;
};

// OBJ `mtllib`: the text after the keyword (one .mtl file, or several separated by spaces,
// relative to the OBJ file's folder) and its line.
struct MeshMaterialLibrary {
  std::string files;
  int line = 0;
};

struct MeshData {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;      // empty, or one per position
  std::vector<glm::vec2> uvs;          // empty, or one per position (texture coordinates)
  std::vector<std::uint32_t> indices;  // 3 per triangle, into positions
  // empty, or one per position: xyz the unit tangent along ∂p/∂u, w = ±1 the bitangent's
  // sign (bitangent = w · normal × tangent), glTF's TANGENT convention (normal maps)
  std::vector<glm::vec4> tangents;
  // empty, or one per position: linear Rec.709 RGB in [0, 1] that multiplies the material's
  // reflectance (glTF COLOR_0; OBJ and PLY meshes leave it empty)
  std::vector<glm::vec3> colors;
  // OBJ only (other sources leave them empty): the usemtl groups in triangle order, covering
  // every triangle, none empty (empty vector: the file has no usemtl), and the mtllib
  // statements. The scene loader maps them to materials (integrator/scene/scene_loader_mtl.cpp).
  std::vector<MeshMaterialGroup> materialGroups;
  std::vector<MeshMaterialLibrary> materialLibraries;
};

MeshData readObj(const std::filesystem::path& path, const MeshPlacement& placement = {});
MeshData parseObj(std::string_view text, const std::string& sourceName,
                  const MeshPlacement& placement = {});
MeshData readPly(const std::filesystem::path& path, const MeshPlacement& placement = {});
MeshData parsePly(std::string_view bytes, const std::string& sourceName,
                  const MeshPlacement& placement = {});
// By extension (.obj / .ply, case-insensitive); InputError otherwise.
MeshData readMeshFile(const std::filesystem::path& path, const MeshPlacement& placement = {});

}  // namespace camsim
