// libFuzzer harness: lens prescription files → camsim::parseLensPrescription
// (integrator/camera/lens_file.h), then the LensSystem a camera would build from it:
// paraxial data, focus, real rays and the exit-pupil bounds at a small size. Bad input must
// end in InputError; anything else is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include <glm/geometric.hpp>

#include "fuzz/fuzz_check.h"
#include "integrator/camera/lens_pupil.h"
#include "sensor/base/input_error.h"

namespace {

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace camsim;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const LensPrescription lens = parseLensPrescription(text, "fuzz.dat");
    // The contract of lens_file.h.
    FUZZ_CHECK(!lens.surfaces.empty() && lens.surfaces.size() <= kMaxLensSurfaces);
    FUZZ_CHECK(lens.stopIndex >= 0 && lens.stopIndex < static_cast<int>(lens.surfaces.size()));
    for (std::size_t i = 0; i < lens.surfaces.size(); ++i) {
      const LensSurface& s = lens.surfaces[i];
      FUZZ_CHECK(s.stop == (static_cast<int>(i) == lens.stopIndex));
      FUZZ_CHECK(std::isfinite(s.radius) && std::isfinite(s.thickness) && s.thickness >= 0.0);
      FUZZ_CHECK(std::isfinite(s.apertureDiameter) && s.apertureDiameter > 0.0);
      FUZZ_CHECK(std::isfinite(s.conic));
      for (const double a : s.asphere) FUZZ_CHECK(std::isfinite(a));
      for (const double lambda : {360.0, kLambdaDNm, 830.0})
        FUZZ_CHECK(s.medium.index(lambda) >= 1.0 && s.medium.index(lambda) <= 4.0);
    }
    FUZZ_CHECK(lens.surfaces.back().medium.nd() == 1.0);

    const LensSystem system = LensSystem::forCamera(lens);
    const ParaxialData p = system.paraxial();
    for (const ParaxialField& field : paraxialFields(p))
      FUZZ_CHECK(std::isfinite(field.value) || field.name == std::string_view("object_distance"));
    const double s = system.focusSensorDistance(kInfiniteDistance, 550.0, FocusMethod::kBestRms);
    FUZZ_CHECK(std::isfinite(s));
    if (!(s > 0.0)) return 0;
    for (int i = 0; i < 16; ++i) {
      const glm::dvec3 film(0.001 * i, 0.0, -s);
      const glm::dvec3 rear(system.rearClearRadius() * (i / 8.0 - 1.0), 0.0, 0.0);
      const std::optional<LensRay> out =
          system.traceFromFilm({film, glm::normalize(rear - film)}, 450.0 + 20.0 * i);
      if (out) FUZZ_CHECK(finite(out->origin) && finite(out->direction));
    }
    ExitPupilBounds::Options options;
    options.intervals = 2;
    options.coarseGrid = 8;
    options.columns = 8;
    options.rows = 4;
    const ExitPupilBounds bounds(system, s, 0.01, options);
    for (int k = 0; k < bounds.intervals(); ++k)
      FUZZ_CHECK(bounds.bound(k).empty() || std::isfinite(bounds.area(k)));
  } catch (const InputError&) {
  }
  return 0;
}
