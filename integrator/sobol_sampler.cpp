#include "integrator/sobol_sampler.h"

namespace camsim {
namespace {

std::uint32_t reverseBits(std::uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
  return (x >> 16) | (x << 16);
}

// A hash in which each bit depends only on itself and lower bits: applied to the
// bit-reversed value it is a nested uniform (Owen) scramble.
std::uint32_t laineKarras(std::uint32_t x, std::uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

std::uint32_t seed32(std::uint64_t key, std::uint64_t salt) {
  return static_cast<std::uint32_t>(hashValues(key, salt) >> 32);
}

float toUnit(std::uint32_t x) { return static_cast<float>(x >> 8) * 0x1p-24f; }

}  // namespace

std::uint32_t sobolDimension0(std::uint32_t index) { return reverseBits(index); }

std::uint32_t sobolDimension1(std::uint32_t index) {
  std::uint32_t result = 0, v = 1u << 31;
  for (; index != 0; index >>= 1, v ^= v >> 1)
    if (index & 1u) result ^= v;
  return result;
}

std::uint32_t owenScramble(std::uint32_t value, std::uint32_t seed) {
  return reverseBits(laineKarras(reverseBits(value), seed));
}

void SobolSampler::startPixelSample(glm::ivec2 pixel, int sampleIndex) {
  pixelKey_ = hashValues(seed_, static_cast<std::uint32_t>(pixel.x), static_cast<std::uint32_t>(pixel.y));
  index_ = static_cast<std::uint32_t>(sampleIndex);
  dimension_ = 0;
}

float SobolSampler::get1D() {
  const std::uint64_t key = hashValues(pixelKey_, static_cast<std::uint64_t>(dimension_++));
  const std::uint32_t shuffled = owenScramble(index_, seed32(key, 0));
  return toUnit(owenScramble(sobolDimension0(shuffled), seed32(key, 1)));
}

glm::vec2 SobolSampler::get2D() {
  const std::uint64_t key = hashValues(pixelKey_, static_cast<std::uint64_t>(dimension_));
  dimension_ += 2;
  const std::uint32_t shuffled = owenScramble(index_, seed32(key, 0));
  return {toUnit(owenScramble(sobolDimension0(shuffled), seed32(key, 1))),
          toUnit(owenScramble(sobolDimension1(shuffled), seed32(key, 2)))};
}

}  // namespace camsim
