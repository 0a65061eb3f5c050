#include "sensor/base/input_error.h"

namespace camsim {
namespace {

// `text` with its control bytes (C0 but tab and newline, and DEL) as \xNN: they come from the
// input (a NUL inside a lens-file number, a carriage return in a file name), and printed raw
// a NUL cut the line short and others would drive the user's terminal. UTF-8 passes.
std::string printable(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto b = static_cast<unsigned char>(c);
    if ((b < 0x20 && c != '\t' && c != '\n') || b == 0x7f) {
      constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[b >> 4];
      out += kHex[b & 15];
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

std::string formatInputError(const SourceLocation& where, const std::string& key,
                             const std::string& message) {
  std::string out = where.file.empty() ? std::string("<input>") : printable(where.file);
  if (where.line > 0) {
    out += ":" + std::to_string(where.line);
    if (where.column > 0) out += ":" + std::to_string(where.column);
  }
  out += ": ";
  if (!key.empty()) out += "key '" + printable(key) + "': ";
  out += printable(message);
  return out;
}

InputError namedBy(const InputError& inner, const SourceLocation& by, const std::string& key) {
  std::string named = by.file;
  if (by.line > 0) named += ":" + std::to_string(by.line) + ":" + std::to_string(by.column);
  return InputError(inner.where(), inner.key(),
                    inner.message() + " (in the file named by " + named + ", key '" + key + "')");
}

InputError inFile(const InputError& e, const std::string& file) {
  if (!e.where().file.empty()) return e;
  return InputError({file, 0, 0}, e.key(), e.message());
}

InputError::InputError(SourceLocation where, std::string key, std::string message)
    : std::runtime_error(formatInputError(where, key, message)),
      where_(std::move(where)),
      key_(std::move(key)),
      message_(std::move(message)) {}

}  // namespace camsim
