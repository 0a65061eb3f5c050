// YamlMap / YamlValue: checked access to a parsed YAML (or JSON) document with the
// location of every value, for error messages "file:line:col: key 'a.b[2].c': …".
// A YamlMap remembers which keys were read; finish() rejects any key nobody asked for,
// so typos are errors rather than silently ignored settings. Used by the scene loader
// (integrator/) and the sensor-description loader (sensor/).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>
#include <glm/vec3.hpp>

#include "sensor/base/input_error.h"

namespace camsim {

class YamlValue {
 public:
  YamlValue(YAML::Node node, std::string key, std::string file)
      : node_(std::move(node)), key_(std::move(key)), file_(std::move(file)), mark_(node_.Mark()) {}
  // `mark` overrides the node's own location (used for keys given without a value, whose
  // null node yaml-cpp places at the next token, often on a later line).
  YamlValue(YAML::Node node, std::string key, std::string file, YAML::Mark mark)
      : node_(std::move(node)), key_(std::move(key)), file_(std::move(file)), mark_(mark) {}

  const YAML::Node& node() const { return node_; }
  const std::string& key() const { return key_; }
  const std::string& file() const { return file_; }
  SourceLocation where() const;
  [[noreturn]] void fail(const std::string& message) const;

  bool isMap() const { return node_.IsMap(); }
  bool isSequence() const { return node_.IsSequence(); }
  bool isScalar() const { return node_.IsScalar(); }

  std::string string() const;
  double number() const;                                           // finite
  double number(double lo, double hi, bool loOpen = false) const;  // in [lo, hi] (or (lo, hi])
  std::int64_t integer(std::int64_t lo, std::int64_t hi) const;
  bool boolean() const;
  glm::dvec3 vec3() const;               // [x, y, z], finite
  std::vector<YamlValue> items() const;  // elements of a sequence
  std::vector<double> numbers() const;   // a sequence of finite numbers
  // The value as one of the named choices; otherwise fails with
  // "unknown WHAT 'value' (known: a, b, ...)".
  template <typename T>
  T choice(const std::string& what,
           std::initializer_list<std::pair<std::string_view, T>> choices) const {
    const std::string v = string();
    std::string known;
    for (const auto& [name, value] : choices) {
      if (name == v) return value;
      known += (known.empty() ? "" : ", ") + std::string(name);
    }
    fail("unknown " + what + " '" + v + "' (known: " + known + ")");
  }

 private:
  YAML::Node node_;
  std::string key_;
  std::string file_;
  YAML::Mark mark_;
};

class YamlMap {
 public:
  // Fails unless value is a mapping whose keys are distinct plain scalars.
  explicit YamlMap(const YamlValue& value);

  bool has(const std::string& name) const;
  std::optional<YamlValue> find(const std::string& name);  // marks the key as used
  YamlValue require(const std::string& name);              // error if missing
  std::vector<std::string> keys() const;
  const YamlValue& self() const { return self_; }
  // Rejects keys that were never read, naming the first one and listing the known ones.
  void finish(const std::vector<std::string>& known) const;

 private:
  std::string childKey(const std::string& name) const;
  YamlValue self_;
  std::set<std::string> used_;
};

// Parses YAML/JSON text holding one document; syntax errors become InputError with the
// location (for an unclosed '[' or '{': the bracket's location).
YamlValue parseYaml(const std::string& text, const std::string& file);

}  // namespace camsim
