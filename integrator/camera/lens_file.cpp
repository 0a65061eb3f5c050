#include "integrator/camera/lens_file.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <map>

#include "sensor/base/format.h"
#include "sensor/base/input_error.h"
#include "sensor/base/input_file.h"
#include "sensor/base/luts_directory.h"
#include "sensor/spectra/spectral_data.h"

namespace camsim {
namespace {

constexpr double kMm = 1e-3;  // m per mm
constexpr const char* kColumns[4] = {"radius", "thickness", "N", "aperture"};
constexpr const char* kAsphereKeys[kAsphereTerms] = {"a4", "a6", "a8", "a10", "a12", "a14", "a16"};

struct Token {
  std::string_view text;
  int column = 0;  // 1-based
};

bool parseLensNumber(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && ptr == s.data() + s.size();
}

std::string shortText(std::string_view s) {
  return std::string(s.substr(0, 40)) + (s.size() > 40 ? "…" : "");
}

// The parse of one file: where it is, the glass tables read so far.
class Parser {
 public:
  Parser(const std::string& source, const TableSearch& search) : source_(source), search_(search) {}

  [[noreturn]] void fail(int line, int column, const std::string& key, const std::string& msg) {
    throw InputError({source_, line, column}, key, msg);
  }

  double number(int line, const Token& t, const std::string& key) {
    double v = 0.0;
    if (!parseLensNumber(t.text, v))
      fail(line, t.column, key, "'" + shortText(t.text) + "' is no number");
    if (!std::isfinite(v)) fail(line, t.column, key, "must be finite, not " + shortText(t.text));
    return v;
  }

  LensSurface surface(int line, const std::vector<Token>& tokens);
  Glass glass(int line, const Token& t, std::string_view name, double nd);

