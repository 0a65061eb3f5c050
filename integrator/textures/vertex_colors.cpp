// VertexColors (vertex_colors.h): the vertices' colours uplifted as a one-row image.
#include "integrator/textures/vertex_colors.h"

#include <algorithm>
#include <utility>

#include "integrator/textures/image_texture.h"
#include "sensor/base/check.h"

namespace camsim {

VertexColors::VertexColors(const std::vector<glm::vec3>& rgb, std::vector<std::uint32_t> indices)
    : indices_(std::move(indices)) {
  CAMSIM_CHECK(!rgb.empty() && indices_.size() % 3 == 0);
  for (std::uint32_t i : indices_) CAMSIM_CHECK(i < rgb.size());
  TextureImage row;
  row.width = static_cast<int>(rgb.size());
  row.height = 1;
  row.channels = 3;
  row.values.reserve(3 * rgb.size());
  for (const glm::vec3& c : rgb)
    for (int k = 0; k < 3; ++k) row.values.push_back(std::clamp(c[k], 0.0f, 1.0f));
  coefficients_ = upliftTexels(row).coefficients;
}

}  // namespace camsim
