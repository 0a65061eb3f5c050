// NormalMap: a tangent-space normal map (glTF 2.0 normalTexture, OpenGL convention), and
// the shading normal it gives at a surface point.
//
// | parameter | unit | default  | meaning                                                   |
// |-----------|------|----------|-----------------------------------------------------------|
// | image     | —    | required | RGB texels c ∈ [0, 1]³ read raw (linear, no sRGB curve)   |
// | scale     | —    | (1, 1)   | uv' = uv · scale + offset, as other image textures        |
// | offset    | —    | (0, 0)   |                                                           |
// | rotation  | rad  | 0        | uv' = R(θ)(uv · scale) + offset (uv_transform.h)          |
// | strength  | —    | 1        | glTF normalTexture.scale s: the x and y of n_t scaled     |
//
//   c = bilinear(uv') (image_texture.h addressing, repeat), n_t = normalize((2c − 1) ⊙ (s, s, 1))
//   (a degenerate n_t, e.g. c = (0.5, 0.5, 0.5), reads as (0, 0, 1): no bend)
//   +x of n_t along the tangent T (∂p/∂u), +y along the bitangent B (the side of ∂p/∂v,
//   camsim's v: towards the image's top row), +z along the shading normal N:
//     T' = normalize(T − (T·N) N),  B' = ±N × T' (the sign of B·(N × T')),
//     N' = normalize(n_t.x T' + n_t.y B' + n_t.z N)
//   A flat texel (n_t = (0, 0, 1) exactly, e.g. EXR c = (0.5, 0.5, 1)) returns N bit for
//   bit. An 8-bit PNG cannot store 0.5: its 128 reads 128/255, a tilt of 0.45° with s = 1.
// Guard: N' is kept at least kMinCosGeometric above the geometric surface (n on N's side):
//   if N'·n < kMinCosGeometric, N' is bent towards n to N'·n = kMinCosGeometric (its
//   tangential direction kept); a degenerate T (zero, not finite, along N) leaves N as it is.
#pragma once

#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "integrator/textures/uv_transform.h"

namespace camsim {

struct TextureImage;  // integrator/textures/image_texture.h

class NormalMap {
 public:
  // image: 3 channels (R, G, B) of raw values.
  NormalMap(const TextureImage& image, glm::vec2 uvScale, glm::vec2 uvOffset, float strength,
            float uvRotation = 0.0f);

  // The unit tangent-space normal n_t at uv.
  glm::vec3 tangentSpaceNormal(glm::vec2 uv) const;
  float strength() const { return strength_; }

 private:
  int width_, height_;
  UvTransform uvTransform_;
  float strength_;
  std::vector<glm::vec3> texels_;  // width·height, rows top to bottom
};

// Smallest cosine between a mapped shading normal and the geometric normal (the guard above).
inline constexpr float kMinCosGeometric = 0.01f;

// The shading normal ns (unit) bent by the tangent-space normal nt (unit) in the frame of
// `tangent` and `bitangent` (any length, not orthogonal to ns); n: the geometric normal,
// unit, on ns's side. See the header comment for the equations and the guard.
glm::vec3 perturbShadingNormal(const glm::vec3& ns, const glm::vec3& n, const glm::vec3& tangent,
                               const glm::vec3& bitangent, const glm::vec3& nt);

}  // namespace camsim
