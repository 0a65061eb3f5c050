// libFuzzer harness: spectral CSV tables → camsim::parseSpectralCsv
// (sensor/spectra/spectral_data.h), then every column resampled to a Spectrum as the scene loader
// does. Bad input must end in InputError; anything else is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz/fuzz_check.h"
#include "sensor/base/input_error.h"
#include "sensor/spectra/spectral_data.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const camsim::SpectralTable table = camsim::parseSpectralCsv(text, "fuzz.csv");
    // The contract of spectral_data.h.
    FUZZ_CHECK(!table.columns.empty());
    FUZZ_CHECK(!table.wavelengthsNm.empty());
    FUZZ_CHECK(table.values.size() == table.columns.size());
    for (std::size_t i = 0; i < table.wavelengthsNm.size(); ++i) {
      FUZZ_CHECK(std::isfinite(table.wavelengthsNm[i]) && table.wavelengthsNm[i] > 0.0);
      if (i > 0) FUZZ_CHECK(table.wavelengthsNm[i] > table.wavelengthsNm[i - 1]);
    }
    for (std::size_t c = 0; c < table.columns.size(); ++c) {
      FUZZ_CHECK(table.values[c].size() == table.wavelengthsNm.size());
      for (const double v : table.values[c]) FUZZ_CHECK(std::isfinite(v));
      FUZZ_CHECK(table.columnIndex(table.columns[c]) <= c);  // duplicates: the first wins
      table.spectrum(c, camsim::Extrapolation::kClamp);
      table.spectrum(c, camsim::Extrapolation::kZero);
    }
  } catch (const camsim::InputError&) {
  }
  return 0;
}
