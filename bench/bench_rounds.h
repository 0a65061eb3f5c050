// The micro-benchmarks' one option, `--rounds N` (N ≥ 1 timed rounds; atoi's parse: a
// non-number reads 0 and is refused).
#pragma once

#include <cstdio>
#include <cstdlib>
#include <cstring>
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

}  // namespace camsim::bench
