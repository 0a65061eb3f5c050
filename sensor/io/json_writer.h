// A minimal JSON writer for sidecar files: nested objects of strings, numbers, booleans
// and arrays of numbers or strings, written in insertion order.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "sensor/base/format.h"

namespace camsim {

class JsonObject {
 public:
  JsonObject& set(const std::string& key, const std::string& value) {
    return raw(key, quote(value));
  }
  JsonObject& set(const std::string& key, const char* value) { return raw(key, quote(value)); }
  JsonObject& set(const std::string& key, double value) { return raw(key, number(value)); }
  JsonObject& set(const std::string& key, bool value) { return raw(key, value ? "true" : "false"); }
  JsonObject& set(const std::string& key, const std::vector<double>& values) {
    return raw(key, array(values, number));
  }
  JsonObject& set(const std::string& key, const std::vector<std::string>& values) {
    std::string s = "[";
    for (size_t i = 0; i < values.size(); ++i) s += (i ? ", " : "") + quote(values[i]);
    return raw(key, s + "]");
  }
  JsonObject& set(const std::string& key, const JsonObject& object) {
    return raw(key, object.str());
  }
  JsonObject& set(const std::string& key, const std::vector<JsonObject>& objects) {
    std::string s = "[";
    for (size_t i = 0; i < objects.size(); ++i)
      s += (i ? ",\n  " : "\n  ") + indented(objects[i].str(), 2);
    return raw(key, s + (objects.empty() ? "]" : "\n]"));
  }
  // A matrix, row by row (rows of numbers).
  JsonObject& set(const std::string& key, const std::vector<std::vector<double>>& rows) {
    return raw(key, matrix(rows, number));
  }
  // Numbers in their shortest round-trip form (formatShortest), for values that must read
  // back as the same doubles — scene inputs, poses; set() keeps 10 significant digits.
  JsonObject& setExact(const std::string& key, double value) {
    return raw(key, exactNumber(value));
  }
  JsonObject& setExact(const std::string& key, const std::vector<double>& values) {
    return raw(key, array(values, exactNumber));
  }
  JsonObject& setExact(const std::string& key, const std::vector<std::vector<double>>& rows) {
    return raw(key, matrix(rows, exactNumber));
  }

  // An integer exactly (a 64-bit seed; set(key, double) keeps 10 significant digits).
  JsonObject& setInteger(const std::string& key, std::uint64_t value) {
    return raw(key, std::to_string(value));
  }
  // A value that is already JSON text (a number as written, a nested array).
  JsonObject& setJson(const std::string& key, std::string json) {
    return raw(key, std::move(json));
  }
  // A string as a JSON string literal.
  static std::string quoted(const std::string& s) { return quote(s); }
  // The object on one line (JSON Lines): the layout's newlines and indents dropped
  // (strings hold none: quote() escapes them).
  std::string line() const {
    const std::string text = str();
    std::string out;
    for (size_t i = 0; i < text.size(); ++i) {
      if (text[i] != '\n') {
        out += text[i];
        continue;
      }
      while (i + 1 < text.size() && text[i + 1] == ' ') ++i;
      if (!out.empty() && out.back() != '{' && out.back() != '[' && i + 1 < text.size() &&
          text[i + 1] != '}' && text[i + 1] != ']')
        out += ' ';
    }
    return out;
  }

  std::string str(int indent = 0) const {
    const std::string pad(static_cast<size_t>(indent + 2), ' ');
    std::string s = "{\n";
    for (size_t i = 0; i < fields_.size(); ++i) {
      std::string value = fields_[i].second;
      for (size_t p = value.find('\n'); p != std::string::npos; p = value.find('\n', p + 1))
        value.insert(p + 1, std::string(static_cast<size_t>(indent + 2), ' '));
      s += pad + quote(fields_[i].first) + ": " + value + (i + 1 < fields_.size() ? ",\n" : "\n");
    }
    return s + std::string(static_cast<size_t>(indent), ' ') + "}";
  }

 private:
  static std::string indented(std::string text, int by) {
    for (size_t p = text.find('\n'); p != std::string::npos; p = text.find('\n', p + 1))
      text.insert(p + 1, std::string(static_cast<size_t>(by), ' '));
    return text;
  }
  JsonObject& raw(const std::string& key, std::string value) {
    fields_.emplace_back(key, std::move(value));
    return *this;
  }
  static std::string number(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
  }
  static std::string exactNumber(double v) { return std::isfinite(v) ? formatShortest(v) : "null"; }
  // "[a, b, …]" and "[[…], […]]", each number by `format`. Appended piece by piece:
  // `(c ? ", " : "") + number(…)` made GCC 12 report a false -Wstringop-overflow when the
  // Python module's link inlines it (LTO).
  static std::string array(const std::vector<double>& values, std::string (*format)(double)) {
    std::string s = "[";
    for (size_t i = 0; i < values.size(); ++i) {
      if (i) s += ", ";
      s += format(values[i]);
    }
    return s + "]";
  }
  static std::string matrix(const std::vector<std::vector<double>>& rows,
                            std::string (*format)(double)) {
    std::string s = "[";
    for (size_t r = 0; r < rows.size(); ++r) {
      if (r) s += ", ";
      s += array(rows[r], format);
    }
    return s + "]";
  }
  // A control character as JSON's \u escape (a space before: Scene.from_dict turned a tab
  // in a name into a space, which the loader then took).
  static std::string hexEscape(unsigned char c) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "\\u%04x", c);
    return buf;
  }
  static std::string quote(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
      if (c == '"' || c == '\\')
        out += '\\', out += c;
      else if (c == '\n')
        out += "\\n";
      else if (static_cast<unsigned char>(c) < 0x20)  // kept: read back, a tab is a tab
        out += hexEscape(static_cast<unsigned char>(c));
      else
        out += c;
    }
    return out + "\"";
  }
  std::vector<std::pair<std::string, std::string>> fields_;
};

}  // namespace camsim
