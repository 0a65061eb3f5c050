// The integrator's one factory: builds materials, textures, lights and alpha cut-outs from
// their plain descriptions (scene_description.h). Explicit switches over the small closed
// sets; no registration. Descriptions are validated by the scene loader, so anything invalid here
// is a programming error (CAMSIM_CHECK).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "integrator/geometry/hit_filter.h"
#include "integrator/geometry/triangle_mesh.h"
#include "integrator/lights/light.h"
#include "integrator/materials/material.h"
#include "integrator/scene/scene_description.h"
#include "integrator/textures/texture.h"

namespace camsim {

struct TextureImage;
struct UpliftedTexels;

// Reflectance images uplifted once per (file, encoding) while a Scene builds its materials:
// materials and uv transforms naming the same texture share one set of texels (the uplift
// costs ≈ 2 µs of CPU per distinct colour; see integrator/textures/reflectance_uplift.h). A
// description whose decoded texels differ from the cached ones under the same name (built
// in code) gets an uplift of its own; so does one without a file name.
class TextureCache {
 public:
  // The texels of an image texture's description (its decoded image, or read now).
  std::shared_ptr<const UpliftedTexels> uplifted(const TextureDescription& d);
  size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    std::shared_ptr<const TextureImage> image;  // what was uplifted
    std::shared_ptr<const UpliftedTexels> texels;
  };
  std::map<std::pair<std::string, TextureEncoding>, Entry> entries_;
};

// cache: shared uplifts across calls (nullptr: each image texture uplifts its own).
std::unique_ptr<SpectrumTexture> makeSpectrumTexture(const TextureDescription& d,
                                                     TextureCache* cache = nullptr);
std::unique_ptr<FloatTexture> makeFloatTexture(const TextureDescription& d);
// A tangent-space normal map from an image texture's description (3 channels, raw values)
// and glTF's normalTexture.scale.
std::unique_ptr<NormalMap> makeNormalMap(const TextureDescription& d, float strength);
// The material's BSDF, with its normal map (d.normalMap) if it has one.
std::unique_ptr<Material> makeMaterial(const MaterialDescription& d, TextureCache* cache = nullptr);
std::unique_ptr<Light> makeLight(const LightDescription& d);
// A material's alpha (the cut-out's scalar texture): null when it is opaque everywhere (no
// texture and factor ≥ cutoff), so Embree asks nothing. One per material, shared by its
// cut-outs on every mesh (a Scene that rebuilds its meshes keeps it: no file read again).
std::shared_ptr<const FloatTexture> makeAlphaTexture(const MaterialDescription::AlphaCutout& d);
// The material's alpha cut-out on `mesh` (AlphaCutout, integrator/textures/alpha_cutout.h)
// with its alpha from makeAlphaTexture (not null).
std::unique_ptr<HitFilter> makeAlphaCutout(const MaterialDescription::AlphaCutout& d,
                                           std::shared_ptr<const FloatTexture> alpha,
                                           const TriangleMesh& mesh);

// Files a Scene build has read in this process so far: image textures, normal maps, alpha
// textures and environment maps of a description whose decoded images were released
// (SceneDescription::releaseDecodedImages). A statistic, as pbrt's counters are, by which
// tests check that a capture builds its Scene once and never reads a file again.
std::uint64_t sceneFilesRead();

}  // namespace camsim
