// Cryptomatte (the open ID-matte convention: Psyop's specification 1.1.0, read by Nuke,
// Blender and OpenImageIO): a name's id is its MurmurHash3_x86_32 (seed 0) as a float with
// the exponent clamped to [1, 254] (no zero, denormal, inf or NaN), and a type's header key
// the first 7 hex digits of its name's hash. This module is the only one that includes
// libmurmurhash.
//
// Header attributes of a type T with key K (all strings):
//   cryptomatte/K/name = T, …/hash = MurmurHash3_32, …/conversion = uint32_to_float32,
//   …/manifest = {"name": "8 hex digits of the float's bits", …}
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sensor/base/image.h"

namespace camsim {

std::uint32_t murmurHash3(std::string_view text);  // x86_32, seed 0
float cryptomatteId(std::string_view name);        // 0 for "" (nothing hit)
std::string cryptomatteHex(float id);              // the float's bits, 8 lower-case hex digits
std::string cryptomatteKey(std::string_view typeName);
// The header attributes of type `typeName` whose manifest lists `names` ("" left out).
Metadata cryptomatteMetadata(const std::string& typeName, const std::vector<std::string>& names);

}  // namespace camsim