 private:
  std::string source_;
  const TableSearch& search_;
  std::map<std::string, SpectralTable, std::less<>> tables_;
};

Glass Parser::glass(int line, const Token& t, std::string_view name, double nd) {
  bool valid = !name.empty() && name.front() != '.' && name.size() <= 64;
  for (const char ch : name)
    valid = valid && (std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' ||
                      ch == '.' || ch == '+');
  if (!valid)
    fail(line, t.column, "glass",
         "'" + shortText(name) + "' is no glass name (letters, digits, _ - . +)");
  auto it = tables_.find(name);
  if (it == tables_.end()) {
    const std::string file = "glasses/" + std::string(name) + ".csv";
    const std::optional<std::filesystem::path> path = search_.locate(file);
    if (!path) {
      std::string where;
      for (const auto& d : search_.directories) where += (where.empty() ? "" : ", ") + d.string();
      fail(line, t.column, "glass",
           "unknown glass '" + std::string(name) + "' (no " + file + " in " + where + ")");
    }
    try {
      SpectralTable table = readSpectralCsv(*path);
      const size_t column = table.columnIndex("eta");
      table.values = {table.values[column]};
      if (table.wavelengthsNm.size() < 2) throw InputError({}, "", "fewer than two rows");
      for (const double eta : table.values[0])
        if (!(eta >= 1.0 && eta <= 4.0)) throw InputError({}, "", "an eta outside [1, 4]");
      it = tables_.emplace(std::string(name), std::move(table)).first;
    } catch (const InputError& e) {
      fail(line, t.column, "glass", "glass table " + path->string() + ": " + e.message());
    }
  }
  const SpectralTable& table = it->second;
  return Glass::table(std::string(name), table.wavelengthsNm, table.values[0], nd);
}

LensSurface Parser::surface(int line, const std::vector<Token>& tokens) {
  if (tokens.size() < 4)
    fail(line, tokens.back().column, kColumns[tokens.size()],
         "a surface needs 4 columns (radius thickness N aperture, in mm); found " +
             std::to_string(tokens.size()));
  double v[4];
  for (int c = 0; c < 4; ++c) v[c] = number(line, tokens[c], kColumns[c]);
  LensSurface s;
  s.line = line;
  s.radius = v[0] * kMm;
  s.thickness = v[1] * kMm;
  s.apertureDiameter = v[3] * kMm;
  s.stop = v[2] == 0.0;
  if (v[1] < 0.0) fail(line, tokens[1].column, "thickness", "must be ≥ 0");
  if (!(v[3] > 0.0)) fail(line, tokens[3].column, "aperture", "the clear aperture must be > 0");
  if (s.stop && v[0] != 0.0)
    fail(line, tokens[0].column, "radius", "the aperture stop (N = 0) must have radius 0");
  if (!s.stop && !(v[2] >= 1.0 && v[2] <= 3.0))
    fail(line, tokens[2].column, "N", "the index must be 0 (the stop) or in [1, 3]");

  // The extension: key=value tokens.
  std::map<std::string, int, std::less<>> seen;
  const Token* glassToken = nullptr;
  const Token* abbeToken = nullptr;
  double abbe = 0.0;
  for (size_t i = 4; i < tokens.size(); ++i) {
    const Token& t = tokens[i];
    const size_t eq = t.text.find('=');
    if (eq == std::string_view::npos || eq == 0)
      fail(line, t.column, "",
           "'" + shortText(t.text) +
               "' after the 4 columns is no key=value (glass, abbe, conic, a4 … a16)");
    const std::string key(t.text.substr(0, eq));
    const std::string_view value = t.text.substr(eq + 1);
    if (!seen.emplace(key, t.column).second) fail(line, t.column, key, "given twice on one line");
    if (s.stop) fail(line, t.column, key, "the aperture stop takes no keys");
    if (key == "glass") {
      glassToken = &t;
    } else if (key == "abbe") {
      abbeToken = &t;
      abbe = number(line, {value, t.column}, key);
      if (!(abbe >= 5.0 && abbe <= 200.0)) fail(line, t.column, key, "V_d must be in [5, 200]");
    } else if (key == "conic") {
      s.conic = number(line, {value, t.column}, key);
    } else {
      int term = -1;
      for (int a = 0; a < kAsphereTerms; ++a)
        if (key == kAsphereKeys[a]) term = a;
      if (term < 0)
        fail(line, t.column, key, "unknown key (known: glass, abbe, conic, a4, a6, … a16)");
      // a_{2i} mm^(1−2i) → m^(1−2i): z = a r^{2i} with z, r in mm is 1000^(2i−1) a in m.
      const double converted =
          number(line, {value, t.column}, key) * std::pow(1e3, 2.0 * (term + 2) - 1.0);
      if (!std::isfinite(converted)) fail(line, t.column, key, "too large");
      s.asphere[term] = converted;
    }
  }
  if ((glassToken || abbeToken) && v[2] == 1.0)
    fail(line, (glassToken ? glassToken : abbeToken)->column, glassToken ? "glass" : "abbe",
         "air (N = 1) has no glass or dispersion");
  if (glassToken && abbeToken)
    fail(line, abbeToken->column, "abbe", "give either glass or abbe, not both");
  if (glassToken)
    s.medium = glass(line, *glassToken, glassToken->text.substr(6), v[2]);
  else if (abbeToken)
    s.medium = Glass::abbe(v[2], abbe);
  else if (!s.stop)
    s.medium = Glass::constant(v[2]);
  if (s.medium.disperses()) {  // the dispersion keeps n a glass's over the hero wavelengths
    const Token& t = glassToken ? *glassToken : *abbeToken;
    for (int lambda = 360; lambda <= 830; ++lambda)
      if (!(s.medium.index(lambda) >= 1.0 && s.medium.index(lambda) <= 4.0))
        fail(line, t.column, glassToken ? "glass" : "abbe",
             "with N = " + formatShortest(v[2]) + " the index leaves [1, 4] at " +
                 std::to_string(lambda) + " nm");
  }

  // The surface must exist over its clear aperture.
  const SurfaceShape shape = SurfaceShape::from(s, 0.0);
  if (!sagDefined(shape, shape.clearRadius2) || !std::isfinite(sag(shape, shape.clearRadius2)) ||
      !std::isfinite(sagSlopeOverR(shape, shape.clearRadius2))) {
    const bool conic = seen.count("conic") > 0;
    fail(line, conic ? seen.at("conic") : tokens[0].column, conic ? "conic" : "radius",
         "the surface does not reach its clear aperture (radius " + formatShortest(v[0]) +
             " mm, aperture " + formatShortest(v[3]) + " mm)");
  }
  return s;
}

}  // namespace

TableSearch defaultGlassSearch() {
  return TableSearch{{lutsDirectory() / "spectra"}, nullptr};
}

LensPrescription parseLensPrescription(std::string_view text, const std::string& sourceName,
                                       const TableSearch& glassSearch) {
  Parser parser(sourceName, glassSearch);
  LensPrescription lens;
  lens.source = sourceName;
  int lineNumber = 0;
  int lastLine = 0;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    start = end + 1;
    ++lineNumber;
    line = line.substr(0, line.find('#'));
    std::vector<Token> tokens;
    for (size_t i = 0; i < line.size();) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      const size_t from = i;
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      if (i > from) tokens.push_back({line.substr(from, i - from), static_cast<int>(from) + 1});
    }
    if (tokens.empty()) continue;
    if (lens.surfaces.size() == kMaxLensSurfaces)
      parser.fail(lineNumber, 1, "", "more than " + std::to_string(kMaxLensSurfaces) + " surfaces");
    LensSurface s = parser.surface(lineNumber, tokens);
    if (s.stop) {
      if (lens.stopIndex >= 0)
        parser.fail(lineNumber, tokens[2].column, "N",
                    "a second aperture stop (the first is on line " +
                        std::to_string(lens.surfaces[lens.stopIndex].line) + ")");
      lens.stopIndex = static_cast<int>(lens.surfaces.size());
      if (!lens.surfaces.empty()) s.medium = lens.surfaces.back().medium;
    }
    lens.surfaces.push_back(std::move(s));
    lastLine = lineNumber;
  }
  if (lens.surfaces.empty()) parser.fail(0, 0, "", "no surfaces");
  if (lens.stopIndex < 0) parser.fail(0, 0, "", "no aperture stop (a line with N = 0)");
  if (lens.surfaces.back().medium.nd() != 1.0)
    parser.fail(lastLine, 0, "N",
                "the last surface must have air (N = 1) behind it: the sensor is in air");
  return lens;
}

LensPrescription readLensPrescription(const std::filesystem::path& file,
                                      const TableSearch& glassSearch) {
  return parseLensPrescription(readInputFile(file, "lens file"), file.string(), glassSearch);
}

}  // namespace camsim
