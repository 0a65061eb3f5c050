// Fixture of the test Architecture.X86CodeOutsideSimdHeaderIsRejected (tests/CMakeLists.txt):
// a source tree whose only file has, on each line below, one kind of x86-specific code that
// cmake/check_includes.cmake must reject outside the SIMD header. Never compiled.
#include <cpuid.h>
#include <immintrin.h>
#include <x86intrin.h>

__attribute__((target("avx2"))) void withTarget();
__attribute__((target_clones("avx2", "default"))) void withClones();
bool supports = __builtin_cpu_supports("avx2");
int mask = __builtin_ia32_movmskps(v);
__m256i lanes;
int first = _mm_cvtsi128_si32(x);
auto wide = _mm256_setzero_si256();
