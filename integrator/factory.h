// The integrator's one factory: builds materials, textures and lights from their plain
// descriptions (scene_description.h). Explicit switches over the small closed sets; no
// registration. Descriptions are validated by the scene loader, so anything invalid here
// is a programming error (CAMSIM_CHECK).
#pragma once

#include <memory>

#include "integrator/light.h"
#include "integrator/material.h"
#include "integrator/scene_description.h"
#include "integrator/texture.h"

namespace camsim {

std::unique_ptr<SpectrumTexture> makeSpectrumTexture(const TextureDescription& d);
std::unique_ptr<FloatTexture> makeFloatTexture(const TextureDescription& d);
std::unique_ptr<Material> makeMaterial(const MaterialDescription& d);
std::unique_ptr<Light> makeLight(const LightDescription& d);

}  // namespace camsim
