#include "integrator/yaml_reader.h"

#include <charconv>
#include <cmath>

namespace camsim {

SourceLocation YamlValue::where() const {
  const YAML::Mark mark = node_.Mark();
  if (mark.line < 0) return {file_, 0, 0};
  return {file_, mark.line + 1, mark.column + 1};
}

void YamlValue::fail(const std::string& message) const { throw InputError(where(), key_, message); }

std::string YamlValue::string() const {
  if (!node_.IsScalar()) fail("expected a string");
  return node_.Scalar();
}

double YamlValue::number() const {
  if (!node_.IsScalar()) fail("expected a number");
  const std::string& s = node_.Scalar();
  double value = 0.0;
  const char* begin = s.data();
  if (!s.empty() && s.front() == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, s.data() + s.size(), value);
  if (ec != std::errc() || ptr != s.data() + s.size()) {
    if (s == ".nan" || s == ".NaN" || s == ".inf" || s == "-.inf" || s == ".Inf")
      fail("'" + s + "' is not a finite number");
    fail("'" + s + "' is not a number");
  }
  if (!std::isfinite(value)) fail("'" + s + "' is not a finite number");
  return value;
}

double YamlValue::number(double lo, double hi, bool loOpen) const {
  const double v = number();
  if (v < lo || v > hi || (loOpen && v == lo)) {
    fail("value " + node_.Scalar() + " is out of range " + (loOpen ? "(" : "[") + std::to_string(lo) +
         ", " + std::to_string(hi) + "]");
  }
  return v;
}

std::int64_t YamlValue::integer(std::int64_t lo, std::int64_t hi) const {
  if (!node_.IsScalar()) fail("expected an integer");
  const std::string& s = node_.Scalar();
  std::int64_t value = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec == std::errc::result_out_of_range) fail("integer " + s + " is out of range");
  if (ec != std::errc() || ptr != s.data() + s.size()) fail("'" + s + "' is not an integer");
  if (value < lo || value > hi)
    fail("value " + s + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return value;
}

bool YamlValue::boolean() const {
  if (node_.IsScalar()) {
    const std::string& s = node_.Scalar();
    if (s == "true" || s == "True" || s == "yes") return true;
    if (s == "false" || s == "False" || s == "no") return false;
  }
  fail("expected true or false");
}

std::vector<YamlValue> YamlValue::items() const {
  if (!node_.IsSequence()) fail("expected a list");
  std::vector<YamlValue> out;
  out.reserve(node_.size());
  for (size_t i = 0; i < node_.size(); ++i)
    out.emplace_back(node_[i], key_ + "[" + std::to_string(i) + "]", file_);
  return out;
}

std::vector<double> YamlValue::numbers() const {
  std::vector<double> out;
  for (const YamlValue& item : items()) out.push_back(item.number());
  return out;
}

glm::dvec3 YamlValue::vec3() const {
  if (!node_.IsSequence() || node_.size() != 3) fail("expected a list of 3 numbers [x, y, z]");
  const std::vector<double> v = numbers();
  return {v[0], v[1], v[2]};
}

YamlMap::YamlMap(const YamlValue& value) : self_(value) {
  if (!value.isMap()) value.fail("expected a mapping of keys to values");
}

std::string YamlMap::childKey(const std::string& name) const {
  return self_.key().empty() ? name : self_.key() + "." + name;
}

bool YamlMap::has(const std::string& name) const { return static_cast<bool>(self_.node()[name]); }

std::optional<YamlValue> YamlMap::find(const std::string& name) {
  const YAML::Node child = self_.node()[name];
  if (!child) return std::nullopt;
  used_.insert(name);
  return YamlValue(child, childKey(name), self_.file());
}

YamlValue YamlMap::require(const std::string& name) {
  std::optional<YamlValue> v = find(name);
  if (!v) throw InputError(self_.where(), childKey(name), "required key is missing");
  return *v;
}

std::vector<std::string> YamlMap::keys() const {
  std::vector<std::string> out;
  for (auto it = self_.node().begin(); it != self_.node().end(); ++it) out.push_back(it->first.Scalar());
  return out;
}

void YamlMap::finish(const std::vector<std::string>& known) const {
  for (auto it = self_.node().begin(); it != self_.node().end(); ++it) {
    const std::string name = it->first.Scalar();
    if (used_.count(name)) continue;
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    const YamlValue keyNode(it->first, childKey(name), self_.file());
    bool isKnown = false;
    for (const auto& k : known) isKnown = isKnown || k == name;
    keyNode.fail(isKnown ? "key is not allowed together with the keys given here"
                         : "unknown key (allowed here: " + list + ")");
  }
}

YamlValue parseYaml(const std::string& text, const std::string& file) {
  try {
    YAML::Node root = YAML::Load(text);
    return YamlValue(root, "", file);
  } catch (const YAML::Exception& e) {
    throw InputError({file, e.mark.line >= 0 ? e.mark.line + 1 : 0, e.mark.column >= 0 ? e.mark.column + 1 : 0},
                     "", "YAML syntax error: " + e.msg);
  }
}

}  // namespace camsim
