// libFuzzer harness: PLY bytes (ascii or binary) → camsim::parsePly (integrator/geometry/mesh_io.h).
// Bad input must end in InputError; anything else (crash, sanitizer report, another
// exception, a mesh that breaks the contract in fuzz_check.h) is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz/fuzz_check.h"
#include "integrator/geometry/mesh_io.h"
#include "sensor/base/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    camsim::fuzz::checkMesh(camsim::parsePly(text, "fuzz.ply"));
  } catch (const camsim::InputError&) {
  }
  return 0;
}
