// Every x86-specific builtin and target attribute of camsim, each with a portable path
// (Architecture.IncludeRules rejects them anywhere else).
//
//   CAMSIM_SIMD_X86      1 when CMake's CAMSIM_SIMD is ON (it defines CAMSIM_SIMD=1) and
//                        the compiler targets x86-64; else 0: the portable path
//   CAMSIM_TARGET_AVX2   on a function: compile it for AVX2 (only call it when
//                        cpuHasAvx2()); nothing in the portable path
//   simd::cpuHasAvx2()   whether the running CPU has AVX2; false in the portable path
//   simd::anyLane(mask)  whether any lane of a comparison result (−1 true, 0 false) is true
//
// Float4 / Int4 are GCC/Clang vector extensions, not x86-specific (the compiler lowers
// them to whatever vector unit the target has, or to scalars).
#pragma once

#include <bit>
#include <cstdint>

#if defined(CAMSIM_SIMD) && CAMSIM_SIMD && defined(__x86_64__)
#define CAMSIM_SIMD_X86 1
#define CAMSIM_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define CAMSIM_SIMD_X86 0
#define CAMSIM_TARGET_AVX2
#endif

namespace camsim {

// Four floats / ints in one 16-byte vector (an SSE register on x86-64).
using Float4 = float __attribute__((vector_size(16)));
using Int4 = std::int32_t __attribute__((vector_size(16)));
// Four doubles (two SSE2 registers on x86-64 without AVX; the compiler splits the operations).
using Double4 = double __attribute__((vector_size(32)));
using Long4 = std::int64_t __attribute__((vector_size(32)));  // a Double4 comparison's result
// Eight floats / ints (two SSE registers, or one AVX register in an AVX2 function).
using Float8 = float __attribute__((vector_size(32)));
using Int8 = std::int32_t __attribute__((vector_size(32)));

namespace simd {

inline bool cpuHasAvx2() {
#if CAMSIM_SIMD_X86
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

// x86: one movmskps (extracting the four lanes to OR them takes eight instructions).
inline bool anyLane(Int4 mask) {
#if CAMSIM_SIMD_X86
  return __builtin_ia32_movmskps(std::bit_cast<Float4>(mask)) != 0;
#else
  return (mask[0] | mask[1] | mask[2] | mask[3]) != 0;
#endif
}

inline bool anyLane(Int8 mask) {
  return anyLane(Int4{mask[0], mask[1], mask[2], mask[3]} |
                 Int4{mask[4], mask[5], mask[6], mask[7]});
}

}  // namespace simd
}  // namespace camsim
