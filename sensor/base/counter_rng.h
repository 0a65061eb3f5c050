// Counter-based random numbers for the sensor stages: every (seed, frame, x, y, …) tuple
// is hashed to a 64-bit key that names its own stream, so a photosite's noise does not
// depend on thread count, tile order or image size. The stream is SplitMix64 (Steele,
// Lea & Flood 2014): a Weyl counter passed through a bijective 64-bit avalanche mix.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

namespace camsim {

inline constexpr std::uint64_t kWeylIncrement = 0x9e3779b97f4a7c15ull;  // 2^64 / golden ratio

// Bijective avalanche mix of 64 bits (the SplitMix64 output function).
constexpr std::uint64_t avalanche64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Key of an ordered tuple: each value is folded in through the mix, so (a, b) and (b, a)
// differ and, for a fixed prefix, distinct last values give distinct keys.
constexpr std::uint64_t streamKey(std::uint64_t a) {
  return avalanche64(a + kWeylIncrement);
}
template <typename... Rest>
constexpr std::uint64_t streamKey(std::uint64_t a, std::uint64_t b, Rest... rest) {
  return streamKey(avalanche64(streamKey(a) ^ (b + kWeylIncrement)),
                   static_cast<std::uint64_t>(rest)...);
}

class CounterRng {
 public:
  explicit CounterRng(std::uint64_t key) : state_(avalanche64(key)) {}

  std::uint64_t next() {
    state_ += kWeylIncrement;
    return avalanche64(state_);
  }
  // Uniform in the open interval (0, 1): 53 random bits, never 0 or 1 (logs stay finite).
  double uniformOpen() { return (static_cast<double>(next() >> 11) + 0.5) * 0x1p-53; }
  // Standard normal (Box–Muller; the second value of the pair is discarded so that every
  // draw consumes exactly two uniforms).
  double normal() {
    const double r = std::sqrt(-2.0 * std::log(uniformOpen()));
    return r * std::cos(2.0 * std::numbers::pi * uniformOpen());
  }

 private:
  std::uint64_t state_;
};

}  // namespace camsim
