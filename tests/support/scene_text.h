// Helpers for tests that write scene text or call outside tools.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

namespace camsim::test {

// A number as scene text that reads back as the same double ("%.17g").
inline std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Whether `program` is on PATH (e.g. dcraw, exiftool for checks with the real tools).
inline bool onPath(const std::string& program) {
  return std::system(("command -v '" + program + "' >/dev/null 2>&1").c_str()) == 0;
}

// A scene whose line 3 holds the material `m` (its value starts at column 6) on one sphere,
// for the loader's material and texture tests.
inline std::string materialScene(const std::string& material) {
  return "camera: {position: [0, 0, -1], look_at: [0, 0, 0]}\n"  // 1
         "materials:\n"                                          // 2
         "  m: " +
         material +
         "\n"  // 3
         "shapes: [{type: sphere, centre: [0, 0, 0], radius: 1, material: m}]\n";
}

}  // namespace camsim::test
