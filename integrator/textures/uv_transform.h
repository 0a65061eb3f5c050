// UvTransform: the affine map an image texture (or normal map) applies to the surface's
// texture coordinates before its lookup (TextureDescription::uvScale, uvOffset, uvRotation):
//
//   uv' = R(θ) · (uv ⊙ scale) + offset,   R(θ) = [cos θ  −sin θ; sin θ  cos θ]
//
// θ in radians, counter-clockwise in camsim's (u, v) (v up the image). glTF's
// KHR_texture_transform is converted to this form by the glTF importer (gltf_materials.cpp).
// θ = 0 computes uv · scale + offset exactly as before rotation existed (the same
// operations, so unrotated textures give the same bits).
#pragma once

#include <cmath>

#include <glm/vec2.hpp>

namespace camsim {

class UvTransform {
 public:
  UvTransform() = default;
  UvTransform(glm::vec2 scale, glm::vec2 offset, float rotation = 0.0f)
      : scale_(scale),
        offset_(offset),
        cos_(std::cos(rotation)),
        sin_(std::sin(rotation)),
        rotated_(rotation != 0.0f) {}

  glm::vec2 operator()(glm::vec2 uv) const {
    if (!rotated_) [[likely]]
      return uv * scale_ + offset_;
    const glm::vec2 s = uv * scale_;
    return glm::vec2(cos_ * s.x - sin_ * s.y, sin_ * s.x + cos_ * s.y) + offset_;
  }

 private:
  glm::vec2 scale_{1.0f}, offset_{0.0f};
  float cos_ = 1.0f, sin_ = 0.0f;
  bool rotated_ = false;
};

}  // namespace camsim
