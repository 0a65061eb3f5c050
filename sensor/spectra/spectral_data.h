// Spectral data tables: CSV files with one header line, comma-separated, the first
// column wavelength in nm (strictly increasing), the others named value columns.
// The tables camsim needs by default (CIE 1931 observer, CIE illuminants) are embedded
// in the binary from luts/spectra/ at build time; user tables are read from disk.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "sensor/spectra/spectrum.h"

namespace camsim {

struct SpectralTable {
  std::string source;                       // file name, for error messages
  std::vector<std::string> columns;         // value column names (not the wavelength one)
  std::vector<double> wavelengthsNm;        // strictly increasing
  std::vector<std::vector<double>> values;  // values[column][row]

  // Index of a column by name; throws InputError naming the table and the columns.
  size_t columnIndex(const std::string& name) const;
  Spectrum spectrum(size_t column, Extrapolation outside) const;
};

// Parses CSV text. Throws InputError (with the line) on a malformed table: no header, a
// row of the wrong width, a non-number, NaN/Inf, non-increasing wavelengths, < 1 row.
SpectralTable parseSpectralCsv(std::string_view text, const std::string& sourceName);
SpectralTable readSpectralCsv(const std::filesystem::path& path);

// Embedded copies of luts/spectra/ files, by path relative to luts/spectra/
// (e.g. "cie1931_2deg_xyz.csv", "illuminants/illuminant_D65.csv"); empty if absent.
std::string_view embeddedSpectralFile(std::string_view relPath);
// The relative paths of every embedded table (sensor/CMakeLists.txt chooses them).
std::vector<std::string_view> embeddedSpectralFileNames();

// A CIE standard illuminant ("A", "D50", "D65", "F1".."F12", "ACES_D60") as tabulated
// (relative power, 0 outside its table). Throws InputError for an unknown name.
Spectrum cieIlluminant(const std::string& name);
std::vector<std::string> cieIlluminantNames();

}  // namespace camsim
