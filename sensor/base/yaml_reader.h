// YamlMap / YamlValue: checked access to a parsed YAML (or JSON) document with the
// location of every value, for error messages "file:line:col: key 'a.b[2].c': …".
// A YamlMap remembers which keys were read; finish() rejects any key nobody asked for,
// so typos are errors rather than silently ignored settings. Used by the scene loader
// (integrator/) and the sensor-description loader (sensor/).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "sensor/base/enum_names.h"
#include "sensor/base/input_error.h"

// yaml-cpp stays in yaml_reader.cpp (and yaml_edit.cpp): its types are only declared here.
namespace YAML {
class Node;
struct Mark;
}  // namespace YAML

namespace camsim {

class YamlValue {
 public:
  YamlValue(const YAML::Node& node, std::string key, std::string file);
  // `mark` overrides the node's own location (used for keys given without a value, whose
  // null node yaml-cpp places at the next token, often on a later line).
  YamlValue(const YAML::Node& node, std::string key, std::string file, const YAML::Mark& mark);

  // The yaml-cpp node, for yaml_reader.cpp (the only file that sees its definition).
  const YAML::Node& node() const { return *node_; }
  bool isNull() const;  // no value: an empty document, a key given without one
  const std::string& key() const { return key_; }
  const std::string& file() const { return file_; }
  SourceLocation where() const;
  [[noreturn]] void fail(const std::string& message) const;
  // An error raised reading the file this value names (a table, a sensor, a mesh): one with
  // a line in that file keeps it and adds this file, line and key ("in the file named by
  // …"); one without becomes fail(its message).
  [[noreturn]] void failInNamedFile(const InputError& inner) const;

  bool isMap() const;
  bool isSequence() const;
  bool isScalar() const;

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
  // The same with the enum's own name table (sensor/base/enum_names.h): aliases read,
  // the message lists the canonical names.
  template <typename E>
  E choice(const std::string& what) const {
    const std::string v = string();
    if (const std::optional<E> e = enumFromName<E>(v)) return *e;
    fail("unknown " + what + " '" + v + "' (known: " + enumNameList<E>() + ")");
  }

 private:
  std::shared_ptr<const YAML::Node> node_;
  std::string key_;
  std::string file_;
  int line_ = -1, column_ = -1;  // 0-based, as yaml-cpp marks them; −1: unknown
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
