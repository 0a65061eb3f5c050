// A square matrix's entries in row order, as camsim's JSON files write matrices (glm stores
// columns, m[column][row]):
//
// | function   | result | used by |
// |------------|--------|---------|
// | matrixRows | rows[i][j] = m[j][i], N arrays of N | cameras.json's and transforms.json's 4×4 poses |
// | rowMajor   | the same rows one after another, N² numbers | BOP's cam_R_w2c / cam_R_m2c, the sidecar's colour matrices |
//
// Unitless: the entries as they are.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

namespace camsim {

template <glm::length_t N>
std::vector<std::vector<double>> matrixRows(const glm::mat<N, N, double>& m) {
  std::vector<std::vector<double>> rows(N, std::vector<double>(N));
  for (glm::length_t i = 0; i < N; ++i)
    for (glm::length_t j = 0; j < N; ++j)
      rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = m[j][i];
  return rows;
}

template <glm::length_t N>
std::vector<double> rowMajor(const glm::mat<N, N, double>& m) {
  std::vector<double> flat;
  for (const std::vector<double>& row : matrixRows(m))
    flat.insert(flat.end(), row.begin(), row.end());
  return flat;
}

}  // namespace camsim
