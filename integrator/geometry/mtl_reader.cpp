// Wavefront .mtl reader (statements and fields: see mtl_reader.h). One pass over the lines;
// each statement is dispatched on its keyword, compared without regard to case.
#include "integrator/geometry/mtl_reader.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "integrator/geometry/mesh_io.h"
#include "sensor/base/input_error.h"
#include "sensor/base/input_file.h"

namespace camsim {

namespace {

constexpr std::size_t kMaxMaterials = 1'000'000;
constexpr std::size_t kMaxIgnored = 10'000'000;

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && isObjSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isObjSpace(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> words(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && isObjSpace(s[i])) ++i;
    const std::size_t start = i;
    while (i < s.size() && !isObjSpace(s[i])) ++i;
    if (i > start) out.push_back(s.substr(start, i - start));
  }
  return out;
}

bool isNumber(std::string_view w, double& v) {
  auto [ptr, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
  return !w.empty() && ec == std::errc() && ptr == w.data() + w.size() && std::isfinite(v);
}

// Why camsim ignores a statement (keys in lower case); nullptr: a statement it reads.
const char* ignoredReason(const std::string& key) {
  struct Entry {
    const char* key;
    const char* reason;
  };
  static constexpr Entry kReasons[] = {
      {"ka", "camsim has no ambient term"},
      {"map_ka", "camsim has no ambient term"},
      {"ke", "emission comes from the shape's 'emission:' in the scene file"},
      {"map_ke", "emission comes from the shape's 'emission:' in the scene file"},
      {"tf", "camsim's dielectric has no transmission filter colour"},
      {"map_bump", "camsim has no bump maps"},
      {"bump", "camsim has no bump maps"},
      {"disp", "camsim has no displacement maps"},
      {"decal", "camsim has no decal maps"},
      {"map_ks", "only Kd may be an image texture"},
      {"map_ns", "only Kd may be an image texture"},
      {"map_d", "only Kd may be an image texture (camsim has no cut-outs from .mtl files)"},
      {"map_tr", "only Kd may be an image texture (camsim has no cut-outs from .mtl files)"},
      {"map_aat", "camsim has no texture anti-aliasing switch"},
      {"refl", "reflection maps are not used (camsim traces reflections)"},
      {"sharpness", "reflection maps are not used (camsim traces reflections)"},
      {"norm", "normal maps from .mtl files are not read"},
  };
  for (const Entry& e : kReasons)
    if (key == e.key) return e.reason;
  static constexpr const char* kPbr[] = {"pr",    "pm",     "ps",     "pc",     "pcr",
                                         "aniso", "anisor", "map_pr", "map_pm", "map_ps"};
  for (const char* k : kPbr)
    if (key == k) return "the .mtl PBR extension is not read (import such assets as glTF)";
  return nullptr;
}

class MtlParser {
 public:
  MtlParser(std::string_view text, const std::string& source) : text_(text) {
    lib_.sourceName = source;
  }
  MtlLibrary run();

 private:
  void statement(std::string_view keyword, std::string_view rest);
  std::vector<double> numbers(std::string_view rest, std::size_t min, std::size_t max,
                              std::string_view key, double lo, double hi) const;
  glm::dvec3 colour(std::string_view rest, std::string_view key);
  MtlMaterial::TextureMap textureMap(std::string_view rest, std::string_view key);
  void ignore(std::string_view key, std::string reason);
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError({lib_.sourceName, line_, 0}, "", message);
  }

  std::string_view text_;
  MtlLibrary lib_;
  std::map<std::string, int> lineOf_;  // newmtl name → its line
  int line_ = 0;
};

MtlLibrary MtlParser::run() {
  std::size_t pos = 0;
  while (pos < text_.size()) {
    std::size_t nl = text_.find('\n', pos);
    if (nl == std::string_view::npos) nl = text_.size();
    const std::string_view line = trim(text_.substr(pos, nl - pos));
    pos = nl + 1;
    if (line_ < std::numeric_limits<int>::max()) ++line_;
    if (line.empty() || line.front() == '#') continue;
    std::size_t k = 0;
    while (k < line.size() && !isObjSpace(line[k])) ++k;
    statement(line.substr(0, k), trim(line.substr(k)));
  }
  return std::move(lib_);
}

void MtlParser::ignore(std::string_view key, std::string reason) {
  std::vector<MtlIgnored>& list =
      lib_.materials.empty() ? lib_.ignored : lib_.materials.back().ignored;
  if (list.size() >= kMaxIgnored) fail("more than 10000000 ignored statements");
  list.push_back({std::string(key), line_, std::move(reason)});
}

void MtlParser::statement(std::string_view keyword, std::string_view rest) {
  const std::string key = lower(keyword);
  if (key == "newmtl") {
    if (rest.empty()) fail("newmtl needs a material name");
    const auto [it, added] = lineOf_.try_emplace(std::string(rest), line_);
    if (!added)
      fail("material '" + std::string(rest) + "' is defined twice (first on line " +
           std::to_string(it->second) + ")");
    if (lib_.materials.size() >= kMaxMaterials) fail("more than 1000000 materials");
    lib_.materials.emplace_back();
    lib_.materials.back().name = std::string(rest);
    lib_.materials.back().line = line_;
    return;
  }
  const char* reason = ignoredReason(key);
  const bool known = key == "kd" || key == "ks" || key == "ns" || key == "ni" || key == "d" ||
                     key == "tr" || key == "illum" || key == "map_kd";
  if (!known || lib_.materials.empty()) {
    ignore(keyword, reason != nullptr ? reason
                    : known           ? "it comes before the first newmtl"
                                      : "not a statement camsim reads");
    return;
  }
  MtlMaterial& m = lib_.materials.back();
  if (key == "kd" || key == "ks") {
    const std::string_view first = rest.substr(0, rest.find_first_of(" \t"));
    if (first == "spectral" || first == "xyz") {
      ignore(std::string(keyword) + " " + std::string(first),
             "only RGB colours are read (the default applies)");
      return;
    }
    (key == "kd" ? m.kd : m.ks) = MtlMaterial::Field<glm::dvec3>{colour(rest, keyword), line_};
  } else if (key == "ns") {
    m.ns = {{numbers(rest, 1, 1, keyword, 0.0, 1e12)[0], line_}};
  } else if (key == "ni") {
    m.ni = {{numbers(rest, 1, 1, keyword, 1e-3, 1e3)[0], line_}};
  } else if (key == "d" || key == "tr") {
    const std::vector<std::string_view> w = words(rest);
    if (!w.empty() && w[0] == "-halo") ignore("d -halo", "camsim has no halo dissolve");
    const std::string_view value = !w.empty() && w[0] == "-halo" ? rest.substr(5) : rest;
    const double v = numbers(value, 1, 1, keyword, 0.0, 1.0)[0];
    m.dissolve = {{key == "d" ? v : 1.0 - v, line_}};
  } else if (key == "illum") {
    const double n = numbers(rest, 1, 1, keyword, 0.0, 10.0)[0];
    if (n != std::floor(n)) fail("illum must be an integer from 0 to 10");
    m.illum = {{static_cast<int>(n), line_}};
  } else {  // map_kd
    m.mapKd = textureMap(rest, keyword);
  }
}

// min..max numbers in [lo, hi]; a '#' ends the list.
std::vector<double> MtlParser::numbers(std::string_view rest, std::size_t min, std::size_t max,
                                       std::string_view key, double lo, double hi) const {
  const std::string range = lo == 1e-3   ? "0.001 to 1000"
                            : hi == 1.0  ? "0 to 1"
                            : hi == 10.0 ? "0 to 10"
                                         : ">= 0";
  std::vector<double> out;
  for (std::string_view w : words(rest.substr(0, rest.find('#')))) {
    double v = 0.0;
    if (!isNumber(w.size() > 1 && w[0] == '+' && w[1] != '-' ? w.substr(1) : w, v))
      fail("'" + std::string(w.substr(0, 40)) + "' is not a number (" + std::string(key) + ")");
    if (v < lo || v > hi)
      fail(std::string(key) + " value " + std::string(w.substr(0, 40)) + " is out of range (" +
           range + ")");
    if (out.size() == max)
      fail(std::string(key) + " takes " + std::to_string(max) + " value" + (max > 1 ? "s" : "") +
           ", more are given");
    out.push_back(v);
  }
  if (out.size() < min)
    fail(std::string(key) + " needs " + std::to_string(min) + " value" + (min > 1 ? "s" : ""));
  return out;
}

glm::dvec3 MtlParser::colour(std::string_view rest, std::string_view key) {
  const std::vector<double> c = numbers(rest, 1, 3, key, 0.0, 1e6);
  if (c.size() == 2) fail(std::string(key) + " takes 1 (grey) or 3 values (r g b)");
  return c.size() == 1 ? glm::dvec3(c[0]) : glm::dvec3(c[0], c[1], c[2]);
}

// map_Kd [options] FILE. -s and -o (u v [w]) are read; other options are skipped with their
// values (the known options' arity from the format; unknown ones: the numbers and on/off
// words that follow) and noted. The file name is the rest of the line, spaces included.
MtlMaterial::TextureMap MtlParser::textureMap(std::string_view rest, std::string_view key) {
  MtlMaterial::TextureMap t;
  t.line = line_;
  auto nextWord = [&rest] {
    const std::size_t e = std::min(rest.find_first_of(" \t"), rest.size());
    return rest.substr(0, e);
  };
  auto drop = [&rest](std::string_view word) { rest = trim(rest.substr(word.size())); };
  while (!rest.empty() && rest.front() == '-') {
    const std::string option = lower(nextWord());
    drop(nextWord());
    std::vector<double> values;
    const bool uvw = option == "-s" || option == "-o" || option == "-t";
    const bool oneWord = option == "-blendu" || option == "-blendv" || option == "-clamp" ||
                         option == "-cc" || option == "-bm" || option == "-boost" ||
                         option == "-texres" || option == "-imfchan" || option == "-type";
    const std::size_t most = uvw ? 3 : oneWord ? 1 : option == "-mm" ? 2 : 16;
    while (values.size() < most) {
      const std::string_view w = nextWord();
      if (w.size() == rest.size()) break;  // the last word is the file name
      double v = 0.0;
      const bool number = isNumber(w, v);
      if (!number && !oneWord && w != "on" && w != "off") break;
      values.push_back(number ? v : 0.0);
      drop(w);
    }
    if (option == "-s" || option == "-o") {
      if (values.size() < 2 || std::fabs(values[0]) > 1e30 || std::fabs(values[1]) > 1e30)
        fail(std::string(key) + " " + option + " needs u v [w], each within ±1e30");
      (option == "-s" ? t.scale : t.offset) = glm::dvec2(values[0], values[1]);
    } else {
      ignore(std::string(key) + " " + option, "texture map option not read");
    }
  }
  t.file = std::string(rest);
  if (t.file.empty()) fail(std::string(key) + " needs a file name");
  return t;
}

}  // namespace

MtlLibrary parseMtl(std::string_view text, const std::string& sourceName) {
  return MtlParser(text, sourceName).run();
}

MtlLibrary readMtl(const std::filesystem::path& path) {
  const std::string text = readInputFile(path, "material library");
  return parseMtl(text, path.string());
}

}  // namespace camsim
