// Random numbers: PCG32 (O'Neill 2014) seeded through a 64-bit mixing hash, so that any
// tuple (seed, pixel, sample index, …) names its own independent stream. This is what
// makes images independent of thread count and tile order.
#pragma once

#include <cstdint>

namespace camsim {

// SplitMix64 finaliser: a bijective avalanche mix of 64 bits.
inline std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

inline std::uint64_t hashValues(std::uint64_t a, std::uint64_t b) {
  return mix64(a ^ mix64(b));
}
template <typename... Rest>
std::uint64_t hashValues(std::uint64_t a, std::uint64_t b, Rest... rest) {
  return hashValues(hashValues(a, b), static_cast<std::uint64_t>(rest)...);
}

// The high 24 bits of x as a float in [0, 1): exact, never 1 (every generator's numbers).
inline float unitFloat(std::uint32_t x) {
  return static_cast<float>(x >> 8) * 0x1p-24f;
}

class Pcg32 {
 public:
  Pcg32() { seed(0, 0); }
  Pcg32(std::uint64_t seedValue, std::uint64_t stream) { seed(seedValue, stream); }

  void seed(std::uint64_t seedValue, std::uint64_t stream) {
    state_ = 0;
    inc_ = (stream << 1u) | 1u;
    next();
    state_ += seedValue;
    next();
  }

  std::uint32_t next() {
    const std::uint64_t old = state_;
    state_ = old * 0x5851f42d4c957f2dull + inc_;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
  }

  // Uniform in [0, 1): 24 random mantissa bits, never 1.
  float uniform() { return unitFloat(next()); }

 private:
  std::uint64_t state_ = 0, inc_ = 1;
};

}  // namespace camsim
