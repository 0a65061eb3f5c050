// The worker-thread count every front end takes (`--threads`, Python's `threads=`): 0 means
// all hardware threads. One range for all: TBB's task arena crashed (SIGSEGV in
// tbb::detail::r1::terminate) past 65536 threads, which Python let through.
#pragma once

#include <string>

#include "sensor/base/input_error.h"

namespace camsim {

inline constexpr int kMaxThreads = 1024;

// The refusal of a count given as `got` (a front end's text of it: Python's repr of an int
// beyond 64 bits).
inline InputError threadCountError(const std::string& where, const std::string& got) {
  return InputError(
      {where, 0, 0}, "threads",
      "expected 0 (all cores) or a count up to " + std::to_string(kMaxThreads) + ", got " + got);
}

// InputError at `where`, key "threads", unless 0 ≤ threads ≤ kMaxThreads.
inline void checkThreadCount(long long threads, const std::string& where) {
  if (threads < 0 || threads > kMaxThreads) throw threadCountError(where, std::to_string(threads));
}

}  // namespace camsim
