// Placeholder until image and checkerboard textures land: constants only.
#include "integrator/scene_loader_parts.h"

namespace camsim {

TextureDescription parseTexture(const YamlValue& v, TextureUse use, const SpectrumSearch& search,
                                const std::filesystem::path& /*baseDir*/) {
  if (use == TextureUse::kRoughness) return TextureDescription::constant(v.number(0.0, 1e3));
  TextureDescription t;
  t.value = parseSpectrum(v, SpectrumUse::kReflectance, search);
  return t;
}

}  // namespace camsim
