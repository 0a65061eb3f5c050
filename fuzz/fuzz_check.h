// Shared by the libFuzzer harnesses: FUZZ_CHECK aborts (a finding) when a parser returned
// something that breaks its documented contract, so the harnesses catch wrong results as
// well as memory errors, undefined behaviour and exceptions other than InputError.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "integrator/geometry/mesh_io.h"

#define FUZZ_CHECK(cond)                                                                      \
  do {                                                                                        \
    if (!(cond)) {                                                                            \
      std::fprintf(stderr, "fuzz contract violated: %s:%d: %s\n", __FILE__, __LINE__, #cond); \
      std::abort();                                                                           \
    }                                                                                         \
  } while (false)

namespace camsim::fuzz {

// mesh_io.h: indices come in triangles and are in range, normals are absent or one per
// position, coordinates are finite, there is at least one triangle.
inline void checkMesh(const MeshData& mesh) {
  FUZZ_CHECK(!mesh.indices.empty());
  FUZZ_CHECK(mesh.indices.size() % 3 == 0);
  for (const std::uint32_t i : mesh.indices) FUZZ_CHECK(i < mesh.positions.size());
  FUZZ_CHECK(mesh.normals.empty() || mesh.normals.size() == mesh.positions.size());
  for (const auto& p : mesh.positions)
    FUZZ_CHECK(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  // OBJ usemtl groups: none empty, back to back, covering every triangle (or none at all).
  std::size_t next = 0;
  for (const MeshMaterialGroup& g : mesh.materialGroups) {
    FUZZ_CHECK(g.triangleCount > 0 && g.firstTriangle == next);
    next += g.triangleCount;
  }
  FUZZ_CHECK(mesh.materialGroups.empty() || next == mesh.indices.size() / 3);
}

}  // namespace camsim::fuzz
