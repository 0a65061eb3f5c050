// Internal to the glTF structural check (gltf_validate.cpp, gltf_validate_buffers.cpp): the
// JSON being checked and the helpers that name what is wrong by its JSON path. Only these
// two files include it (with nlohmann-json, which no other header exposes).
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "sensor/base/file_status.h"
#include "sensor/base/input_error.h"

namespace camsim::gltf_check {

using Json = nlohmann::json;

struct Checker {
  std::string file;
  std::filesystem::path baseDir;
  const Json& root;

  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    throw InputError({file, 0, 0}, path, message);
  }
  size_t count(const char* array) const {
    const auto it = root.find(array);
    if (it == root.end()) return 0;
    if (!it->is_array()) fail(array, "must be an array");
    return it->size();
  }
  // An integer in [lo, hi] at obj[key] (required or optional); returns fallback if absent.
  std::int64_t integer(const Json& obj, const std::string& path, const char* key, std::int64_t lo,
                       std::int64_t hi, bool required, std::int64_t fallback = 0) const {
    const auto it = obj.find(key);
    const std::string where = path + "." + key;
    if (it == obj.end()) {
      if (required) fail(where, "is missing");
      return fallback;
    }
    if (!it->is_number()) fail(where, "must be a number");
    const double v = it->get<double>();
    if (!(std::floor(v) == v) || !(v >= static_cast<double>(lo)) || !(v <= static_cast<double>(hi)))
      fail(where, "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                      "] (it is " + it->dump() + ")");
    return static_cast<std::int64_t>(v);
  }
  // A reference obj[key] into the top-level array `array`.
  std::int64_t index(const Json& obj, const std::string& path, const char* key, const char* array,
                     bool required) const {
    const size_t n = count(array);
    const auto it = obj.find(key);
    if (it == obj.end()) {
      if (required) fail(path + "." + key, "is missing");
      return -1;
    }
    if (n == 0) fail(path + "." + key, std::string("refers to ") + array + ", which is empty");
    return integer(obj, path, key, 0, static_cast<std::int64_t>(n) - 1, required);
  }
  const Json& item(const char* array, size_t i) const {
    const Json& v = root[array][i];
    if (!v.is_object())
      fail(std::string(array) + "[" + std::to_string(i) + "]", "must be an object");
    return v;
  }
  static std::string at(const char* array, size_t i) {
    return std::string(array) + "[" + std::to_string(i) + "]";
  }
  // The external file obj.uri names (it must exist); empty for none or a data URI.
  std::filesystem::path externalFile(const Json& obj, const std::string& path) const {
    const auto uri = obj.find("uri");
    if (uri == obj.end()) return {};
    if (!uri->is_string()) fail(path + ".uri", "must be a string");
    const std::string u = uri->get<std::string>();
    if (u.rfind("data:", 0) == 0) return {};
    std::string decoded;  // percent-encoding, as tinygltf decodes it
    for (size_t i = 0; i < u.size(); ++i) {
      if (u[i] == '%' && i + 2 < u.size() && std::isxdigit(static_cast<unsigned char>(u[i + 1])) &&
          std::isxdigit(static_cast<unsigned char>(u[i + 2]))) {
        decoded += static_cast<char>(std::stoi(u.substr(i + 1, 2), nullptr, 16));
        i += 2;
      } else {
        decoded += u[i];
      }
    }
    const std::filesystem::path p = baseDir / decoded;
    if (!isRegularFile(p)) fail(path + ".uri", "file '" + p.string() + "' not found");
    return p;
  }
};

inline size_t componentBytes(std::int64_t type) {
  switch (type) {
    case 5120:
    case 5121:
      return 1;
    case 5122:
    case 5123:
      return 2;
    case 5125:
    case 5126:
      return 4;
    default:
      return 0;
  }
}

inline const char* componentName(std::int64_t type) {
  switch (type) {
    case 5120:
      return "BYTE (5120)";
    case 5121:
      return "UNSIGNED_BYTE (5121)";
    case 5122:
      return "SHORT (5122)";
    case 5123:
      return "UNSIGNED_SHORT (5123)";
    case 5125:
      return "UNSIGNED_INT (5125)";
    default:
      return "FLOAT (5126)";
  }
}

inline size_t componentCount(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

// Buffers, buffer views and accessors: every extent inside its view and buffer, each
// buffer's data of its byteLength, strides that fit their elements, index accessors of
// unsigned integers.
void checkBuffers(const Checker& c, std::size_t glbBinBytes, bool isGlb);

}  // namespace camsim::gltf_check
