// How an image texture's stored numbers map to linear values (docs/scene-format.md):
//   kSrgb    decode the sRGB transfer curve (IEC 61966-2-1) to linear (PNG default)
//   kLinear  linear Rec.709 RGB (EXR default)
//   kRaw     the numbers as stored (PNG: code / (2ⁿ − 1)); the default for scalar maps
#pragma once

#include "sensor/base/enum_names.h"

namespace camsim {

enum class TextureEncoding { kSrgb, kLinear, kRaw };
// The scene's texture `encoding` names (sensor/base/enum_names.h).
template <>
struct EnumNames<TextureEncoding> {
  static constexpr EnumName<TextureEncoding> kTable[] = {{TextureEncoding::kSrgb, "srgb"},
                                                         {TextureEncoding::kLinear, "linear"},
                                                         {TextureEncoding::kRaw, "raw"}};
};

}  // namespace camsim
