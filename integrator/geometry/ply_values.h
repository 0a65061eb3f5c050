// Internal to the PLY reader (ply_reader.cpp): the value types of a PLY header, its element
// and property descriptions, and the two value readers the body loop is written against —
// binary (either byte order) and ASCII (one element row per line). Not a public API.
#pragma once

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace camsim::ply_detail {

enum class Type : std::uint8_t { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat, kDouble };

struct Property {
  std::string name;
  Type type = Type::kFloat;  // scalar type, or the item type of a list
  bool isList = false;
  Type countType = Type::kUint8;
  int slot = -1;  // where the value goes (ply_reader.cpp's slots); -1 = skipped
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  int line = 0;  // header line declaring it
  std::vector<Property> properties;
};

struct TypeInfo {
  std::string_view name, alias;
  std::size_t size;
  std::int64_t min, max;  // integer types only
};
// Indexed by Type.
constexpr TypeInfo kTypes[] = {{"char", "int8", 1, INT8_MIN, INT8_MAX},
                               {"uchar", "uint8", 1, 0, UINT8_MAX},
                               {"short", "int16", 2, INT16_MIN, INT16_MAX},
                               {"ushort", "uint16", 2, 0, UINT16_MAX},
                               {"int", "int32", 4, INT32_MIN, INT32_MAX},
                               {"uint", "uint32", 4, 0, UINT32_MAX},
                               {"float", "float32", 4, 0, 0},
                               {"double", "float64", 8, 0, 0}};

inline const TypeInfo& info(Type t) {
  return kTypes[static_cast<std::size_t>(t)];
}
inline bool isInteger(Type t) {
  return t != Type::kFloat && t != Type::kDouble;
}

// Reader interface used by readBody: beginRow/endRow delimit a row, number/integer/skip/
// skipList consume values (false = missing, malformed or out of range for the type),
// line() is the current line (0 for binary), moreRows() reports leftover data.
class BinaryReader {
 public:
  BinaryReader(std::string_view body, bool bigEndian)
      : p_(body.data()),
        end_(body.data() + body.size()),
        swap_(bigEndian != (std::endian::native == std::endian::big)) {}

  bool beginRow() { return true; }
  bool endRow() { return true; }
  bool moreRows() { return false; }  // trailing bytes are ignored
  int line() const { return 0; }
  std::size_t bytesLeft() const { return static_cast<std::size_t>(end_ - p_); }
  static std::size_t minRowBytes(const Element& e) {
    std::size_t n = 0;
    for (const Property& p : e.properties) n += info(p.isList ? p.countType : p.type).size;
    return n;
  }

  bool number(Type t, double& out) { return read(t, out); }
  bool integer(Type t, std::int64_t& out) { return isInteger(t) && read(t, out); }
  bool skip(Type t) { return skipList(t, 1); }
  bool skipList(Type t, std::uint64_t n) {
    if (n > bytesLeft() / info(t).size) return false;
    p_ += n * info(t).size;
    return true;
  }

 private:
  template <class Out>
  bool read(Type t, Out& out) {
    // clang-format off
    switch (t) {
      case Type::kInt8: return load<std::int8_t>(out);
      case Type::kUint8: return load<std::uint8_t>(out);
      case Type::kInt16: return load<std::int16_t>(out);
      case Type::kUint16: return load<std::uint16_t>(out);
      case Type::kInt32: return load<std::int32_t>(out);
      case Type::kUint32: return load<std::uint32_t>(out);
      case Type::kFloat: return load<float>(out);
      case Type::kDouble: return load<double>(out);
    }
    // clang-format on
    return false;
  }

  template <class T, class Out>
  bool load(Out& out) {
    if (bytesLeft() < sizeof(T)) return false;
    unsigned char buf[sizeof(T)];
    std::memcpy(buf, p_, sizeof(T));
    if (swap_) std::reverse(buf, buf + sizeof(T));
    T v;
    std::memcpy(&v, buf, sizeof(T));
    p_ += sizeof(T);
    out = static_cast<Out>(v);
    return true;
  }

  const char* p_;
  const char* end_;
  bool swap_;
};

// One element row per line; blank lines are skipped.
class AsciiReader {
 public:
  AsciiReader(std::string_view body, int headerLines)
      : next_(body.data()), end_(body.data() + body.size()), line_(headerLines) {}

  bool beginRow() {  // moves to the next non-blank line
    while (next_ < end_) {
      const void* nl = std::memchr(next_, '\n', static_cast<std::size_t>(end_ - next_));
      cur_ = next_;
      lineEnd_ = nl != nullptr ? static_cast<const char*>(nl) : end_;
      next_ = nl != nullptr ? lineEnd_ + 1 : end_;
      if (line_ < std::numeric_limits<int>::max()) ++line_;
      skipSpace();
      if (cur_ != lineEnd_) return true;
    }
    return false;
  }
  bool endRow() {
    skipSpace();
    return cur_ == lineEnd_;
  }
  bool moreRows() { return beginRow(); }
  int line() const { return line_; }
  std::size_t bytesLeft() const { return static_cast<std::size_t>(end_ - next_) + 1; }
  // Each value takes at least one character and one separator.
  static std::size_t minRowBytes(const Element& e) { return 2 * e.properties.size(); }

  bool number(Type t, double& out) {
    if (isInteger(t)) {
      std::int64_t i = 0;
      const bool ok = integer(t, i);
      out = static_cast<double>(i);
      return ok;
    }
    const std::string_view tok = token();
    const char* first = tok.data();
    const char* last = first + tok.size();
    if (last - first > 1 && *first == '+' && first[1] != '-') ++first;
    auto [ptr, ec] = std::from_chars(first, last, out);
    if (ec == std::errc::result_out_of_range) {  // rare: let strtod decide (inf or tiny)
      out = std::strtod(std::string(first, last).c_str(), nullptr);
      ec = std::errc();
    }
    return !tok.empty() && ec == std::errc() && ptr == last;
  }
  bool integer(Type t, std::int64_t& out) {
    const std::string_view tok = token();
    auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
    if (tok.empty() || ec != std::errc() || ptr != tok.data() + tok.size()) return false;
    return isInteger(t) && out >= info(t).min && out <= info(t).max;
  }
  bool skip(Type t) {
    double d = 0.0;
    return number(t, d);
  }
  bool skipList(Type t, std::uint64_t n) {
    for (std::uint64_t i = 0; i < n; ++i)  // bounded: each value consumes a token of the line
      if (!skip(t)) return false;
    return true;
  }

 private:
  static bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
  }
  void skipSpace() {
    while (cur_ < lineEnd_ && isSpace(*cur_)) ++cur_;
  }
  std::string_view token() {
    skipSpace();
    const char* start = cur_;
    while (cur_ < lineEnd_ && !isSpace(*cur_)) ++cur_;
    return {start, static_cast<std::size_t>(cur_ - start)};
  }

  const char* next_;
  const char* end_;
  const char* cur_ = nullptr;
  const char* lineEnd_ = nullptr;
  int line_;
};

// One vertex index of a face or strip list, checked against the vertex count; a strip's
// restart marker (−1, or 4294967295 in a uint list) is returned as −1.
}  // namespace camsim::ply_detail
