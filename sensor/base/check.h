// CAMSIM_CHECK: internal invariants. A failed check is a camsim bug, not bad input: it
// prints the condition and location and aborts (exit code 1 path in main via
// std::logic_error would hide the stack; abort keeps the core dump).
#pragma once

#include <cstdio>
#include <cstdlib>

#define CAMSIM_CHECK(cond)                                                                         \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      std::fprintf(stderr, "camsim internal error: %s:%d: check failed: %s\n", __FILE__, __LINE__, \
                   #cond);                                                                         \
      std::abort();                                                                                \
    }                                                                                              \
  } while (false)
