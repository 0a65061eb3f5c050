// libFuzzer harness: Wavefront .mtl text → camsim::parseMtl (integrator/geometry/mtl_reader.h).
// Bad input must end in InputError; anything else (crash, sanitizer report, another
// exception, a library that breaks the ranges documented in mtl_reader.h) is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>

#include "fuzz/fuzz_check.h"
#include "integrator/geometry/mtl_reader.h"
#include "sensor/base/input_error.h"

namespace {

bool inRange(const glm::dvec3& c) {
  return c.x >= 0.0 && c.y >= 0.0 && c.z >= 0.0 && std::isfinite(c.x + c.y + c.z);
}

void checkLibrary(const camsim::MtlLibrary& lib) {
  std::set<std::string> names;
  for (const camsim::MtlMaterial& m : lib.materials) {
    FUZZ_CHECK(!m.name.empty() && names.insert(m.name).second);
    FUZZ_CHECK(!m.kd || inRange(m.kd->value));
    FUZZ_CHECK(!m.ks || inRange(m.ks->value));
    FUZZ_CHECK(!m.ns || (m.ns->value >= 0.0 && std::isfinite(m.ns->value)));
    FUZZ_CHECK(!m.ni || (m.ni->value >= 1e-3 && m.ni->value <= 1e3));
    FUZZ_CHECK(!m.dissolve || (m.dissolve->value >= 0.0 && m.dissolve->value <= 1.0));
    FUZZ_CHECK(!m.illum || (m.illum->value >= 0 && m.illum->value <= 10));
    FUZZ_CHECK(!m.mapKd || !m.mapKd->file.empty());
    FUZZ_CHECK(!m.mapKd || (std::isfinite(m.mapKd->scale.x + m.mapKd->scale.y + m.mapKd->offset.x +
                                          m.mapKd->offset.y)));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    checkLibrary(camsim::parseMtl(text, "fuzz.mtl"));
  } catch (const camsim::InputError&) {
  }
  return 0;
}
