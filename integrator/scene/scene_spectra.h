// Spectrum values in scene files (used for reflectance and emission):
//   0.5                                  constant
//   {rgb: [r, g, b]}                     uplifted from linear Rec.709 (smooth, bounded)
//   {csv: file.csv, column: name}        tabulated; column optional for 1-column tables
//   {blackbody: 5000}                    Planck radiance at T (K), W·m⁻²·sr⁻¹·nm⁻¹ (emission)
//   {illuminant: D65}                    CIE standard illuminant, relative (emission)
// Refractive indices (kIndex) take a number or {csv}.
#pragma once

#include <filesystem>
#include <vector>

#include "sensor/base/table_search.h"
#include "sensor/base/yaml_reader.h"
#include "sensor/spectra/spectrum.h"

namespace camsim {

// kIndex: a refractive index η(λ) or extinction coefficient k(λ): a number ≥ 0 or {csv}
// (tables are clamped, not zeroed, beyond their range).
enum class SpectrumUse { kReflectance, kEmission, kIndex };

Spectrum parseSpectrum(const YamlValue& value, SpectrumUse use, const TableSearch& search);

}  // namespace camsim
