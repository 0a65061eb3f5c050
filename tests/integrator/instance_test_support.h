// Test helpers for instanced meshes: a small closed mesh with vertex normals and texture
// coordinates, placements that stretch and mirror it, and the same placement baked into the
// vertices (what a copy of the instance holds), by the rules of
// integrator/geometry/mesh_instance.h: positions by the affine map, normals by its inverse
// transpose.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "integrator/geometry/mesh_io.h"
#include "integrator/geometry/triangle_mesh.h"

namespace camsim::test {

// A bumpy sphere of radius ≈ 0.1 m about the origin: nu × nv quads in longitude/latitude
// (2·nu·(nv − 1) triangles), radius r(θ, φ) = 0.1·(1 + 0.15·sin 3φ·sin 2θ), normals of the
// smooth sphere (so shading and geometric normals differ a little), uv = (φ/2π, θ/π).
inline MeshData bumpySphere(int nu = 16, int nv = 10) {
  MeshData m;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const double theta = M_PI * j / nv, phi = 2.0 * M_PI * i / nu;
      const double r = 0.1 * (1.0 + 0.15 * std::sin(3.0 * phi) * std::sin(2.0 * theta));
      const glm::dvec3 d(std::sin(theta) * std::cos(phi), std::cos(theta),
                         std::sin(theta) * std::sin(phi));
      m.positions.emplace_back(r * d);
      m.normals.emplace_back(d);
      m.uvs.emplace_back(static_cast<float>(i) / nu, static_cast<float>(j) / nv);
    }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      // Counter-clockwise seen from outside: the front faces out.
      if (j > 0) m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
      if (j + 1 < nv)
        m.indices.insert(m.indices.end(), {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

// T(translate) · R(axis, degrees) · S(scale): scale may be negative (mirroring).
inline glm::dmat4 placementOf(glm::dvec3 translate, glm::dvec3 axis, double degrees,
                              glm::dvec3 scale) {
  const glm::dmat4 r = glm::mat4_cast(glm::angleAxis(glm::radians(degrees), glm::normalize(axis)));
  glm::dmat4 m = r * glm::scale(glm::dmat4(1.0), scale);
  m[3] = glm::dvec4(translate, 1.0);
  return m;
}

// A random placement within `extent` m of the origin: any rotation, scales in [0.5, 2] per
// axis, mirrored one time in three.
inline glm::dmat4 randomPlacement(std::mt19937& rng, double extent) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), s(0.5, 2.0);
  glm::dvec3 scale(s(rng), s(rng), s(rng));
  if (rng() % 3 == 0) scale.y = -scale.y;
  glm::dvec3 axis(u(rng), u(rng), u(rng));
  if (glm::length(axis) < 1e-3) axis = {0.0, 1.0, 0.0};
  return placementOf(extent * glm::dvec3(u(rng), u(rng), u(rng)), axis, 180.0 * u(rng), scale);
}

// The mesh with the placement baked in (in double, rounded once).
inline MeshData baked(const MeshData& m, const glm::dmat4& placement) {
  MeshData out = m;
  const glm::dmat3 normalMatrix = glm::inverseTranspose(glm::dmat3(placement));
  for (size_t i = 0; i < m.positions.size(); ++i)
    out.positions[i] = glm::vec3(placement * glm::dvec4(glm::dvec3(m.positions[i]), 1.0));
  for (size_t i = 0; i < m.normals.size(); ++i)
    out.normals[i] = glm::vec3(glm::normalize(normalMatrix * glm::dvec3(m.normals[i])));
  return out;
}

// A static TriangleMesh of m as it stands (positions, normals, uvs).
inline std::shared_ptr<TriangleMesh> staticMeshOf(const MeshData& m, bool samplable = false) {
  std::vector<glm::vec3> positions = m.positions;
  std::vector<std::uint32_t> indices = m.indices;
  return std::make_shared<TriangleMesh>(std::move(positions), m.normals, std::move(indices),
                                        TimeSteps{}, m.uvs, samplable);
}

}  // namespace camsim::test
