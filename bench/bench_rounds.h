// The micro-benchmarks' one option, `--rounds N` (N ≥ 1 timed rounds; atoi's parse: a
// non-number reads 0 and is refused), and the clock they time a round with.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <optional>

namespace camsim::bench {

// The rounds asked for (fallback without --rounds), or none after printing why to stderr:
// the caller exits 2.
inline std::optional<int> parseRounds(int argc, char** argv, const char* program, int fallback) {
  int rounds = fallback;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--rounds") == 0 && i + 1 < argc) {
      rounds = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: %s [--rounds N]\n", program);
      return std::nullopt;
    }
  }
  if (rounds < 1) {
    std::fprintf(stderr, "%s: --rounds must be at least 1\n", program);
    return std::nullopt;
  }
  return rounds;
}

// The calling thread's CPU time, s: a one-thread measurement that other processes on the
// machine do not inflate.
inline double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace camsim::bench
