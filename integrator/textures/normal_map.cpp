// Tangent-space normal maps (see normal_map.h): texel decoding, bilinear lookup and the
// bent shading normal.
#include "integrator/textures/normal_map.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "integrator/textures/image_texture.h"
#include "sensor/base/check.h"

namespace camsim {
namespace {

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

NormalMap::NormalMap(const TextureImage& image, glm::vec2 uvScale, glm::vec2 uvOffset,
                     float strength, float uvRotation)
    : width_(image.width),
      height_(image.height),
      uvTransform_(uvScale, uvOffset, uvRotation),
      strength_(strength) {
  CAMSIM_CHECK(width_ > 0 && height_ > 0 && image.channels == 3);
  CAMSIM_CHECK(std::isfinite(strength_));
  const size_t texels = static_cast<size_t>(width_) * static_cast<size_t>(height_);
  CAMSIM_CHECK(image.values.size() == 3 * texels);
  texels_.resize(texels);
  for (size_t t = 0; t < texels; ++t) {
    glm::vec3 c(image.values[3 * t], image.values[3 * t + 1], image.values[3 * t + 2]);
    if (!finite(c)) c = glm::vec3(0.5f, 0.5f, 1.0f);  // NaN texel: flat
    texels_[t] = c;
  }
}

glm::vec3 NormalMap::tangentSpaceNormal(glm::vec2 uv) const {
  const TexelFootprint f = bilinearFootprint(uvTransform_(uv), width_, height_);
  // Bilinear as a + f (b − a): equal texels (a flat region) give their value exactly, so a
  // flat map bends nothing (weights summing to 1 only to rounding would not).
  const auto lerp = [](const glm::vec3& a, const glm::vec3& b, float t) { return a + t * (b - a); };
  const glm::vec3 c =
      lerp(lerp(texels_[f.texel[0]], texels_[f.texel[1]], f.fraction.x),
           lerp(texels_[f.texel[2]], texels_[f.texel[3]], f.fraction.x), f.fraction.y);
  const glm::vec3 n = (2.0f * c - 1.0f) * glm::vec3(strength_, strength_, 1.0f);
  if (n.x == 0.0f && n.y == 0.0f) return {0.0f, 0.0f, n.z < 0.0f ? -1.0f : 1.0f};
  const float len = std::sqrt(glm::dot(n, n));
  if (!(len > 0.0f) || !std::isfinite(len)) return {0.0f, 0.0f, 1.0f};
  return n / len;
}

glm::vec3 perturbShadingNormal(const glm::vec3& ns, const glm::vec3& n, const glm::vec3& tangent,
                               const glm::vec3& bitangent, const glm::vec3& nt) {
  if (nt.x == 0.0f && nt.y == 0.0f && nt.z > 0.0f) return ns;  // flat: bit for bit
  // Gram–Schmidt: the tangent's part orthogonal to ns; the bitangent only gives the side.
  const glm::vec3 t = tangent - glm::dot(tangent, ns) * ns;
  const float tLen = std::sqrt(glm::dot(t, t));
  if (!(tLen > 1e-20f) || !std::isfinite(tLen)) return ns;
  const glm::vec3 tu = t / tLen;
  glm::vec3 b = glm::cross(ns, tu);
  if (glm::dot(b, bitangent) < 0.0f) b = -b;
  glm::vec3 m = nt.x * tu + nt.y * b + nt.z * ns;
  const float mLen = std::sqrt(glm::dot(m, m));
  if (!(mLen > 0.0f) || !std::isfinite(mLen)) return ns;
  m /= mLen;
  // Below (or too close to) the geometric surface: bend towards n, keep the azimuth.
  const float c = glm::dot(m, n);
  if (!(c >= kMinCosGeometric)) {
    const glm::vec3 side = m - c * n;
    const float sideLen = std::sqrt(glm::dot(side, side));
    if (!(sideLen > 1e-20f) || !std::isfinite(sideLen)) return ns;
    const float sinMin = std::sqrt(1.0f - kMinCosGeometric * kMinCosGeometric);
    m = glm::normalize(side * (sinMin / sideLen) + kMinCosGeometric * n);
  }
  return finite(m) ? m : ns;
}

}  // namespace camsim
