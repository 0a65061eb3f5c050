// libFuzzer harness: sensor descriptions (YAML/JSON) → camsim::parseSensorSpec
// (sensor/model/sensor_spec.h), then the quantities the sensor model derives from them. Bad
// input must end in InputError; anything else (crash, sanitizer report, non-finite
// derived value) is a finding. Relative CSV paths resolve against camsim's luts/ only.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_check.h"
#include "sensor/base/input_error.h"
#include "sensor/model/sensor_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::filesystem::path luts(CAMSIM_LUTS_DIR);
  try {
    const camsim::SensorSpec s = camsim::parseSensorSpec(text, "fuzz.yaml", luts, luts);
    FUZZ_CHECK(s.pixelPitchM > 0.0 && std::isfinite(s.pixelPitchM));
    FUZZ_CHECK(s.fillFactor > 0.0 && s.fillFactor <= 1.0);
    FUZZ_CHECK(s.qe.size() == s.cfa.channels.size());
    FUZZ_CHECK(s.adcBits >= 1 && s.adcBits <= 16);
    FUZZ_CHECK(s.blackLevelDn < s.whiteLevelDn());
    for (const camsim::Spectrum& q : s.qe)
      FUZZ_CHECK(q.minValue() >= 0.0 && std::isfinite(q.maxValue()));
    const camsim::IsoRange range = camsim::isoRange(s);
    const double highIso = range.max > 0.0 ? range.max : 2.0 * s.baseIso;
    for (const double iso : {s.baseIso, highIso}) {
      try {
        FUZZ_CHECK(std::isfinite(s.systemGain(iso)) && s.systemGain(iso) > 0.0);
        FUZZ_CHECK(std::isfinite(s.saturationElectrons(iso)) && s.saturationElectrons(iso) >= 0.0);
        const camsim::NoiseAtIso n = camsim::noiseAtIso(s, iso);
        FUZZ_CHECK(std::isfinite(n.readVarianceDn2()) && n.readVarianceDn2() >= 0.0);
        FUZZ_CHECK(n.blackOffsetsDn.empty() ||
                   n.blackOffsetsDn.size() == static_cast<std::size_t>(s.cfa.width * s.cfa.height));
      } catch (const camsim::InputError&) {
        // A fit that overflows at this ISO is refused there, not at load.
      }
    }
    FUZZ_CHECK(std::isfinite(s.darkCurrentAtTemperature()) && s.darkCurrentAtTemperature() >= 0.0);
  } catch (const camsim::InputError&) {
  }
  return 0;
}
