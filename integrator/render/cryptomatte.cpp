#include "integrator/render/cryptomatte.h"

#include <cstdio>
#include <cstring>
#include <set>

#include <murmurhash.h>

#include "sensor/io/json_writer.h"

namespace camsim {

std::uint32_t murmurHash3(std::string_view text) {
  std::uint32_t out[1] = {0};
  lmmh_x86_32(text.data(), static_cast<unsigned>(text.size()), 0, out);
  return out[0];
}

float cryptomatteId(std::string_view name) {
  if (name.empty()) return 0.0f;
  std::uint32_t bits = murmurHash3(name);
  std::uint32_t exponent = (bits >> 23) & 0xffu;
  exponent = exponent < 1u ? 1u : (exponent > 254u ? 254u : exponent);
  bits = (bits & 0x807fffffu) | (exponent << 23);
  float id;
  std::memcpy(&id, &bits, sizeof id);
  return id;
}

std::string cryptomatteHex(float id) {
  std::uint32_t bits;
  std::memcpy(&bits, &id, sizeof bits);
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", bits);
  return hex;
}

std::string cryptomatteKey(std::string_view typeName) {
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", murmurHash3(typeName));
  return std::string(hex, 7);
}

Metadata cryptomatteMetadata(const std::string& typeName, const std::vector<std::string>& names) {
  const std::string prefix = "cryptomatte/" + cryptomatteKey(typeName) + "/";
  JsonObject manifest;
  std::set<std::string> listed;  // shapes may share a name: Cryptomatte then merges them
  for (const std::string& n : names)
    if (!n.empty() && listed.insert(n).second) manifest.set(n, cryptomatteHex(cryptomatteId(n)));
  return {{prefix + "name", typeName},
          {prefix + "hash", "MurmurHash3_32"},
          {prefix + "conversion", "uint32_to_float32"},
          {prefix + "manifest", manifest.str()}};
}

}  // namespace camsim
