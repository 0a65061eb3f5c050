#include "sensor/spectra/spectral_data.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "sensor/base/input_error.h"
#include "sensor/base/input_file.h"

namespace camsim {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> splitCommas(std::string_view line) {
  std::vector<std::string_view> out;
  size_t start = 0;
  for (;;) {
    const size_t comma = line.find(',', start);
    out.push_back(
        trim(line.substr(start, comma == std::string_view::npos ? comma : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

bool parseDouble(std::string_view s, double& out) {
  if (s.empty()) return false;
  if (s.front() == '+') s.remove_prefix(1);
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && ptr == s.data() + s.size();
}

}  // namespace

size_t SpectralTable::columnIndex(const std::string& name) const {
  for (size_t i = 0; i < columns.size(); ++i)
    if (columns[i] == name) return i;
  std::string list;
  for (const auto& c : columns) list += (list.empty() ? "" : ", ") + c;
  throw InputError({source, 0, 0}, "", "no column '" + name + "' (columns: " + list + ")");
}

Spectrum SpectralTable::spectrum(size_t column, Extrapolation outside) const {
  return Spectrum::fromSamples(wavelengthsNm, values.at(column), outside);
}

SpectralTable parseSpectralCsv(std::string_view text, const std::string& sourceName) {
  SpectralTable table;
  table.source = sourceName;
  int lineNo = 0;
  int headerLine = 0;
  bool haveHeader = false;
  size_t pos = 0;
  while (pos <= text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = trim(text.substr(pos, end - pos));
    pos = end + 1;
    ++lineNo;
    if (line.empty() || line.front() == '#') continue;
    const auto fields = splitCommas(line);
    const SourceLocation where{sourceName, lineNo, 1};
    if (!haveHeader) {
      if (fields.size() < 2)
        throw InputError(where, "",
                         "header needs a wavelength column and at least one value column");
      // A numeric first field means the header line is missing: without this check the
      // first data row would silently become the header (and be lost).
      double firstField = 0.0;
      if (parseDouble(fields[0], firstField))
        throw InputError(where, "",
                         "missing header line (e.g. 'wavelength_nm,value'): found a data row");
      for (size_t i = 1; i < fields.size(); ++i) {
        if (fields[i].empty()) throw InputError(where, "", "empty column name in header");
        // A name given twice: `column: NAME` read the first silently.
        if (std::find(table.columns.begin(), table.columns.end(), fields[i]) != table.columns.end())
          throw InputError(
              where, "",
              "column name '" + std::string(fields[i]) + "' appears twice in the header");
        table.columns.emplace_back(fields[i]);
      }
      table.values.resize(table.columns.size());
      haveHeader = true;
      headerLine = lineNo;
      continue;
    }
    if (fields.size() != table.columns.size() + 1)
      throw InputError(where, "",
                       "row has " + std::to_string(fields.size()) + " fields, header has " +
                           std::to_string(table.columns.size() + 1));
    double lambda = 0.0;
    if (!parseDouble(fields[0], lambda) || !std::isfinite(lambda) || lambda <= 0.0)
      throw InputError(where, "",
                       "wavelength '" + std::string(fields[0]) + "' is not a positive number (nm)");
    if (!table.wavelengthsNm.empty() && lambda <= table.wavelengthsNm.back())
      throw InputError(where, "", "wavelengths must be strictly increasing");
    table.wavelengthsNm.push_back(lambda);
    for (size_t c = 0; c < table.columns.size(); ++c) {
      double v = 0.0;
      if (!parseDouble(fields[c + 1], v) || !std::isfinite(v))
        throw InputError(where, table.columns[c],
                         "'" + std::string(fields[c + 1]) + "' is not a finite number");
      table.values[c].push_back(v);
    }
  }
  if (!haveHeader) throw InputError({sourceName, 0, 0}, "", "empty spectral table");
  if (table.wavelengthsNm.empty())
    throw InputError({sourceName, headerLine, 0}, "", "spectral table has no rows");
  return table;
}

SpectralTable readSpectralCsv(const std::filesystem::path& path) {
  return parseSpectralCsv(readInputFile(path, "spectral table"), path.string());
}

std::vector<std::string> cieIlluminantNames() {
  return {"A",  "D50", "D65", "ACES_D60", "F1", "F2",  "F3",  "F4",
          "F5", "F6",  "F7",  "F8",       "F9", "F10", "F11", "F12"};
}

Spectrum cieIlluminant(const std::string& name) {
  const std::string rel = "illuminants/illuminant_" + name + ".csv";
  const std::string_view text = embeddedSpectralFile(rel);
  if (text.empty()) {
    std::string list;
    for (const auto& n : cieIlluminantNames()) list += (list.empty() ? "" : ", ") + n;
    throw InputError({}, "", "unknown CIE illuminant '" + name + "' (known: " + list + ")");
  }
  const SpectralTable table = parseSpectralCsv(text, "luts/spectra/" + rel);
  return table.spectrum(0, Extrapolation::kZero);
}

}  // namespace camsim
