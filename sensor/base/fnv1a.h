// 64-bit FNV-1a of a byte string, as 16 lower-case hex digits: identifies an input's
// text in output metadata and cache keys (not a cryptographic hash).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace camsim {

inline std::string fnv1aHex(std::string_view data) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : data) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace camsim
